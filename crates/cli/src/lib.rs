//! The `argus` command as a library: the command line ([`run_command_line`], called by
//! the `argus` binary) and the `argus track` job on files ([`track_files`], the job of
//! [`argus_io::track`]) with the command's error type ([`CliError`]). File formats:
//! `docs/FORMATS.md`.
//!
//! The `argus track` configuration is read and checked by `argus_config` (its
//! [`Location`] re-exported here), the plot, ASTERIX and tracks files read and written
//! by `argus_io`, whose [`argus_io::track`] runs the job (estimators, the tracker's
//! session); this crate holds the commands, summaries, figures and the progress bar.
//! Their errors become a
//! [`CliError`] of the same text (`From<argus_config::ConfigError>`,
//! `From<argus_io::IoError>`).
//!
//! Errors are printed once (`error: <file>:<line>: field '<f>': <what>`) and the process
//! exits with code 2; nothing a user feeds in panics.

/// `println!` for the command's messages. A closed standard output (`argus run … | head`)
/// is not a failure of the run — its files are still written, atomically — so a write
/// error there is ignored instead of panicking as `println!` does.
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}

mod campaign_plan;
mod campaign_scan;
mod convert;
mod error;
mod merge_error;
mod progress;
mod render;
mod runs_file;
mod score;
mod shard;
mod summary;
mod track;

pub use crate::error::CliError;
pub use crate::merge_error::MergeError;
pub use crate::track::{Smoothing, run as track_files};
pub use argus_config::Location;

use std::io::IsTerminal;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use argus_filters::Lag;
use argus_scenarios::{Params, Scenario};

use crate::progress::Bar;
use crate::summary::{RunInfo, table_text};
use argus_io::asterix::encode::{self, Container, Sweep};
use argus_io::output::write_atomic;
use argus_io::plotfile;

