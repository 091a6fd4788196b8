//! A fixed number of filter steps, for instruction counting:
//! `valgrind --tool=callgrind target/release/examples/step_profile kf-joseph 100000`
//! (instruction counts do not depend on the machine's load, unlike timings).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{CovarianceForm, Ekf, GaussianFilter, Kf, Ukf, UtParams};
use argus_motion_models::Cv2D;
use argus_sensors::{CartesianPosition, MeasurementModel, Polar2D, RadarNoise};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let which = args.next().unwrap_or_else(|| "kf-joseph".into());
    let n: u32 = args.next().map_or(Ok(100_000), |s| s.parse())?;
    #[rustfmt::skip]
    let p = Matrix::<4, 4>::new(
        900.0, 60.0, 100.0, 0.0,
        60.0, 100.0, 0.0, 5.0,
        100.0, 0.0, 900.0, 60.0,
        0.0, 5.0, 60.0, 100.0,
    );
    let est = Gaussian::new(Vector::<4>::new(20_000.0, -100.0, 10_000.0, 50.0), p)?;
    let cv = Cv2D::discrete(0.5)?;
    let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::new(400.0, 50.0, 50.0, 300.0))?;
    let z_pos = Vector::<2>::new(19_810.0, 10_095.0);
    let polar = Polar2D::cv([0.0, 0.0], RadarNoise::constant(30.0, 0.01, 0.0)?)?;
    let z_polar = polar.predict(&Vector::<4>::new(19_810.0, -100.0, 10_095.0, 50.0));
    let mut sum = 0.0;
    for _ in 0..n {
        let e = black_box(&est);
        let out = match which.as_str() {
            "kf-joseph" => {
                let f = Kf::with_form(cv, CovarianceForm::Joseph);
                f.update(&f.predict(e, 2.0)?, &pos, black_box(&z_pos))?.0
            }
            "kf-standard" => {
                let f = Kf::with_form(cv, CovarianceForm::Standard);
                f.update(&f.predict(e, 2.0)?, &pos, black_box(&z_pos))?.0
            }
            "ekf-joseph" => {
                let f = Ekf::with_form(cv, CovarianceForm::Joseph);
                f.update(&f.predict(e, 2.0)?, &polar, black_box(&z_polar))?
                    .0
            }
            "ekf-standard" => {
                let f = Ekf::with_form(cv, CovarianceForm::Standard);
                f.update(&f.predict(e, 2.0)?, &polar, black_box(&z_polar))?
                    .0
            }
            "ukf" => {
                let f = Ukf::new(cv, UtParams::default())?;
                f.update(&f.predict(e, 2.0)?, &polar, black_box(&z_polar))?
                    .0
            }
            other => return Err(format!("unknown filter {other}").into()),
        };
        sum += out.mean()[0];
    }
    println!("{which}: {n} steps, checksum {sum:.6e}");
    Ok(())
}
