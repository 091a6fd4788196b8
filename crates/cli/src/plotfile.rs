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
    /// Position (m) and covariance `[r_xx, r_xy, r_yy]` (m²).
    Cartesian { x: f64, y: f64, cov: [f64; 3] },
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

/// Reads a plot file: header required, columns known, numbers finite, time
/// non-decreasing. 3-D columns (`elevation`, `z`) are recognised and rejected for now.
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
    for name in ["elevation", "z", "r_xz", "r_yz", "r_zz"] {
        if idx(name).is_some() {
            return Err(CliError::input(
                path,
                Some(1),
                Some(name),
                "3-D plots are not supported by `argus track` yet (2-D polar or Cartesian only)",
            ));
        }
    }
    let polar = idx("range").is_some() || idx("azimuth").is_some();
    let cart = idx("x").is_some() || idx("y").is_some();
    let need: &[&str] = match (polar, cart) {
        (true, false) => &["range", "azimuth"],
        (false, true) => &["x", "y", "r_xx", "r_xy", "r_yy"],
        (true, true) => {
            return Err(CliError::input(
                path,
                Some(1),
                None,
                "a file holds either polar (range, azimuth) or Cartesian (x, y) plots, not both",
            ));
        }
        (false, false) => {
            return Err(CliError::input(
                path,
                Some(1),
                None,
                "no measurement columns: expected range,azimuth or x,y,r_xx,r_xy,r_yy",
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
        if idx("amplitude").is_some() {
            num("amplitude")?;
        }
        let value = if polar {
            let range = num("range")?;
            if range < 0.0 {
                return Err(CliError::input(
                    path,
                    Some(line),
                    Some("range"),
                    "negative range",
                ));
            }
            FileValue::Polar {
                range,
                azimuth: num("azimuth")?,
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

/// Plot file text for simulated plots of 2-D polar or Cartesian sensors (the layout of
/// the first plot; others are skipped with a count returned). Includes the `origin`
/// column (`target:<id>` or `clutter`) — `argus track` ignores it.
pub(crate) fn write_text(plots: &[Plot]) -> (String, usize) {
    let polar = matches!(
        plots.first().map(|p| p.measurement),
        Some(Measurement::Polar { .. }) | None
    );
    let amp = plots.iter().any(|p| p.amplitude.is_some());
    let mut s = String::from(if polar {
        "t,sensor,range,azimuth"
    } else {
        "t,sensor,x,y,r_xx,r_xy,r_yy"
    });
    if amp {
        s.push_str(",amplitude");
    }
    s.push_str(",origin\n");
    let mut skipped = 0;
    for p in plots {
        let body = match (polar, p.measurement) {
            (true, Measurement::Polar { range, azimuth }) => format!("{range},{azimuth}"),
            (false, Measurement::Cartesian2d { position, cov }) => format!(
                "{},{},{},{},{}",
                position[0], position[1], cov[0], cov[1], cov[2]
            ),
            _ => {
                skipped += 1;
                continue;
            }
        };
        s.push_str(&format!("{},{},{body}", p.time, p.sensor.0));
        if amp {
            s.push_str(&format!(",{}", p.amplitude.unwrap_or(f64::NAN)));
        }
        match p.origin {
            Origin::Target(id) => s.push_str(&format!(",target:{}\n", id.0)),
            Origin::Clutter => s.push_str(",clutter\n"),
        }
    }
    (s, skipped)
}
