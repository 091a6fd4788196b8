//! Plot CSV files (see `docs/FORMATS.md`): reading with file/line/field errors, writing.

use std::path::Path;

use argus_sim::{Measurement, Origin, Plot};

use crate::error::CliError;

/// Every column a plot file may have.
const KNOWN: [&str; 16] = [
    "t",
    "sensor",
    "range",
    "azimuth",
    "elevation",
    "amplitude",
    "x",
    "y",
    "z",
    "r_xx",
    "r_xy",
    "r_yy",
    "r_xz",
    "r_yz",
    "r_zz",
    "origin",
];

/// A plot's value as read from a file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum FileValue {
    /// Range (m), azimuth (rad).
    Polar { range: f64, azimuth: f64 },
    /// Range (m), azimuth (rad), elevation (rad).
    Spherical {
        range: f64,
        azimuth: f64,
        elevation: f64,
    },
    /// Position (m) and covariance `[r_xx, r_xy, r_yy]` (m²).
    Cartesian { x: f64, y: f64, cov: [f64; 3] },
    /// 3-D position (m) and covariance `[r_xx, r_xy, r_xz, r_yy, r_yz, r_zz]` (m²).
    Cartesian3 { p: [f64; 3], cov: [f64; 6] },
}

impl FileValue {
    /// Spatial dimension of the plot: 2 or 3.
    pub(crate) fn dim(&self) -> usize {
        match self {
            Self::Polar { .. } | Self::Cartesian { .. } => 2,
            Self::Spherical { .. } | Self::Cartesian3 { .. } => 3,
        }
    }
}

/// One plot read from a file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FilePlot {
    /// 1-based line in the file.
    pub(crate) line: u64,
    pub(crate) time: f64,
    pub(crate) sensor: u32,
    pub(crate) value: FileValue,
}

