//! Runs `steps` steps of the aircraft IMM on the bench's fixed input
//! (`benches/benches/imm.rs`, `imm/aircraft_imm_2cv_ct_step`: the default tuning, a start
//! from two plots 5 s apart, one plot 5 s later) and prints a checksum, for instruction
//! counting, which does not depend on the machine's load:
//!
//! ```text
//! cargo build --release -p argus-imm --example aircraft_profile
//! valgrind --tool=callgrind target/release/examples/aircraft_profile step 20000
//! valgrind --tool=callgrind target/release/examples/aircraft_profile none 20000
//! ```
//!
//! `<which>` is `step` or `none` (set-up only, to subtract). Instructions per step =
//! (total − `none` total) / steps.
#![allow(clippy::unwrap_used, missing_docs)]

use std::hint::black_box;

use argus_core_math::Vector;
use argus_imm::{AircraftRadar, AircraftTuning};
use argus_sensors::RadarNoise;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let which = args.get(1).map_or("step", String::as_str);
    let steps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(20_000);
    let tuning = AircraftTuning::<2, 3>::default();
    let imm = tuning.build().unwrap();
    let radar = AircraftRadar::new(
        [0.0, 0.0],
        RadarNoise::constant(70.0, 0.08_f64.to_radians(), 0.0).unwrap(),
    )
    .unwrap();
    let polar = |x: f64, y: f64| Vector::<2>::new(x.hypot(y), y.atan2(x));
    let est = tuning
        .start(
            &radar,
            &polar(-60_000.0 - 450.0, -20_000.0),
            &polar(-60_000.0, -20_000.0),
            5.0,
        )
        .unwrap();
    let z = polar(-60_000.0 + 450.0, -20_000.0);
    let mut sum = 0.0;
    if which == "step" {
        for _ in 0..steps {
            let up = imm
                .step(black_box(&est), 5.0, &radar, black_box(&z))
                .unwrap();
            sum += up.log_likelihood;
        }
    }
    println!("{which} {steps}: checksum {sum:.6}");
}
