//! Plot CSV files (see `docs/FORMATS.md`): one codec, reading and writing the same
//! columns through one column schema (`Layout`); reading names file, line and field in
//! every error.

use std::path::Path;

use argus_core_math::{Matrix, Vector};
// A cell of a plot table: a CSV field's text (empty when the column is absent), or a
// value of a column (`from_columns`).
use argus_score::Cell;
use argus_sensors::{
    CartesianMeasurement, Measurement, Plot, PolarMeasurement, SensorId, SphericalMeasurement,
};
use argus_sim::{LabelledPlot, Origin};

use crate::error::IoError;

/// The columns of every plot file, before the measurement's.
const TIME: &str = "t";
const SENSOR: &str = "sensor";
/// Optional columns after the measurement's.
const AMPLITUDE: &str = "amplitude";
const ORIGIN: &str = "origin";

/// Every column a plot file may have.
const KNOWN: [&str; 16] = [
    TIME,
    SENSOR,
    "range",
    "azimuth",
    "elevation",
    AMPLITUDE,
    "x",
    "y",
    "z",
    "r_xx",
    "r_xy",
    "r_yy",
    "r_xz",
    "r_yz",
    "r_zz",
    ORIGIN,
];

/// The column schema: a file holds one layout, whose measurement columns the writer
/// writes and the reader requires, in the order listed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Layout {
    /// `range,azimuth`.
    Polar,
    /// `range,azimuth,elevation`.
    Spherical,
    /// `x,y,r_xx,r_xy,r_yy`.
    Cartesian2,
    /// `x,y,z,r_xx,r_xy,r_xz,r_yy,r_yz,r_zz`.
    Cartesian3,
}

impl Layout {
    /// The position (or polar) columns, then the covariance's upper triangle row by row.
    fn columns(self) -> (&'static [&'static str], &'static [&'static str]) {
        match self {
            Self::Polar => (&["range", "azimuth"], &[]),
            Self::Spherical => (&["range", "azimuth", "elevation"], &[]),
            Self::Cartesian2 => (&["x", "y"], &["r_xx", "r_xy", "r_yy"]),
            Self::Cartesian3 => (
                &["x", "y", "z"],
                &["r_xx", "r_xy", "r_xz", "r_yy", "r_yz", "r_zz"],
            ),
        }
    }

    /// All its measurement columns, in file order.
    fn all_columns(self) -> Vec<&'static str> {
        let (a, b) = self.columns();
        a.iter().chain(b).copied().collect()
    }

    /// The layout of a measurement.
    fn of(m: &Measurement) -> Self {
        match m {
            Measurement::Polar(_) => Self::Polar,
            Measurement::Spherical(_) => Self::Spherical,
            Measurement::Cartesian2(_) => Self::Cartesian2,
            Measurement::Cartesian3(_) => Self::Cartesian3,
        }
    }

    /// The values of `m` in the order of [`Layout::all_columns`].
    fn values(m: &Measurement) -> Vec<f64> {
        match m {
            Measurement::Polar(p) => vec![p.range(), p.azimuth()],
            Measurement::Spherical(p) => vec![p.range(), p.azimuth(), p.elevation()],
            Measurement::Cartesian2(c) => {
                let (p, r) = (c.position(), c.covariance());
                vec![p[0], p[1], r[(0, 0)], r[(0, 1)], r[(1, 1)]]
            }
            Measurement::Cartesian3(c) => {
                let (p, r) = (c.position(), c.covariance());
                let mut v = vec![p[0], p[1], p[2]];
                v.extend(upper_3(r));
                v
            }
        }
    }
}

/// The upper triangle `[xx, xy, xz, yy, yz, zz]` of a 3 × 3 matrix.
fn upper_3(r: &Matrix<3, 3>) -> [f64; 6] {
    [
        r[(0, 0)],
        r[(0, 1)],
        r[(0, 2)],
        r[(1, 1)],
        r[(1, 2)],
        r[(2, 2)],
    ]
}

/// One plot read from a file, with its 1-based line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilePlot {
    /// 1-based line in the file.
    pub line: u64,
    /// The plot (its amplitude when the file gives one; the `origin` column is not read).
    pub plot: Plot,
}

impl FilePlot {
    /// Its time (s).
    pub fn time(&self) -> f64 {
        self.plot.time()
    }

    /// Its sensor's number.
    pub fn sensor(&self) -> u32 {
        self.plot.sensor().0
    }

    /// What it measured.
    pub fn measurement(&self) -> &Measurement {
        self.plot.measurement()
    }

