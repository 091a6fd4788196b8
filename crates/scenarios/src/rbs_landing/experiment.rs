//! The "rbs-landing" experiment of seed 003: a UAV on a constant-velocity glide
//! to the runway, tracked from converted radar-beacon plots by the conventional
//! decoupled filter (CDKF), the adaptive one (ADKF) and the coupled 6-state KF.
//!
//! Every parameter the paper leaves open is fixed in [`RbsLandingConfig::default`]
//! (SPEC section 003's default geometry): radar at the origin; runway along +x at
//! y = −100 m, touchdown at (0, −100, 0); start 6000 m ground distance before
//! touchdown at 314.4 m (3° glide), 35 m/s along the path; plots at 10 Hz to
//! touchdown; truth perturbed by white acceleration 0.05 m/s² per axis; Δr =
//! 149.9 m, 2° beamwidths, k_m = 1.6; SNR ∝ 1/R² calibrated so σr = 2.97 m at the
//! mean SNR at 3006 m (mid-approach), with a 3 dB (1σ) log-normal fluctuation per
//! plot. The degraded cases multiply every plot σ by 5 and 10; the filters always
//! assume the link-budget σ at the measured range (normal case, no fluctuation).
//!
//! A run is a pure function of its seed ([`simulate_run`]); runs are independent,
//! so a caller can run them in parallel and aggregate with `summary::McSummary::from_runs`.

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::GaussianFilter;
use argus_sensors::{Sigmas, SnrNoise};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

use argus_adaptive::{
    AdaptiveDecoupledFilter, AdaptiveError, AdaptiveRConfig, AdaptiveState, ConvertedPlot,
    CoupledCvFilter, DecoupledEstimate, DecoupledFilter, FrameHandling, REstimate, Warmup,
    beacon_plot, beacon_plot_of,
};

use argus_adaptive::check_positive as positive;

/// The filters run side by side on the same plots.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FilterKind {
    /// Conventional decoupled filter (assumed R).
    Cdkf,
    /// Adaptive decoupled filter with our start-up ([`Warmup::InnovationScale`]):
    /// `R` scaled from the innovations for the first L plots, then the paper's method.
    Adkf,
    /// Adaptive decoupled filter as printed (window L from the first plot, from the
    /// assumed `R`: [`Warmup::Constant`]).
    AdkfPaper,
    /// ADKF with a window growing 1…L (our warm-up variant).
    AdkfGrowing,
    /// ADKF with innovation-based samples during the first L plots.
    AdkfInnovation,
    /// The coupled 6-state KF with the assumed R (accuracy reference).
    Coupled,
}

impl FilterKind {
    /// All filters in output order.
    pub const ALL: [Self; 6] = [
        Self::Cdkf,
        Self::Adkf,
        Self::AdkfPaper,
        Self::AdkfGrowing,
        Self::AdkfInnovation,
        Self::Coupled,
    ];

    /// A short name for tables and file names.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Cdkf => "CDKF",
            Self::Adkf => "ADKF",
            Self::AdkfPaper => "ADKF-paper",
            Self::AdkfGrowing => "ADKF-grow",
            Self::AdkfInnovation => "ADKF-innov",
            Self::Coupled => "KF6",
        }
    }

    /// The index in [`FilterKind::ALL`].
    #[must_use]
    pub fn index(self) -> usize {
        match self {
            Self::Cdkf => 0,
            Self::Adkf => 1,
            Self::AdkfPaper => 2,
            Self::AdkfGrowing => 3,
            Self::AdkfInnovation => 4,
            Self::Coupled => 5,
        }
    }
}

/// The number of filters run side by side.
pub const FILTERS: usize = FilterKind::ALL.len();

/// The adaptive variants, in [`FilterKind`] order (index 0 = ADKF).
pub const ADAPTIVE: [FilterKind; 4] = [
    FilterKind::Adkf,
    FilterKind::AdkfPaper,
    FilterKind::AdkfGrowing,
    FilterKind::AdkfInnovation,
];