/// Reads a plot file: header required, columns known, one layout (polar, spherical,
/// Cartesian 2-D or 3-D), numbers finite, ranges positive, covariances positive definite,
/// time non-decreasing.
///
/// # Errors
/// [`CliError::Input`] naming the file, line and field; [`CliError::Io`].
pub(crate) fn read(path: &Path) -> Result<Vec<FilePlot>, CliError> {
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(true)
        .flexible(false)
        .trim(csv::Trim::All)
        .from_path(path)
        .map_err(|e| csv_error(path, e))?;
    let headers = rdr.headers().map_err(|e| csv_error(path, e))?.clone();
    let cols: Vec<String> = headers.iter().map(str::to_owned).collect();
    for c in &cols {
        if !KNOWN.contains(&c.as_str()) {
            return Err(CliError::input(
                path,
                Some(1),
                Some(c),
                format!("unknown column (known: {})", KNOWN.join(", ")),
            ));
        }
    }
    let idx = |name: &str| cols.iter().position(|c| c == name);
    for name in ["t", "sensor"] {
        if idx(name).is_none() {
            return Err(CliError::input(
                path,
                Some(1),
                Some(name),
                "required column is missing",
            ));
        }
    }
    let polar = ["range", "azimuth", "elevation"]
        .iter()
        .any(|c| idx(c).is_some());
    let cart = [
        "x", "y", "z", "r_xx", "r_xy", "r_yy", "r_xz", "r_yz", "r_zz",
    ]
    .iter()
    .any(|c| idx(c).is_some());
    let three_d = ["elevation", "z", "r_xz", "r_yz", "r_zz"]
        .iter()
        .any(|c| idx(c).is_some());
    let need: &[&str] = match (polar, cart, three_d) {
        (true, false, false) => &["range", "azimuth"],
        (true, false, true) => &["range", "azimuth", "elevation"],
        (false, true, false) => &["x", "y", "r_xx", "r_xy", "r_yy"],
        (false, true, true) => &[
            "x", "y", "z", "r_xx", "r_xy", "r_xz", "r_yy", "r_yz", "r_zz",
        ],
        (true, true, _) => {
            return Err(CliError::input(
                path,
                Some(1),
                None,
                "a file holds either polar/spherical (range, azimuth[, elevation]) or Cartesian (x, y[, z]) plots, not both",
            ));
        }
        (false, false, _) => {
            return Err(CliError::input(
                path,
                Some(1),
                None,
                "no measurement columns: expected range,azimuth[,elevation] or x,y,r_xx,r_xy,r_yy (3-D: x,y,z,r_xx,r_xy,r_xz,r_yy,r_yz,r_zz)",
            ));
        }
    };
    for name in need {
        if idx(name).is_none() {
            return Err(CliError::input(
                path,
                Some(1),
                Some(name),
                "required column is missing",
            ));
        }
    }
    let mut out = Vec::new();
    let mut last_t = f64::NEG_INFINITY;
    for rec in rdr.records() {
        let rec = rec.map_err(|e| csv_error(path, e))?;
        let line = rec.position().map_or(0, csv::Position::line);
        let num = |name: &str| -> Result<f64, CliError> {
            let raw = idx(name).and_then(|i| rec.get(i)).unwrap_or("");
            let v: f64 = raw.parse().map_err(|_| {
                CliError::input(
                    path,
                    Some(line),
                    Some(name),
                    format!("'{raw}' is not a number"),
                )
            })?;
            if v.is_finite() {
                Ok(v)
            } else {
                Err(CliError::input(
                    path,
                    Some(line),
                    Some(name),
                    format!("'{raw}' is not finite"),
                ))
            }
        };
        let time = num("t")?;
        if time < last_t {
            return Err(CliError::input(
                path,
                Some(line),
                Some("t"),
                format!("time goes backwards ({time} after {last_t})"),
            ));
        }
        last_t = time;
        let raw_sensor = idx("sensor").and_then(|i| rec.get(i)).unwrap_or("");
        let sensor: u32 = raw_sensor.parse().map_err(|_| {
            CliError::input(
                path,
                Some(line),
                Some("sensor"),
                format!("'{raw_sensor}' is not a sensor id (a non-negative integer)"),
            )
        })?;
        // An empty amplitude field means the plot has none (a file may mix both).
        if idx("amplitude")
            .and_then(|i| rec.get(i))
            .is_some_and(|raw| !raw.trim().is_empty())
        {
            num("amplitude")?;
        }
        let value = if polar {
            let range = num("range")?;
            if range <= 0.0 {
                return Err(CliError::input(
                    path,
                    Some(line),
                    Some("range"),
                    format!("range {range} must be positive"),
                ));
            }
            let azimuth = num("azimuth")?;
            if three_d {
                let elevation = num("elevation")?;
                if elevation.abs() > std::f64::consts::FRAC_PI_2 {
                    return Err(CliError::input(
                        path,
                        Some(line),
                        Some("elevation"),
                        format!("elevation {elevation} rad lies outside [-π/2, π/2]"),
                    ));
                }
                FileValue::Spherical {
                    range,
                    azimuth,
                    elevation,
                }
            } else {
                FileValue::Polar { range, azimuth }
            }
        } else if three_d {
            let cov = [
                num("r_xx")?,
                num("r_xy")?,
                num("r_xz")?,
                num("r_yy")?,
                num("r_yz")?,
                num("r_zz")?,
            ];
            if !positive_definite_3(&cov) {
                return Err(CliError::input(
                    path,
                    Some(line),
                    Some("r_xx"),
                    "covariance [r_xx r_xy r_xz; r_xy r_yy r_yz; r_xz r_yz r_zz] is not positive definite",
                ));
            }
            FileValue::Cartesian3 {
                p: [num("x")?, num("y")?, num("z")?],
                cov,
            }
        } else {
            let cov = [num("r_xx")?, num("r_xy")?, num("r_yy")?];
            if cov[0] <= 0.0 || cov[2] <= 0.0 || cov[0] * cov[2] - cov[1] * cov[1] <= 0.0 {
                return Err(CliError::input(
                    path,
                    Some(line),
                    Some("r_xx"),
                    "covariance [r_xx r_xy; r_xy r_yy] is not positive definite",
                ));
            }
            FileValue::Cartesian {
                x: num("x")?,
                y: num("y")?,
                cov,
            }
        };
        out.push(FilePlot {
            line,
            time,
            sensor,
            value,
        });
    }
    Ok(out)
}