    /// It in the reference frame ([`argus_config::to_reference`]; `rotations`: the
    /// configuration's `(sensor, γ)`), its line kept.
    #[must_use]
    pub fn to_reference(self, rotations: &[(u32, f64)]) -> Self {
        Self {
            plot: argus_config::to_reference(rotations, self.plot),
            ..self
        }
    }
}

/// Reads a plot file: header required, columns known, one layout (polar, spherical,
/// Cartesian 2-D or 3-D), numbers finite, ranges positive, covariances positive definite,
/// time non-decreasing.
///
/// # Errors
/// [`IoError::Input`] naming the file, line and field; [`IoError::Io`].
pub fn read(path: &Path) -> Result<Vec<FilePlot>, IoError> {
    PlotReader::open(path)?.collect()
}

/// [`read`] on plot file text held in memory; `path` names it in errors.
///
/// # Errors
/// As [`read`].
pub fn read_text(text: &str, path: &Path) -> Result<Vec<FilePlot>, IoError> {
    PlotReader::new(reader().from_reader(text.as_bytes()), path)?.collect()
}

/// The CSV reader settings of plot files.
fn reader() -> csv::ReaderBuilder {
    let mut b = csv::ReaderBuilder::new();
    b.has_headers(true).flexible(false).trim(csv::Trim::All);
    b
}

/// A plot file read one plot at a time (memory independent of the file's length), with
/// the checks of [`read`]: the header when opened, each row as it comes. After an error
/// it yields nothing more.
pub struct PlotReader<R> {
    rdr: csv::Reader<R>,
    path: std::path::PathBuf,
    cols: Vec<String>,
    layout: Layout,
    record: csv::StringRecord,
    last_t: f64,
    done: bool,
}

impl PlotReader<std::fs::File> {
    /// The plot file at `path`, its header checked.
    ///
    /// # Errors
    /// As [`read`], for the header; [`IoError::Io`] when it cannot be opened.
    pub fn open(path: &Path) -> Result<Self, IoError> {
        let rdr = reader().from_path(path).map_err(|e| csv_error(path, e))?;
        Self::new(rdr, path)
    }
}

impl<R: std::io::Read> PlotReader<R> {
    /// The plots of `rdr` (a plot file called `path` in errors), its header checked.
    ///
    /// # Errors
    /// As [`read`], for the header.
    fn new(mut rdr: csv::Reader<R>, path: &Path) -> Result<Self, IoError> {
        let headers = rdr.headers().map_err(|e| csv_error(path, e))?.clone();
        let cols: Vec<String> = headers.iter().map(str::to_owned).collect();
        let layout = layout_of(&cols, path)?;
        Ok(Self {
            rdr,
            path: path.to_path_buf(),
            cols,
            layout,
            record: csv::StringRecord::new(),
            last_t: f64::NEG_INFINITY,
            done: false,
        })
    }

    /// The next row's plot, or `None` at the end of the file.
    fn next_plot(&mut self) -> Result<Option<FilePlot>, IoError> {
        let path = self.path.as_path();
        if !self
            .rdr
            .read_record(&mut self.record)
            .map_err(|e| csv_error(path, e))?
        {
            return Ok(None);
        }
        let rec = &self.record;
        let cols = &self.cols;
        let line = rec.position().map_or(0, csv::Position::line);
        let cell = |name: &str| {
            Cell::Text(
                cols.iter()
                    .position(|c| c == name)
                    .and_then(|i| rec.get(i))
                    .unwrap_or(""),
            )
        };
        row_plot(path, self.layout, line, &mut self.last_t, cell).map(Some)
    }
}