/// Every parameter of the experiment (see the module docs for the defaults and why).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RbsLandingConfig {
    /// Plot interval, s (10 Hz).
    pub dt: f64,
    /// Speed along the glide path, m/s.
    pub speed: f64,
    /// Glide-path angle, degrees.
    pub glide_deg: f64,
    /// Ground distance from the start to touchdown, m.
    pub ground_distance: f64,
    /// The runway's y coordinate (the radar is at the origin), m.
    pub runway_y: f64,
    /// White acceleration of the truth and the filters' `q`, m/s² per axis.
    pub accel_sd: f64,
    /// Range resolution Δr, m (1 µs pulse: 149.9 m).
    pub range_resolution: f64,
    /// Azimuth and elevation beamwidth, degrees.
    pub beamwidth_deg: f64,
    /// Monopulse slope `k_m`.
    pub monopulse_slope: f64,
    /// Range at which the normal-case σr is calibrated, m.
    pub reference_range: f64,
    /// Normal-case σr at the reference range, m (the paper's 2.97 m).
    pub reference_sigma_range: f64,
    /// Per-plot SNR fluctuation, dB (1σ).
    pub snr_fluctuation_db: f64,
    /// Initial position error σ per axis, m.
    pub init_pos_sd: f64,
    /// Initial velocity error σ per axis, m/s.
    pub init_vel_sd: f64,
    /// Moving-average window `L` of the ADKF.
    pub window: usize,
    /// Variance floor of `R̂`, m².
    pub r_floor: f64,
    /// How the decoupled filters carry the covariance between plot frames.
    pub frame_handling: FrameHandling,
}

impl Default for RbsLandingConfig {
    fn default() -> Self {
        Self {
            dt: 0.1,
            speed: 35.0,
            glide_deg: 3.0,
            ground_distance: 6000.0,
            runway_y: -100.0,
            accel_sd: 0.05,
            range_resolution: 149.9,
            beamwidth_deg: 2.0,
            monopulse_slope: 1.6,
            reference_range: 3006.0,
            reference_sigma_range: 2.97,
            snr_fluctuation_db: 3.0,
            init_pos_sd: 10.0,
            init_vel_sd: 5.0,
            window: 20,
            r_floor: 1e-6,
            frame_handling: FrameHandling::Rotate,
        }
    }
}

impl RbsLandingConfig {
    /// Checks every parameter.
    ///
    /// # Errors
    /// [`AdaptiveError::InvalidParameter`] / [`AdaptiveError::NonFinite`] naming the field.
    pub fn validate(&self) -> Result<(), AdaptiveError> {
        positive(self.dt, "dt")?;
        positive(self.speed, "speed")?;
        positive(self.glide_deg, "glide_deg")?;
        if self.glide_deg >= 90.0 {
            return Err(AdaptiveError::InvalidParameter {
                what: "glide_deg",
                value: self.glide_deg,
                reason: "must be below 90",
            });
        }
        positive(self.ground_distance, "ground_distance")?;
        argus_adaptive::check_finite(self.runway_y, "runway_y")?;
        positive(self.accel_sd, "accel_sd")?;
        positive(self.init_pos_sd, "init_pos_sd")?;
        positive(self.init_vel_sd, "init_vel_sd")?;
        argus_adaptive::check_finite(self.snr_fluctuation_db, "snr_fluctuation_db")?;
        if self.snr_fluctuation_db < 0.0 {
            return Err(AdaptiveError::InvalidParameter {
                what: "snr_fluctuation_db",
                value: self.snr_fluctuation_db,
                reason: "must not be negative",
            });
        }
        AdaptiveRConfig::new(self.window, self.r_floor, Warmup::Constant)?;
        self.noise_model()?;
        if self.steps() == 0 {
            return Err(AdaptiveError::InvalidParameter {
                what: "dt",
                value: self.dt,
                reason: "longer than the whole approach",
            });
        }
        Ok(())
    }

    /// The radar's SNR-driven noise (seed 003 eqs 6–8): a 1/R² link calibrated so
    /// that `σr` = `reference_sigma_range` at the mean SNR at `reference_range`.
    ///
    /// # Errors
    /// [`AdaptiveError::Sensor`] for a parameter that is not finite and positive.
    pub fn noise_model(&self) -> Result<SnrNoise, AdaptiveError> {
        let bw = self.beamwidth_deg.to_radians();
        let link = SnrNoise::link_for_range_sigma(
            self.range_resolution,
            self.reference_sigma_range,
            self.reference_range,
        )?;
        Ok(SnrNoise::new(
            self.range_resolution,
            bw,
            bw,
            self.monopulse_slope,
            link,
        )?)
    }

    /// Time from the start to touchdown, s.
    #[must_use]
    pub fn duration(&self) -> f64 {
        self.ground_distance / self.glide_deg.to_radians().cos() / self.speed
    }

    /// Number of plots (at `k·dt`, `k = 1…n`, up to touchdown).
    #[must_use]
    pub fn steps(&self) -> usize {
        let n = (self.duration() / self.dt + 1e-9).floor();
        if n.is_finite() && n > 0.0 {
            n as usize
        } else {
            0
        }
    }