/// Whether the symmetric matrix with upper triangle `[xx, xy, xz, yy, yz, zz]` is
/// positive definite (Sylvester's criterion: leading principal minors positive).
fn positive_definite_3(c: &[f64; 6]) -> bool {
    let [xx, xy, xz, yy, yz, zz] = *c;
    let m2 = xx * yy - xy * xy;
    let det = xx * (yy * zz - yz * yz) - xy * (xy * zz - yz * xz) + xz * (xy * yz - yy * xz);
    xx > 0.0 && m2 > 0.0 && det > 0.0
}

fn csv_error(path: &Path, e: csv::Error) -> CliError {
    let line = e.position().map(csv::Position::line);
    let message = match e.kind() {
        csv::ErrorKind::UnequalLengths {
            expected_len, len, ..
        } => format!("malformed row: {len} fields where the header has {expected_len}"),
        csv::ErrorKind::Io(err) => {
            return CliError::io(path, std::io::Error::new(err.kind(), err.to_string()));
        }
        _ => format!("malformed CSV: {e}"),
    };
    CliError::input(path, line, None, message)
}

/// The layouts [`write_text`] can write, from the first plot's measurement.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Layout {
    Polar,
    Spherical,
    Cartesian2,
    Cartesian3,
}

/// Plot file text for simulated plots (the layout of the first plot: polar, spherical,
/// Cartesian 2-D or 3-D; plots of another layout are skipped and counted). Includes the
/// `origin` column (`target:<id>` or `clutter`) — `argus track` ignores it.
pub(crate) fn write_text(plots: &[Plot]) -> (String, usize) {
    let layout = match plots.first().map(|p| p.measurement) {
        Some(Measurement::Spherical { .. }) => Layout::Spherical,
        Some(Measurement::Cartesian2d { .. }) => Layout::Cartesian2,
        Some(Measurement::Cartesian3d { .. }) => Layout::Cartesian3,
        _ => Layout::Polar,
    };
    let amp = plots.iter().any(|p| p.amplitude.is_some());
    let mut s = String::from(match layout {
        Layout::Polar => "t,sensor,range,azimuth",
        Layout::Spherical => "t,sensor,range,azimuth,elevation",
        Layout::Cartesian2 => "t,sensor,x,y,r_xx,r_xy,r_yy",
        Layout::Cartesian3 => "t,sensor,x,y,z,r_xx,r_xy,r_xz,r_yy,r_yz,r_zz",
    });
    if amp {
        s.push_str(",amplitude");
    }
    s.push_str(",origin\n");
    let mut skipped = 0;
    for p in plots {
        let body = match (layout, p.measurement) {
            (Layout::Polar, Measurement::Polar { range, azimuth }) => format!("{range},{azimuth}"),
            (
                Layout::Spherical,
                Measurement::Spherical {
                    range,
                    azimuth,
                    elevation,
                },
            ) => format!("{range},{azimuth},{elevation}"),
            (Layout::Cartesian2, Measurement::Cartesian2d { position, cov }) => format!(
                "{},{},{},{},{}",
                position[0], position[1], cov[0], cov[1], cov[2]
            ),
            (Layout::Cartesian3, Measurement::Cartesian3d { position, cov }) => {
                let v: Vec<String> = position
                    .iter()
                    .chain(cov.iter())
                    .map(|x| format!("{x}"))
                    .collect();
                v.join(",")
            }
            _ => {
                skipped += 1;
                continue;
            }
        };
        s.push_str(&format!("{},{},{body}", p.time, p.sensor.0));
        if amp {
            // No NaN as a "missing" marker: a plot without amplitude leaves the field empty.
            match p.amplitude {
                Some(a) => s.push_str(&format!(",{a}")),
                None => s.push(','),
            }
        }
        match p.origin {
            Origin::Target(id) => s.push_str(&format!(",target:{}\n", id.0)),
            Origin::Clutter => s.push_str(",clutter\n"),
        }
    }
    (s, skipped)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Vec<FilePlot>, CliError> {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("p.csv");
        std::fs::write(&p, text).unwrap();
        read(&p)
    }

    fn at(e: &CliError) -> (Option<u64>, Option<String>) {
        match e {
            CliError::Input { at, .. } => (at.line, at.field.clone()),
            other => panic!("not an input error: {other}"),
        }
    }

    #[test]
    fn sylvester_criterion_on_hand_matrices() {
        // diag(1, 2, 3): minors 1, 2, 6 > 0.
        assert!(positive_definite_3(&[1.0, 0.0, 0.0, 2.0, 0.0, 3.0]));
        // [[2, 1, 0], [1, 2, 1], [0, 1, 2]]: minors 2, 3, det = 4 > 0.
        assert!(positive_definite_3(&[2.0, 1.0, 0.0, 2.0, 1.0, 2.0]));
        // [[1, 1, 1], [1, 1, 1], [1, 1, 1]] is singular (rank 1).
        assert!(!positive_definite_3(&[1.0, 1.0, 1.0, 1.0, 1.0, 1.0]));
        // [[1, 0, 2], [0, 1, 0], [2, 0, 1]]: det = 1 − 4 = −3 < 0 though the 2×2 minor is 1.
        assert!(!positive_definite_3(&[1.0, 0.0, 2.0, 1.0, 0.0, 1.0]));
    }

    #[test]
    fn layouts_are_recognised() {
        let p = parse("t,sensor,range,azimuth,elevation\n0,1,1000,0.1,0.2\n").unwrap();
        assert_eq!(
            p[0].value,
            FileValue::Spherical {
                range: 1000.0,
                azimuth: 0.1,
                elevation: 0.2
            }
        );
        assert_eq!(p[0].value.dim(), 3);
        // Columns in any order; the covariance keeps its upper-triangle order.
        // [[1, .2, .3], [.2, 4, 1], [.3, 1, 6]]: minors 1, 3.96, det 22.52 > 0.
        let p =
            parse("r_zz,r_yz,r_yy,r_xz,r_xy,r_xx,z,y,x,sensor,t\n6,1,4,0.3,0.2,1,3,2,1,4,0.5\n")
                .unwrap();
        assert_eq!(
            p[0].value,
            FileValue::Cartesian3 {
                p: [1.0, 2.0, 3.0],
                cov: [1.0, 0.2, 0.3, 4.0, 1.0, 6.0]
            }
        );
        // cov [[1, .2, .3], [.2, 4, 5], [.3, 5, 6]] has det < 0: rejected on line 2.
        let e = parse("t,sensor,x,y,z,r_xx,r_xy,r_xz,r_yy,r_yz,r_zz\n0,1,1,2,3,1,0.2,0.3,4,5,6\n")
            .unwrap_err();
        assert_eq!(at(&e), (Some(2), Some("r_xx".into())));
        assert_eq!(p[0].sensor, 4);
        assert_eq!(p[0].line, 2);
    }

    #[test]
    fn plots_without_amplitude_round_trip_beside_plots_with_one() {
        // A target plot with an amplitude and one without: the writer leaves the field
        // empty (never NaN) and the reader accepts the file.
        let mk = |t: f64, amplitude| Plot {
            time: t,
            sensor: argus_sim::SensorId(1),
            measurement: Measurement::Polar {
                range: 1000.0 + t,
                azimuth: 0.1,
            },
            amplitude,
            origin: Origin::Clutter,
        };
        let (text, skipped) = write_text(&[mk(0.0, Some(2.5)), mk(1.0, None)]);
        assert_eq!(skipped, 0);
        assert!(!text.contains("NaN"), "{text}");
        let p = parse(&text).unwrap();
        assert_eq!(p.len(), 2);
        // A non-numeric amplitude is still an error naming line and field.
        let e = parse("t,sensor,range,azimuth,amplitude\n0,1,1000,0.1,x\n").unwrap_err();
        assert_eq!(at(&e), (Some(2), Some("amplitude".into())));
    }

    #[test]
    fn bad_headers_and_values_name_line_and_field() {
        let e = parse("t,sensor,range,x\n").unwrap_err();
        assert_eq!(at(&e).0, Some(1));
        let e = parse("t,sensor,range,azimuth,elevation\n0,1,0,0.1,0.2\n").unwrap_err();
        assert_eq!(at(&e), (Some(2), Some("range".into())));
        let e = parse("t,sensor,range,azimuth\n0,1,5,0.1\n0,-1,5,0.1\n").unwrap_err();
        assert_eq!(at(&e), (Some(3), Some("sensor".into())));
        let e = parse("t,sensor,x,y,z,r_xx\n").unwrap_err();
        assert_eq!(at(&e), (Some(1), Some("r_xy".into())));
    }
}