/// The layout of a table with columns `cols` (a plot file called `path` in errors): the
/// header's checks (known columns, the required ones, one layout).
fn layout_of(cols: &[String], path: &Path) -> Result<Layout, IoError> {
    for c in cols {
        if !KNOWN.contains(&c.as_str()) {
            return Err(IoError::input(
                path,
                Some(1),
                Some(c),
                format!("unknown column (known: {})", KNOWN.join(", ")),
            ));
        }
    }
    let idx = |name: &str| cols.iter().position(|c| c == name);
    // The first of `names` the header lacks, as the error.
    let require = |names: &[&str]| match names.iter().find(|n| idx(n).is_none()) {
        Some(name) => Err(IoError::input(
            path,
            Some(1),
            Some(name),
            "required column is missing",
        )),
        None => Ok(()),
    };
    require(&[TIME, SENSOR])?;
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
    let layout = match (polar, cart, three_d) {
        (true, false, false) => Layout::Polar,
        (true, false, true) => Layout::Spherical,
        (false, true, false) => Layout::Cartesian2,
        (false, true, true) => Layout::Cartesian3,
        (true, true, _) => {
            return Err(IoError::input(
                path,
                Some(1),
                None,
                "a file holds either polar/spherical (range, azimuth[, elevation]) or Cartesian (x, y[, z]) plots, not both",
            ));
        }
        (false, false, _) => {
            return Err(IoError::input(
                path,
                Some(1),
                None,
                "no measurement columns: expected range,azimuth[,elevation] or x,y,r_xx,r_xy,r_yy (3-D: x,y,z,r_xx,r_xy,r_xz,r_yy,r_yz,r_zz)",
            ));
        }
    };
    require(&layout.all_columns())?;
    Ok(layout)
}

/// The sensor id a cell of a plot table holds: a non-negative integer that fits a `u32`.
fn sensor_id(cell: Cell<'_>) -> Option<u32> {
    match cell {
        Cell::Text(raw) => raw.parse().ok(),
        Cell::Int(i) => u32::try_from(i).ok(),
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        Cell::Float(v) => {
            (v.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&v)).then_some(v as u32)
        }
    }
}

/// The checks of one row and its plot: `cell(name)` is the row's cell of column `name`,
/// `line` its line (named in errors with `path` and the field), `last_t` the previous
/// row's time (updated).
fn row_plot<'a>(
    path: &Path,
    layout: Layout,
    line: u64,
    last_t: &mut f64,
    cell: impl Fn(&str) -> Cell<'a>,
) -> Result<FilePlot, IoError> {
    let covariance_cols = layout.columns().1;
    let at = |name: &str, message: String| IoError::input(path, Some(line), Some(name), message);
    let num = |name: &str| -> Result<f64, IoError> {
        let c = cell(name);
        let v: f64 = match c {
            Cell::Text(raw) => raw
                .parse()
                .map_err(|_| at(name, format!("'{raw}' is not a number")))?,
            Cell::Float(v) => v,
            #[allow(clippy::cast_precision_loss)]
            Cell::Int(i) => i as f64,
        };
        if v.is_finite() {
            Ok(v)
        } else {
            Err(at(name, format!("'{c}' is not finite")))
        }
    };
    let time = num(TIME)?;
    if time < *last_t {
        let last_t = *last_t;
        return Err(at(
            TIME,
            format!("time goes backwards ({time} after {last_t})"),
        ));
    }
    *last_t = time;
    let raw_sensor = cell(SENSOR);
    let sensor: u32 = sensor_id(raw_sensor).ok_or_else(|| {
        at(
            SENSOR,
            format!("'{raw_sensor}' is not a sensor id (a non-negative integer)"),
        )
    })?;
    // An empty amplitude field means the plot has none (a file may mix both).
    let amplitude = if cell(AMPLITUDE).is_given() {
        Some(num(AMPLITUDE)?)
    } else {
        None
    };
    let measurement: Measurement = match layout {
        Layout::Polar | Layout::Spherical => {
            let range = num("range")?;
            if range <= 0.0 {
                return Err(at("range", format!("range {range} must be positive")));
            }
            let azimuth = num("azimuth")?;
            let bad = |e: argus_sensors::SensorError| at("range", e.to_string());
            if layout == Layout::Spherical {
                let elevation = num("elevation")?;
                if elevation.abs() > std::f64::consts::FRAC_PI_2 {
                    return Err(at(
                        "elevation",
                        format!("elevation {elevation} rad lies outside [-π/2, π/2]"),
                    ));
                }
                SphericalMeasurement::new(range, azimuth, elevation)
                    .map_err(bad)?
                    .into()
            } else {
                PolarMeasurement::new(range, azimuth).map_err(bad)?.into()
            }
        }
        Layout::Cartesian2 | Layout::Cartesian3 => {
            // The covariance is read (and checked) before the position, so that a
            // bad covariance is reported at `r_xx` whatever the position holds.
            let cov: Vec<f64> = covariance_cols
                .iter()
                .map(|c| num(c))
                .collect::<Result<_, _>>()?;
            let not_pd = || {
                let m = if layout == Layout::Cartesian3 {
                    "covariance [r_xx r_xy r_xz; r_xy r_yy r_yz; r_xz r_yz r_zz] is not positive definite"
                } else {
                    "covariance [r_xx r_xy; r_xy r_yy] is not positive definite"
                };
                at("r_xx", m.to_owned())
            };
            if layout == Layout::Cartesian3 {
                let [xx, xy, xz, yy, yz, zz] = cov[..] else {
                    return Err(not_pd());
                };
                let r = Matrix::<3, 3>::new(xx, xy, xz, xy, yy, yz, xz, yz, zz);
                argus_core_math::SpdFactor::new(&r, "plot covariance").map_err(|_| not_pd())?;
                let p = Vector::<3>::new(num("x")?, num("y")?, num("z")?);
                CartesianMeasurement::new(p, r)
                    .map_err(|_| not_pd())?
                    .into()
            } else {
                let [xx, xy, yy] = cov[..] else {
                    return Err(not_pd());
                };
                let r = Matrix::<2, 2>::new(xx, xy, xy, yy);
                argus_core_math::SpdFactor::new(&r, "plot covariance").map_err(|_| not_pd())?;
                let p = Vector::<2>::new(num("x")?, num("y")?);
                CartesianMeasurement::new(p, r)
                    .map_err(|_| not_pd())?
                    .into()
            }
        }
    };
    let plot = Plot::new(time, SensorId(sensor), measurement)
        .and_then(|p| p.with_amplitude(amplitude))
        .map_err(|e| at(TIME, e.to_string()))?;
    Ok(FilePlot { line, plot })
}