/// Radar target tracking: reproduce the seed papers' experiments, simulate plots, track.
#[derive(Debug, Parser)]
#[command(name = "argus", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Lists the scenarios, one line each.
    Scenarios,
    /// Runs a scenario's Monte Carlo campaign: table on stdout, files in --out.
    Run {
        /// Scenario name (see `argus scenarios`).
        scenario: String,
        /// Number of runs `N` (runs 0..N) or a range `A..B` of run indices.
        #[arg(long)]
        runs: Option<String>,
        /// Base seed.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Output directory (default `out/<scenario>`).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Parameter override `key=value` (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Cut the runs into this many shards and compute only `--shard` (one task of a
        /// cluster job array; `argus merge` then checks that every shard is there).
        #[arg(long, requires = "shard")]
        shards: Option<u64>,
        /// The shard to compute, `0..shards` (e.g. `$SLURM_ARRAY_TASK_ID`).
        #[arg(long, requires = "shards")]
        shard: Option<u64>,
    },
    /// Writes the job files of a campaign for a cluster: a Slurm job array and its
    /// dependent merge job, a Kubernetes Indexed Job and its merge Job (docs/cluster.md).
    Campaign {
        #[command(subcommand)]
        action: CampaignAction,
    },
    /// Merges split campaigns (`argus run --runs A..B` into several directories):
    /// recomputes the report from the union of their per-run files.
    Merge {
        /// Scenario name.
        scenario: String,
        /// Output directories of `argus run` (each holds `runs/<A>-<B>.jsonl`).
        #[arg(required = true)]
        dirs: Vec<PathBuf>,
        /// Output directory for the merged report and per-run file.
        #[arg(long)]
        out: PathBuf,
    },
    /// Writes one run's plots (and truth) of a scenario as CSV, or as ASTERIX CAT048 +
    /// CAT034 (`--format asterix`, or an output ending `.pcap` or `.ast`).
    Simulate {
        /// Scenario name.
        scenario: String,
        /// Base seed.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Run index (the plots of run `R` of a campaign with this seed).
        #[arg(long, default_value_t = 0)]
        run: u64,
        /// Plot file to write.
        #[arg(long)]
        out: PathBuf,
        /// Truth file to write (default: `<out stem>.truth.csv` beside the plots).
        #[arg(long)]
        truth: Option<PathBuf>,
        /// Parameter override `key=value` (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Plot file format: `csv`, or `asterix` (a pcap capture of CAT048 reports and,
        /// for a rotating radar, CAT034 north markers and sector crossings; raw blocks
        /// when the output ends `.ast`). Default: by the output's extension.
        #[arg(long, value_enum)]
        format: Option<PlotFormat>,
        /// ASTERIX: the radar's revolution period (s) for the CAT034 messages (default:
        /// the scenario's `period` parameter when it has `period` and `north_time`).
        #[arg(long, value_parser = positive_seconds)]
        revolution_period: Option<f64>,
        /// ASTERIX: sector crossings per revolution (the north marker is one).
        #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=256))]
        sectors: u32,
    },
    /// Converts between ASTERIX (pcap, pcapng or raw blocks, known by content) and the
    /// CSV layouts (docs/FORMATS.md): CAT048 (+ CAT034) ↔ polar plot CSV, CAT062 ↔ tracks
    /// CSV.
    Convert {
        /// Input file (format by content).
        input: PathBuf,
        /// Output file (format by extension: `.csv`, `.pcap`, `.ast`).
        output: PathBuf,
        /// CSV → ASTERIX: revolution period (s) of the radar, for CAT034 messages.
        #[arg(long, value_parser = positive_seconds)]
        revolution_period: Option<f64>,
        /// CSV → ASTERIX: a time the beam points north (s).
        #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
        north_time: f64,
        /// CSV → ASTERIX: sector crossings per revolution.
        #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=256))]
        sectors: u32,
    },
    /// Runs a configured estimator over a plot file, in time order.
    Track {
        /// Estimator and sensor configuration (TOML).
        #[arg(long)]
        config: PathBuf,
        /// Plot file: CSV, or ASTERIX CAT048 (+ CAT034) as pcap, pcapng or raw blocks
        /// (known by content).
        #[arg(long)]
        plots: PathBuf,
        /// Track file to write (CSV).
        #[arg(long)]
        out: PathBuf,
        /// Also write each track smoothed over its whole life (fixed-interval RTS / IMM
        /// smoother): the `xs, vxs, …` columns.
        #[arg(long, conflicts_with_all = ["smooth_lag", "smooth_lag_seconds"])]
        smooth: bool,
        /// Fixed-lag smoothing: each estimate smoothed with the next N steps (N ≥ 1).
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..),
              conflicts_with = "smooth_lag_seconds")]
        smooth_lag: Option<u64>,
        /// Fixed-lag smoothing: each estimate smoothed with the steps of the next S
        /// seconds (S > 0).
        #[arg(long, value_name = "S", value_parser = positive_seconds, allow_negative_numbers = true)]
        smooth_lag_seconds: Option<f64>,
    },
    /// Scores a tracks CSV (confirmed rows) against a truth CSV: completeness, breaks,
    /// swaps, spurious time, RMSE, GOSPA (docs/scoring.md); the score as JSON in --out.
    Score {
        /// Tracks file (the tracks CSV of `argus track`, or another tracker's in its columns).
        #[arg(long)]
        tracks: PathBuf,
        /// Truth file (`t,target,x,vx,y,vy`, as `argus simulate` writes it).
        #[arg(long)]
        truth: PathBuf,
        /// Score file to write (JSON).
        #[arg(long)]
        out: PathBuf,
        /// Grid step (s).
        #[arg(long, default_value_t = 5.0)]
        step: f64,
        /// Assignment cut-off distance (m).
        #[arg(long, default_value_t = 1000.0)]
        cutoff: f64,
    },
}

/// `argus simulate --format`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum PlotFormat {
    /// The plot CSV.
    Csv,
    /// ASTERIX CAT048 + CAT034.
    Asterix,
}

#[derive(Debug, Subcommand)]
enum CampaignAction {
    /// Writes the job files (Slurm batch scripts, Kubernetes manifests) into --out.
    Plan {
        /// Scenario name.
        scenario: String,
        /// Number of runs `N` (runs 0..N) or a range `A..B` of run indices.
        #[arg(long)]
        runs: String,
        /// Number of shards (array tasks / completions).
        #[arg(long)]
        shards: u64,
        /// Base seed.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Parameter override `key=value` (repeatable), passed to every shard.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Directory for the job files.
        #[arg(long)]
        out: PathBuf,
        /// Shared directory the shards write to and the merge reads (default: `<out>/shards`,
        /// made absolute).
        #[arg(long)]
        shared: Option<PathBuf>,
        /// The `argus` the jobs run (default: this executable's path).
        #[arg(long)]
        argus: Option<String>,
        /// Container image of the Kubernetes jobs.
        #[arg(long, default_value = "argus:latest")]
        image: String,
    },
}