    /// The nominal initial truth `[x, vx, y, vy, z, vz]`.
    #[must_use]
    pub fn initial_truth(&self) -> Vector<6> {
        let g = self.glide_deg.to_radians();
        Vector::<6>::new(
            -self.ground_distance,
            self.speed * g.cos(),
            self.runway_y,
            0.0,
            self.ground_distance * g.tan(),
            -self.speed * g.sin(),
        )
    }
}

/// What one Monte Carlo run records per plot (index `k` is time `(k+1)·dt`); the
/// scenario's per-run record (one per case) of a split campaign.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RunSeries {
    /// Position error (estimate − truth) per filter, per step, per axis.
    pub pos_err: [Vec<[f64; 3]>; FILTERS],
    /// NEES (6 states) per filter, per step.
    pub nees: [Vec<f64>; FILTERS],
    /// `R̂` diagonal (x, y, z variances) per adaptive filter ([`ADAPTIVE`] order), per step.
    pub r_hat_diag: [Vec<[f64; 3]>; 4],
    /// The diagonal of the true Cartesian noise covariance of each plot.
    pub r_true_diag: Vec<[f64; 3]>,
    /// The diagonal of the Cartesian noise covariance the filters assume.
    pub r_assumed_diag: Vec<[f64; 3]>,
    /// CDKF only: per aligned axis, the run mean of `diag(Dᵀ(εεᵀ ± H P⁺ Hᵀ)D) / r̄_true`
    /// for the corrected (`+`, index 0) and printed (`−`, index 1) sign of eq (28).
    pub sample_ratio: [[f64; 3]; 2],
}

/// The per-axis standard normal draws.
fn normal3<R: Rng + ?Sized>(rng: &mut R) -> Vector<3> {
    Vector::<3>::new(
        StandardNormal.sample(rng),
        StandardNormal.sample(rng),
        StandardNormal.sample(rng),
    )
}

fn diag3(m: &Matrix<3, 3>) -> [f64; 3] {
    [m[(0, 0)], m[(1, 1)], m[(2, 2)]]
}

fn pos_of(x: &Vector<6>) -> Vector<3> {
    Vector::<3>::new(x[0], x[2], x[4])
}