/// A column of a plot table given as values ([`from_columns`]): the table column of
/// `argus_score`'s readers (the `origin` column, text, is not read).
pub use argus_score::Column;

/// The plots of a table given as columns (`names[k]` holding `columns[k]`), with exactly
/// the checks of [`read`] on the equivalent plot file: its header `names`, row `i` its
/// line `i + 2`; `name` stands for the file's path in errors.
///
/// # Errors
/// [`IoError::Input`] naming `name`, the line and the field, as [`read`]; also when the
/// names and columns differ in number or the columns in length.
pub fn from_columns(
    names: &[&str],
    columns: &[Column<'_>],
    name: &Path,
) -> Result<Vec<FilePlot>, IoError> {
    let lengths: Vec<usize> = columns.iter().map(Column::len).collect();
    if names.len() != columns.len() || lengths.windows(2).any(|w| w[0] != w[1]) {
        return Err(IoError::input(
            name,
            None,
            None,
            format!(
                "{} column names for {} columns of lengths {lengths:?}",
                names.len(),
                columns.len()
            ),
        ));
    }
    let cols: Vec<String> = names.iter().map(|n| (*n).to_owned()).collect();
    let layout = layout_of(&cols, name)?;
    let mut last_t = f64::NEG_INFINITY;
    (0..lengths.first().copied().unwrap_or(0))
        .map(|i| {
            let cell = |c: &str| {
                names
                    .iter()
                    .position(|n| *n == c)
                    .map_or(Cell::Text(""), |k| {
                        columns[k].cell(i).unwrap_or(Cell::Text(""))
                    })
            };
            row_plot(name, layout, i as u64 + 2, &mut last_t, cell)
        })
        .collect()
}

impl<R: std::io::Read> Iterator for PlotReader<R> {
    type Item = Result<FilePlot, IoError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.done {
            return None;
        }
        let next = self.next_plot().transpose();
        self.done = !matches!(next, Some(Ok(_)));
        next
    }
}

fn csv_error(path: &Path, e: csv::Error) -> IoError {
    let line = e.position().map(csv::Position::line);
    let message = match e.kind() {
        csv::ErrorKind::UnequalLengths {
            expected_len, len, ..
        } => format!("malformed row: {len} fields where the header has {expected_len}"),
        csv::ErrorKind::Io(err) => {
            return IoError::io(path, std::io::Error::new(err.kind(), err.to_string()));
        }
        _ => format!("malformed CSV: {e}"),
    };
    IoError::input(path, line, None, message)
}