/// Parses `--smooth-lag-seconds`: a finite number of seconds above 0.
fn positive_seconds(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        Ok(v) => Err(format!("{v} is not a positive, finite number of seconds")),
        Err(_) => Err(format!("{s:?} is not a number of seconds")),
    }
}

/// Parses `N` (= `0..N`) or `A..B`.
fn parse_runs(s: &str) -> Result<Range<u64>, CliError> {
    let bad = || CliError::Usage(format!("--runs {s}: expected N or A..B with A < B"));
    let r = if let Some((a, b)) = s.split_once("..") {
        a.trim().parse().map_err(|_| bad())?..b.trim().parse().map_err(|_| bad())?
    } else {
        0..s.trim().parse().map_err(|_| bad())?
    };
    if r.is_empty() { Err(bad()) } else { Ok(r) }
}

fn find(name: &str) -> Result<Box<dyn Scenario>, CliError> {
    Ok(argus_scenarios::find(name)?)
}

fn execute(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Scenarios => {
            for s in argus_scenarios::list() {
                say!(
                    "{:<16} {} (default {} runs)",
                    s.name,
                    s.description,
                    s.default_runs
                );
            }
        }
        Command::Run {
            scenario,
            runs,
            seed,
            out,
            set,
            shards,
            shard,
        } => {
            let sc = find(&scenario)?;
            let campaign = match runs {
                Some(r) => parse_runs(&r)?,
                None => 0..sc.default_runs(),
            };
            let (runs, shard) = match (shards, shard) {
                (Some(count), Some(index)) => (
                    shard::shard_range(&campaign, count, index)?,
                    Some(runs_file::ShardInfo {
                        index,
                        count,
                        campaign: [campaign.start, campaign.end],
                    }),
                ),
                _ => (campaign, None),
            };
            let params = Params::from_settings(&sc.params(), &set)?;
            let out = out.unwrap_or_else(|| PathBuf::from("out").join(sc.name()));
            let bar = Bar::new(runs.end - runs.start, std::io::stderr().is_terminal());
            let run = argus_scenarios::run(sc.as_ref(), runs.clone(), seed, params.clone(), &bar)?;
            let report = run.report;
            let runs_text = match &run.records {
                Some(records) => {
                    let header = runs_file::Header::new(sc.name(), seed, &runs, &params, shard);
                    Some(runs_file::runs_text(&header, records)?)
                }
                None => None,
            };
            let mut extra = Vec::new();
            if let Some(text) = runs_text {
                let path = runs_file::runs_file(&out, &runs);
                write_atomic(&path, text.as_bytes())?;
                extra.push(path.display().to_string());
            }
            let info = RunInfo {
                scenario: sc.name(),
                seed,
                runs: runs.clone(),
                params: params.as_map(),
                extra_files: &extra,
            };
            let mut files = summary::write(&report, &out, &info)?;
            files.extend(extra.iter().cloned());
            let of = shard.map_or_else(String::new, |s| {
                format!(
                    " (shard {} of {} of runs {}..{})",
                    s.index, s.count, s.campaign[0], s.campaign[1]
                )
            });
            say!(
                "argus run {} --seed {seed} --runs {}..{}{of}",
                sc.name(),
                runs.start,
                runs.end
            );
            say!("{}", table_text(&report).trim_end_matches('\n'));
            for f in files {
                say!("wrote {f}");
            }
        }
        Command::Merge {
            scenario,
            dirs,
            out,
        } => {
            let sc = find(&scenario)?;
            if sc.splittable().is_none() {
                return Err(argus_scenarios::ScenarioError::NotSplittable {
                    scenario: sc.name(),
                }
                .into());
            }
            let same = |a: &PathBuf| match (std::fs::canonicalize(a), std::fs::canonicalize(&out)) {
                (Ok(x), Ok(y)) => x == y,
                _ => false,
            };
            if let Some(d) = dirs.iter().find(|d| same(d)) {
                return Err(CliError::Usage(format!(
                    "--out {} is one of the merged directories: choose another",
                    d.display()
                )));
            }
            // The whole campaign is checked before anything is reduced; then the records
            // are streamed, file after file, to the reduce step and to the merged file.
            let m = campaign_scan::scan(sc.name(), &sc.params(), &dirs)?;
            let report = argus_scenarios::merge(
                sc.as_ref(),
                &m.params,
                m.runs.end - m.runs.start,
                &mut campaign_scan::records(&m.files),
            )?;
            let header = runs_file::Header::new(sc.name(), m.seed, &m.runs, &m.params, None);
            let path = runs_file::runs_file(&out, &m.runs);
            runs_file::write_streamed(&path, &header, &mut campaign_scan::lines(&m.files))?;
            let extra = vec![path.display().to_string()];
            let info = RunInfo {
                scenario: sc.name(),
                seed: m.seed,
                runs: m.runs.clone(),
                params: m.params.as_map(),
                extra_files: &extra,
            };
            let mut files = summary::write(&report, &out, &info)?;
            files.extend(extra.iter().cloned());
            say!(
                "argus merge {} --seed {} --runs {}..{} ({} files)",
                sc.name(),
                m.seed,
                m.runs.start,
                m.runs.end,
                m.files.len()
            );
            say!("{}", table_text(&report).trim_end_matches('\n'));
            for f in files {
                say!("wrote {f}");
            }
        }
        Command::Simulate {
            scenario,
            seed,
            run,
            out,
            truth,
            set,
            format,
            revolution_period,
            sectors,
        } => {
            let sc = find(&scenario)?;
            let params = Params::from_settings(&sc.params(), &set)?;
            let truth_path = truth.unwrap_or_else(|| out.with_extension("truth.csv"));
            let container = match (format, Container::of(&out)) {
                (Some(PlotFormat::Csv), _) | (None, None) => None,
                (_, Some(c)) => Some(c),
                (Some(PlotFormat::Asterix), None) => Some(Container::Pcap),
            };
            let asterix = container.map(|c| (c, sweep(&params, revolution_period, sectors)));
            if let Some(sim) = sc.simulated(&params, seed, run) {
                let sim = sim?;
                write_plot_file(&out, &sim.plots, asterix)?;
                let mut t_text = String::from("t,target,x,vx,y,vy\n");
                for r in &sim.truth {
                    t_text.push_str(&format!(
                        "{},{},{},{},{},{}\n",
                        r.t, r.target, r.x, r.vx, r.y, r.vy
                    ));
                }
                write_atomic(&truth_path, t_text.as_bytes())?;
                say!(
                    "wrote {} ({} plots) and {}",
                    out.display(),
                    sim.plots.len(),
                    truth_path.display()
                );
                return Ok(());
            }
            let (scene, sensors) = sc.scene(&params)?;
            let plots =
                argus_sim::generate_plots(&scene, &sensors, &mut argus_sim::run_rng(seed, run))?;
            write_plot_file(&out, &plots, asterix)?;
            // Truth at every plot time of each target, in the papers' 2-D order.
            let mut t_text = String::from("t,target,x,vx,y,vy,z,vz\n");
            let mut times: Vec<f64> = plots.iter().map(|p| p.plot.time()).collect();
            times.dedup_by(|a, b| a.to_bits() == b.to_bits());
            for t in times {
                for (id, tr) in scene.targets() {
                    if let Ok(s) = tr.state_at(t) {
                        t_text.push_str(&format!(
                            "{t},{},{},{},{},{},{},{}\n",
                            id.0,
                            s.position.x,
                            s.velocity.x,
                            s.position.y,
                            s.velocity.y,
                            s.position.z,
                            s.velocity.z
                        ));
                    }
                }
            }
            write_atomic(&truth_path, t_text.as_bytes())?;
            say!(
                "wrote {} ({} plots) and {}",
                out.display(),
                plots.len(),
                truth_path.display()
            );
        }
        Command::Campaign {
            action:
                CampaignAction::Plan {
                    scenario,
                    runs,
                    shards,
                    seed,
                    set,
                    out,
                    shared,
                    argus,
                    image,
                },
        } => {
            let sc = find(&scenario)?;
            let runs = parse_runs(&runs)?;
            // Checked here, so that no job of the campaign fails on a bad setting.
            Params::from_settings(&sc.params(), &set)?;
            let argus = match argus {
                Some(a) => a,
                None => std::env::current_exe()
                    .map_err(|e| CliError::io(std::path::Path::new("argus"), e))?
                    .display()
                    .to_string(),
            };
            let shared = shared.unwrap_or_else(|| out.join("shards"));
            let shared = std::path::absolute(&shared).map_err(|e| CliError::io(&shared, e))?;
            let plan = campaign_plan::Plan {
                scenario: sc.name(),
                runs,
                shards,
                seed,
                settings: &set,
                shared: &shared,
                argus: &argus,
                image: &image,
            };
            for line in campaign_plan::write(&plan, &out)? {
                say!("{line}");
            }
        }
        Command::Track {
            config,
            plots,
            out,
            smooth,
            smooth_lag,
            smooth_lag_seconds,
        } => {
            let smoothing = match (smooth, smooth_lag, smooth_lag_seconds) {
                (true, _, _) => Some(Smoothing::Interval),
                (false, Some(n), _) => Some(Smoothing::Lag(Lag::Steps(
                    usize::try_from(n)
                        .map_err(|_| CliError::Usage(format!("--smooth-lag {n}: too large")))?,
                ))),
                (false, None, Some(s)) => Some(Smoothing::Lag(Lag::Seconds(s))),
                (false, None, None) => None,
            };
            let (n, summary) = track::run(&config, &plots, &out, smoothing)?;
            if let Some(path) = summary {
                say!("wrote {}", path.display());
            }
            say!("wrote {} ({n} track points)", out.display());
        }
        Command::Convert {
            input,
            output,
            revolution_period,
            north_time,
            sectors,
        } => {
            let sweep = revolution_period.map(|period| Sweep {
                period,
                north_time,
                clockwise: true,
                sectors,
            });
            for line in convert::run(&input, &output, sweep)? {
                say!("{line}");
            }
        }
        Command::Score {
            tracks,
            truth,
            out,
            step,
            cutoff,
        } => {
            for line in score::run(&tracks, &truth, &out, step, cutoff)? {
                say!("{line}");
            }
            say!("wrote {}", out.display());
        }
    }
    Ok(())
}