/// One Monte Carlo run of the case whose plot noise is `noise_scale` × normal.
///
/// # Errors
/// [`AdaptiveError`] for an invalid configuration or a filter step that fails
/// (reported with the step, never hidden).
#[allow(clippy::too_many_lines)]
pub fn simulate_run(
    config: &RbsLandingConfig,
    noise_scale: f64,
    seed: u64,
) -> Result<RunSeries, AdaptiveError> {
    config.validate()?;
    positive(noise_scale, "noise scale")?;
    let model = config.noise_model()?;
    let n = config.steps();
    let dt = config.dt;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);

    let mut truth = config.initial_truth();
    let init_sd = Vector::<6>::new(
        config.init_pos_sd,
        config.init_vel_sd,
        config.init_pos_sd,
        config.init_vel_sd,
        config.init_pos_sd,
        config.init_vel_sd,
    );
    let mut x0 = truth;
    for i in 0..6 {
        let d: f64 = StandardNormal.sample(&mut rng);
        x0[i] += init_sd[i] * d;
    }
    let p0 = Matrix::<6, 6>::from_diagonal(&init_sd.component_mul(&init_sd));
    let g0 = Gaussian::new(x0, p0)?;
    let sph0 = beacon_plot_of(&pos_of(&x0))?;
    let frame0 = argus_adaptive::aligned_frame(sph0.azimuth(), sph0.elevation());
    let r0 = ConvertedPlot::from_spherical(&sph0, &model.sigmas_at_range(sph0.range()))?
        .cartesian_noise();

    let cdkf = DecoupledFilter::new(config.accel_sd, config.frame_handling)?;
    let warmups = [
        Warmup::InnovationScale,
        Warmup::Constant,
        Warmup::Growing,
        Warmup::Innovation {
            steps: config.window,
        },
    ];
    let make = |w: Warmup| -> Result<AdaptiveDecoupledFilter, AdaptiveError> {
        Ok(AdaptiveDecoupledFilter::new(
            cdkf,
            AdaptiveRConfig::new(config.window, config.r_floor, w)?,
        ))
    };
    let adkfs = [
        make(warmups[0])?,
        make(warmups[1])?,
        make(warmups[2])?,
        make(warmups[3])?,
    ];
    let kf = CoupledCvFilter::new(config.accel_sd)?;

    let dec0 = DecoupledEstimate::from_gaussian(&g0, &frame0)?;
    let mut cd_state = dec0;
    let ad0 = AdaptiveState {
        estimate: dec0,
        r: REstimate::new(r0)?,
    };
    let mut ad_states = [ad0; 4];
    let mut kf_state = g0;

    let mut out = RunSeries {
        pos_err: std::array::from_fn(|_| Vec::with_capacity(n)),
        nees: std::array::from_fn(|_| Vec::with_capacity(n)),
        r_hat_diag: std::array::from_fn(|_| Vec::with_capacity(n)),
        r_true_diag: Vec::with_capacity(n),
        r_assumed_diag: Vec::with_capacity(n),
        sample_ratio: [[0.0; 3]; 2],
    };
    let q = config.accel_sd;
    let fluct = config.snr_fluctuation_db;
    for _ in 0..n {
        // Truth: x ← F x + G w, w ~ N(0, q² I₃) (eq 14).
        let w = normal3(&mut rng) * q;
        for i in 0..3 {
            truth[2 * i] += dt * truth[2 * i + 1] + 0.5 * dt * dt * w[i];
            truth[2 * i + 1] += dt * w[i];
        }
        // Plot: the SNR of this plot fluctuates around the link budget.
        let true_sph = beacon_plot_of(&pos_of(&truth))?;
        let unit: f64 = StandardNormal.sample(&mut rng);
        let snr_db_offset = fluct * unit;
        let snr = model.link().snr_at(true_sph.range()) * 10f64.powf(snr_db_offset / 10.0);
        let s1 = model.sigmas_at_snr(snr)?;
        let s = Sigmas::new(
            s1.range() * noise_scale,
            s1.azimuth() * noise_scale,
            s1.elevation() * noise_scale,
        )?;
        let e = normal3(&mut rng);
        let meas = beacon_plot(
            (true_sph.range() + s.range() * e[0]).max(1e-3),
            true_sph.azimuth() + s.azimuth() * e[1],
            true_sph.elevation() + s.elevation() * e[2],
        )?;
        let assumed = model.sigmas_at_range(meas.range());
        let plot = ConvertedPlot::from_spherical(&meas, &assumed)?;
        let true_plot = ConvertedPlot::from_spherical(&true_sph, &s)?;
        out.r_true_diag.push(diag3(&true_plot.cartesian_noise()));
        out.r_assumed_diag.push(diag3(&plot.cartesian_noise()));

        // CDKF.
        let (post, _) = cdkf.update(&cdkf.predict(&cd_state, dt)?, &plot)?;
        cd_state = post;
        let eps = plot.position() - post.position();
        let hph = post.position_cov();
        let d = plot.frame();
        let ee = d.transpose() * (eps * eps.transpose()) * d;
        let pp = d.transpose() * hph * d;
        let r_true_aligned = d.transpose() * true_plot.cartesian_noise() * d;
        for k in 0..3 {
            out.sample_ratio[0][k] += (ee[(k, k)] + pp[(k, k)]) / r_true_aligned[(k, k)];
            out.sample_ratio[1][k] += (ee[(k, k)] - pp[(k, k)]) / r_true_aligned[(k, k)];
        }
        // ADKFs.
        for (j, (f, st)) in adkfs.iter().zip(ad_states.iter_mut()).enumerate() {
            let (post, _) = f.update(&f.predict(st, dt)?, &plot)?;
            *st = post;
            out.r_hat_diag[j].push(diag3(post.r.r_hat()));
        }
        // Coupled KF.
        let (post, _) = kf.update(&kf.predict(&kf_state, dt)?, &plot, plot.position())?;
        kf_state = post;

        let mut record = |kind: FilterKind, mean: &Vector<6>, nees: f64| {
            let e = pos_of(mean) - pos_of(&truth);
            out.pos_err[kind.index()].push([e[0], e[1], e[2]]);
            out.nees[kind.index()].push(nees);
        };
        record(FilterKind::Cdkf, cd_state.mean(), cd_state.nees(&truth));
        for (kind, st) in ADAPTIVE.iter().zip(&ad_states) {
            record(*kind, st.estimate.mean(), st.estimate.nees(&truth));
        }
        record(
            FilterKind::Coupled,
            kf_state.mean(),
            kf_state.mahalanobis_sq(&truth),
        );
    }
    for row in &mut out.sample_ratio {
        for v in row.iter_mut() {
            *v /= n as f64;
        }
    }
    Ok(out)
}
