//! CPU time per filter step (predict + update), measured from the thread's own
//! scheduler run time (`/proc/thread-self/schedstat`, Linux), so that the number
//! stays meaningful on a loaded machine where criterion's wall-clock medians
//! include time spent waiting for a core.
//!
//! Run: `cargo run --release -p argus-filters --example step_timing`.
//!
//! With arguments `<filter> <steps>` (filter one of `kf-joseph`, `kf-standard`,
//! `ekf-joseph`, `ekf-standard`, `ukf`) it only runs that many steps of one filter and
//! prints a checksum, for instruction counting, which does not depend on the machine's
//! load: `valgrind --tool=callgrind target/release/examples/step_timing kf-joseph 20000`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{CovarianceForm, Ekf, FilterError, GaussianFilter, Kf, Ukf, UtParams};
use argus_motion_models::Cv2D;
use argus_sensors::{CartesianPosition, MeasurementModel, Polar2D, RadarNoise};

/// The thread's on-CPU time in nanoseconds (first field of schedstat).
fn cpu_ns() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    s.split_whitespace().next()?.parse().ok()
}

fn prior() -> Result<Gaussian<4>, Box<dyn std::error::Error>> {
    #[rustfmt::skip]
    let p = Matrix::<4, 4>::new(
        900.0, 60.0, 100.0, 0.0,
        60.0, 100.0, 0.0, 5.0,
        100.0, 0.0, 900.0, 60.0,
        0.0, 5.0, 60.0, 100.0,
    );
    Ok(Gaussian::new(
        Vector::<4>::new(20_000.0, -100.0, 10_000.0, 50.0),
        p,
    )?)
}

fn step<F: GaussianFilter<4>, Me: MeasurementModel<4, 2>>(
    f: &F,
    est: &Gaussian<4>,
    meas: &Me,
    z: &Vector<2>,
) -> Result<Gaussian<4>, FilterError> {
    let pred = f.predict(est, 2.0)?;
    Ok(f.update(&pred, meas, z)?.0)
}

/// Median over 15 batches of the CPU time per step, ns.
fn time(
    mut one: impl FnMut() -> Result<Gaussian<4>, FilterError>,
) -> Result<f64, Box<dyn std::error::Error>> {
    const BATCH: u32 = 200_000;
    let mut per = Vec::new();
    for _ in 0..15 {
        let t0 = cpu_ns().ok_or("no schedstat")?;
        for _ in 0..BATCH {
            black_box(one()?);
        }
        let t1 = cpu_ns().ok_or("no schedstat")?;
        per.push((t1 - t0) as f64 / f64::from(BATCH));
    }
    per.sort_by(f64::total_cmp);
    Ok(per[per.len() / 2])
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let cv = Cv2D::discrete(0.5)?;
    let est = prior()?;
    let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::new(400.0, 50.0, 50.0, 300.0))?;
    let z_pos = Vector::<2>::new(19_810.0, 10_095.0);
    let polar = Polar2D::cv([0.0, 0.0], RadarNoise::constant(30.0, 0.01, 0.0)?)?;
    let z_polar = polar.predict(&Vector::<4>::new(19_810.0, -100.0, 10_095.0, 50.0));
    let mut args = std::env::args().skip(1);
    if let Some(which) = args.next() {
        let n: u32 = args.next().map_or(Ok(100_000), |s| s.parse())?;
        let (e, zp, zq) = (&est, &z_pos, &z_polar);
        let one = |which: &str| -> Result<Gaussian<4>, Box<dyn std::error::Error>> {
            let (kj, ks) = (Kf::new(cv), Kf::with_form(cv, CovarianceForm::Standard));
            let (ej, es) = (Ekf::new(cv), Ekf::with_form(cv, CovarianceForm::Standard));
            Ok(match which {
                "kf-joseph" => step(&kj, black_box(e), &pos, black_box(zp))?,
                "kf-standard" => step(&ks, black_box(e), &pos, black_box(zp))?,
                "ekf-joseph" => step(&ej, black_box(e), &polar, black_box(zq))?,
                "ekf-standard" => step(&es, black_box(e), &polar, black_box(zq))?,
                "ukf" => step(
                    &Ukf::new(cv, UtParams::default())?,
                    black_box(e),
                    &polar,
                    zq,
                )?,
                other => return Err(format!("unknown filter {other}").into()),
            })
        };
        let mut sum = 0.0;
        for _ in 0..n {
            sum += one(&which)?.mean()[0];
        }
        println!("{which}: {n} steps, checksum {sum:.6e}");
        return Ok(());
    }
    for form in [CovarianceForm::Joseph, CovarianceForm::Standard] {
        let kf = Kf::with_form(cv, form);
        let ekf = Ekf::with_form(cv, form);
        let t = time(|| step(&kf, black_box(&est), &pos, black_box(&z_pos)))?;
        println!("kf_step_pos2/{form:?}: {t:.0} ns CPU");
        let t = time(|| step(&ekf, black_box(&est), &polar, black_box(&z_polar)))?;
        println!("ekf_step_polar/{form:?}: {t:.0} ns CPU");
    }
    let ukf = Ukf::new(cv, UtParams::default())?;
    let t = time(|| step(&ukf, black_box(&est), &polar, black_box(&z_polar)))?;
    println!("ukf_step_polar/default: {t:.0} ns CPU");
    Ok(())
}