/// Parses the command line and runs the command: exit code 0, or 2 after printing the error.
#[must_use]
pub fn run_command_line() -> ExitCode {
    let cli = Cli::parse();
    match execute(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// Writes `plots` as one plot file at `out` (atomically): CSV, or with `asterix` as
/// CAT048 (+ CAT034 with a sweep) in that container.
///
/// # Errors
/// [`CliError::Usage`] when plots of different layouts would share the file, or a plot
/// ASTERIX cannot carry; [`CliError::Io`].
fn write_plot_file(
    out: &Path,
    plots: &[argus_sim::LabelledPlot],
    asterix: Option<(Container, Option<Sweep>)>,
) -> Result<(), CliError> {
    if let Some((container, sweep)) = asterix {
        let plain: Vec<argus_sensors::Plot> = plots.iter().map(|p| p.plot).collect();
        let enc = encode::encode_plots(&plain, sweep.as_ref())?;
        return Ok(encode::write(out, &enc, container)?);
    }
    let (text, skipped) = plotfile::write_text(plots);
    if skipped > 0 {
        return Err(CliError::Usage(format!(
            "{skipped} plots of another layout cannot share one file"
        )));
    }
    Ok(write_atomic(out, text.as_bytes())?)
}

/// The sweep of a scenario's radar for `argus simulate`: `--revolution-period` when
/// given, else the scenario's `period` parameter when it also has `north_time` (the
/// rotating radar of real-traffic), `clockwise` ≥ 0.5 (default) north → east. `None`
/// (no CAT034) for a scenario without a rotating radar.
fn sweep(params: &Params, revolution_period: Option<f64>, sectors: u32) -> Option<Sweep> {
    let m = params.as_map();
    let period = revolution_period.or_else(|| m.get("north_time").and(m.get("period").copied()))?;
    Some(Sweep {
        period,
        north_time: m.get("north_time").copied().unwrap_or(0.0),
        clockwise: m.get("clockwise").is_none_or(|c| *c >= 0.5),
        sectors,
    })
}