/// Plot file text for simulated plots, in the layout of the first plot (polar,
/// spherical, Cartesian 2-D or 3-D; plots of another layout are skipped and counted), the
/// columns of `Layout`. Includes the `origin` column (`target:<id>` or `clutter`) —
/// `argus track` ignores it.
pub fn write_text(plots: &[LabelledPlot]) -> (String, usize) {
    let layout = plots
        .first()
        .map_or(Layout::Polar, |p| Layout::of(p.plot.measurement()));
    let amp = plots.iter().any(|p| p.plot.amplitude().is_some());
    let mut columns = vec![TIME, SENSOR];
    columns.extend(layout.all_columns());
    if amp {
        columns.push(AMPLITUDE);
    }
    columns.push(ORIGIN);
    let mut s = columns.join(",");
    s.push('\n');
    let mut skipped = 0;
    for LabelledPlot { plot: p, origin } in plots {
        if Layout::of(p.measurement()) != layout {
            skipped += 1;
            continue;
        }
        s.push_str(&format!("{},{}", p.time(), p.sensor().0));
        for v in Layout::values(p.measurement()) {
            s.push_str(&format!(",{v}"));
        }
        if amp {
            // No NaN as a "missing" marker: a plot without amplitude leaves the field empty.
            match p.amplitude() {
                Some(a) => s.push_str(&format!(",{a}")),
                None => s.push(','),
            }
        }
        match origin {
            Origin::Target(id) => s.push_str(&format!(",target:{}\n", id.0)),
            Origin::Clutter => s.push_str(",clutter\n"),
        }
    }
    (s, skipped)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Vec<FilePlot>, IoError> {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("p.csv");
        std::fs::write(&p, text).unwrap();
        read(&p)
    }

    fn at(e: &IoError) -> (Option<u64>, Option<String>) {
        match e {
            IoError::Input { at, .. } => (at.line, at.field.clone()),
            other => panic!("not an input error: {other}"),
        }
    }

    #[test]
    fn covariances_are_checked_whole() {
        let row = |cov: &str| {
            parse(&format!(
                "t,sensor,x,y,z,r_xx,r_xy,r_xz,r_yy,r_yz,r_zz\n0,1,1,2,3,{cov}\n"
            ))
        };
        // diag(1, 2, 3) and [[2, 1, 0], [1, 2, 1], [0, 1, 2]] (minors 2, 3, 4) are definite.
        assert!(row("1,0,0,2,0,3").is_ok());
        assert!(row("2,1,0,2,1,2").is_ok());
        // All ones is singular (rank 1); [[1, 0, 2], [0, 1, 0], [2, 0, 1]] has det −3 < 0
        // though its 2 × 2 minor is 1. Both named at r_xx, line 2.
        for bad in ["1,1,1,1,1,1", "1,0,2,1,0,1"] {
            assert_eq!(at(&row(bad).unwrap_err()), (Some(2), Some("r_xx".into())));
        }
        // A bad covariance is reported before a bad position.
        let e = parse("t,sensor,x,y,r_xx,r_xy,r_yy\n0,1,nan,2,1,2,1\n").unwrap_err();
        assert_eq!(at(&e), (Some(2), Some("r_xx".into())));
    }

    #[test]
    fn layouts_are_recognised() {
        let p = parse("t,sensor,range,azimuth,elevation\n0,1,1000,0.1,0.2\n").unwrap();
        assert_eq!(
            *p[0].measurement(),
            Measurement::from(SphericalMeasurement::new(1000.0, 0.1, 0.2).unwrap())
        );
        assert_eq!(p[0].measurement().dim(), 3);
        // Columns in any order; the covariance keeps its upper-triangle order.
        // [[1, .2, .3], [.2, 4, 1], [.3, 1, 6]]: minors 1, 3.96, det 22.52 > 0.
        let p =
            parse("r_zz,r_yz,r_yy,r_xz,r_xy,r_xx,z,y,x,sensor,t\n6,1,4,0.3,0.2,1,3,2,1,4,0.5\n")
                .unwrap();
        let Measurement::Cartesian3(c) = p[0].measurement() else {
            panic!("not 3-D Cartesian");
        };
        assert_eq!(*c.position(), Vector::<3>::new(1.0, 2.0, 3.0));
        // Read exactly (the same decimal strings parse to the same f64).
        let bits = |v: [f64; 6]| v.map(f64::to_bits);
        assert_eq!(
            bits(upper_3(c.covariance())),
            bits([1.0, 0.2, 0.3, 4.0, 1.0, 6.0])
        );
        // cov [[1, .2, .3], [.2, 4, 5], [.3, 5, 6]] has det < 0: rejected on line 2.
        let e = parse("t,sensor,x,y,z,r_xx,r_xy,r_xz,r_yy,r_yz,r_zz\n0,1,1,2,3,1,0.2,0.3,4,5,6\n")
            .unwrap_err();
        assert_eq!(at(&e), (Some(2), Some("r_xx".into())));
        assert_eq!(p[0].sensor(), 4);
        assert_eq!(p[0].line, 2);
    }

    #[test]
    fn plots_without_amplitude_round_trip_beside_plots_with_one() {
        // A target plot with an amplitude and one without: the writer leaves the field
        // empty (never NaN) and the reader accepts the file.
        let mk = |t: f64, amplitude| LabelledPlot {
            plot: Plot::polar(t, SensorId(1), 1000.0 + t, 0.1)
                .unwrap()
                .with_amplitude(amplitude)
                .unwrap(),
            origin: Origin::Clutter,
        };
        let plots = [mk(0.0, Some(2.5)), mk(1.0, None)];
        let (text, skipped) = write_text(&plots);
        assert_eq!(skipped, 0);
        assert!(!text.contains("NaN"), "{text}");
        // What is written reads back as the same plots (Rust's shortest round-trip
        // formatting of f64 is exact).
        let p = parse(&text).unwrap();
        assert_eq!(p.len(), 2);
        assert_eq!(p[0].plot, plots[0].plot);
        assert_eq!(p[1].plot, plots[1].plot);
        // A non-numeric amplitude is still an error naming line and field.
        let e = parse("t,sensor,range,azimuth,amplitude\n0,1,1000,0.1,x\n").unwrap_err();
        assert_eq!(at(&e), (Some(2), Some("amplitude".into())));
    }

    #[test]
    fn every_layout_round_trips_through_one_schema() {
        let r2 = Matrix::<2, 2>::new(4.0, 0.5, 0.5, 9.0);
        let r3 = Matrix::<3, 3>::new(4.0, 0.5, 0.1, 0.5, 9.0, 0.2, 0.1, 0.2, 1.0);
        let measurements: [Measurement; 4] = [
            PolarMeasurement::new(1e4, -2.5).unwrap().into(),
            SphericalMeasurement::new(1e4, 0.3, 0.05).unwrap().into(),
            CartesianMeasurement::new(Vector::<2>::new(-3.25, 1e5 / 3.0), r2)
                .unwrap()
                .into(),
            CartesianMeasurement::new(Vector::<3>::new(1.0, -2.0, 1.0 / 3.0), r3)
                .unwrap()
                .into(),
        ];
        for m in measurements {
            let plots: Vec<LabelledPlot> = (0..3)
                .map(|k| LabelledPlot {
                    plot: Plot::new(0.5 * f64::from(k), SensorId(k), m).unwrap(),
                    origin: Origin::Target(argus_sim::TargetId(k)),
                })
                .collect();
            let (text, skipped) = write_text(&plots);
            assert_eq!(skipped, 0);
            let back = parse(&text).unwrap();
            let read: Vec<Plot> = back.iter().map(|p| p.plot).collect();
            let written: Vec<Plot> = plots.iter().map(|p| p.plot).collect();
            assert_eq!(read, written, "{text}");
            assert_eq!(back[2].line, 4);
        }
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

    #[test]
    fn columns_are_read_as_the_equivalent_file() {
        let text = "t,sensor,range,azimuth,amplitude\n0,1,1000.5,0.25,3\n1,1,2000,-0.5,4.5\n";
        let file = parse(text).unwrap();
        let (t, range, az, amp) = ([0.0, 1.0], [1000.5, 2000.0], [0.25, -0.5], [3.0, 4.5]);
        let names = ["t", "sensor", "range", "azimuth", "amplitude"];
        let sensor = [1_i64, 1];
        let cols = [
            Column::Float(&t),
            Column::Int(&sensor),
            Column::Float(&range),
            Column::Float(&az),
            Column::Float(&amp),
        ];
        let plots = from_columns(&names, &cols, Path::new("plots")).unwrap();
        assert_eq!(plots, file);
        // The same checks, named as the file's line and field.
        let bad_range = [1000.5, -3.0];
        let mut bad = cols;
        bad[2] = Column::Float(&bad_range);
        let e = from_columns(&names, &bad, Path::new("plots")).unwrap_err();
        assert!(e.to_string().starts_with("plots:3: field 'range'"), "{e}");
        let bad_sensor = [1_i64, -1];
        let mut bad = cols;
        bad[1] = Column::Int(&bad_sensor);
        let e = from_columns(&names, &bad, Path::new("plots")).unwrap_err();
        assert_eq!(at(&e), (Some(3), Some("sensor".into())));
        let e = from_columns(&names[..4], &cols[..4], Path::new("plots"));
        assert!(e.is_ok());
        let e = from_columns(&["t", "sensor"], &cols[..2], Path::new("plots")).unwrap_err();
        assert_eq!(at(&e).0, Some(1));
    }
}
