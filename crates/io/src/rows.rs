//! The tracks CSV of `argus track` (`docs/FORMATS.md`): a column schema and the one
//! writer of its rows, for both jobs. Numbers are written with `{}` (the shortest text
//! that reads back to the same `f64`); a value a row does not have is an empty cell.

use std::fmt::Write as _;

use argus_core_math::Gaussian;
use argus_imm::NoiseVariances;

use crate::error::IoError;
use crate::output::AtomicFile;
use argus_config::Reference;

/// The state components' names, `[x, vx, y, vy, z, vz]`.
const STATE: [&str; 6] = ["x", "vx", "y", "vy", "z", "vz"];

/// One column of a tracks CSV.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Column {
    /// `t`: the estimate's time (s).
    Time,
    /// `sensor`: the sensor of the scan that produced the row.
    Sensor,
    /// `track`: the track's id.
    Track,
    /// `status`: tentative, confirmed or deleted.
    Status,
    /// `reason`: why a deleted track was deleted (empty otherwise).
    Reason,
    /// State component `i` of `[x, vx, y, vy, z, vz]`.
    State(usize),
    /// `var_<component>`: the covariance's diagonal entry `i`.
    Variance(usize),
    /// `sigma_<axis>`: the standard deviation of position axis `a` (x, y, z).
    PositionSigma(usize),
    /// `mu_<j + 1>`: the probability of IMM mode `j`.
    Mode(usize),
    /// `sigma_range`: the multi-IMM's range noise estimate (m).
    SigmaRange,
    /// `sigma_azimuth_deg`: the multi-IMM's azimuth noise estimate (°).
    SigmaAzimuthDeg,
    /// `score`: the track score.
    Score,
    /// `turn_rate_deg`: the aircraft IMM's CT-mode turn rate (°/s).
    TurnRateDeg,
    /// `sigma_turn_rate_deg`: its standard deviation (°/s).
    SigmaTurnRateDeg,
    /// `<component>s`: smoothed state component `i` (`xs`, `vxs`, …; `--smooth`).
    Smoothed(usize),
    /// `var_<component>s`: the smoothed covariance's diagonal entry `i`.
    SmoothedVariance(usize),
    /// `sigma_<axis>s`: the smoothed standard deviation of position axis `a`.
    SmoothedPositionSigma(usize),
    /// `mu_<j + 1>s`: the smoothed probability of IMM mode `j`.
    SmoothedMode(usize),
    /// `lat`: WGS-84 latitude (°) of the row's `x, y` (with a `[reference]`).
    Lat,
    /// `lon`: WGS-84 longitude (°).
    Lon,
}

impl Column {
    /// The header name.
    fn name(self) -> String {
        let state = |i: usize| STATE.get(i).copied().unwrap_or("?");
        match self {
            Self::Time => "t".into(),
            Self::Sensor => "sensor".into(),
            Self::Track => "track".into(),
            Self::Status => "status".into(),
            Self::Reason => "reason".into(),
            Self::State(i) => state(i).into(),
            Self::Variance(i) => format!("var_{}", state(i)),
            Self::PositionSigma(a) => format!("sigma_{}", state(2 * a)),
            Self::Mode(j) => format!("mu_{}", j + 1),
            Self::SigmaRange => "sigma_range".into(),
            Self::SigmaAzimuthDeg => "sigma_azimuth_deg".into(),
            Self::Score => "score".into(),
            Self::TurnRateDeg => "turn_rate_deg".into(),
            Self::SigmaTurnRateDeg => "sigma_turn_rate_deg".into(),
            Self::Smoothed(i) => format!("{}s", state(i)),
            Self::SmoothedVariance(i) => format!("var_{}s", state(i)),
            Self::SmoothedPositionSigma(a) => format!("sigma_{}s", state(2 * a)),
            Self::SmoothedMode(j) => format!("mu_{}s", j + 1),
            Self::Lat => "lat".into(),
            Self::Lon => "lon".into(),
        }
    }

    /// The aircraft IMM's turn-rate columns, after its mode probabilities.
    pub const TURN_RATE: [Self; 2] = [Self::TurnRateDeg, Self::SigmaTurnRateDeg];

    /// The single-target job's smoothed columns (`--smooth`): the smoothed state of
    /// `axes` axes, its variances and `modes` smoothed mode probabilities.
    pub fn smoothed_single(axes: usize, modes: usize) -> Vec<Self> {
        let n = 2 * axes;
        let mut c: Vec<Self> = (0..n).map(Self::Smoothed).collect();
        c.extend((0..n).map(Self::SmoothedVariance));
        c.extend((0..modes).map(Self::SmoothedMode));
        c
    }

    /// The tracker's smoothed columns: `xs, vxs, ys, vys, sigma_xs, sigma_ys`, then
    /// `modes` smoothed mode probabilities (`mu_1s, …`; the IMM's).
    pub fn smoothed_tracker(modes: usize) -> Vec<Self> {
        let mut c: Vec<Self> = (0..4).map(Self::Smoothed).collect();
        c.extend([
            Self::SmoothedPositionSigma(0),
            Self::SmoothedPositionSigma(1),
        ]);
        c.extend((0..modes).map(Self::SmoothedMode));
        c
    }

    /// The single-target columns: `t, track`, the CV state of `axes` axes (2 or 3), its
    /// variances, then `modes` mode probabilities and, with `noise`, the noise estimate.
    pub fn single(axes: usize, modes: usize, noise: bool) -> Vec<Self> {
        let n = 2 * axes;
        let mut c = vec![Self::Time, Self::Track];
        c.extend((0..n).map(Self::State));
        c.extend((0..n).map(Self::Variance));
        c.extend((0..modes).map(Self::Mode));
        if noise {
            c.extend([Self::SigmaRange, Self::SigmaAzimuthDeg]);
        }
        c
    }

    /// The multi-target tracker's columns: `t, sensor, track, status, reason`, the 2-D
    /// state and position σ, then `modes` mode probabilities, the noise estimate (with
    /// `noise`) and the track score (with `score`).
    pub fn tracker(modes: usize, noise: bool, score: bool) -> Vec<Self> {
        let mut c = vec![
            Self::Time,
            Self::Sensor,
            Self::Track,
            Self::Status,
            Self::Reason,
        ];
        c.extend((0..4).map(Self::State));
        c.extend([Self::PositionSigma(0), Self::PositionSigma(1)]);
        c.extend((0..modes).map(Self::Mode));
        if noise {
            c.extend([Self::SigmaRange, Self::SigmaAzimuthDeg]);
        }
        if score {
            c.push(Self::Score);
        }
        c
    }
}

/// One track's estimate at one time, and what a row may say about it.
#[derive(Debug, Clone, Copy)]
pub struct Point<'a> {
    time: f64,
    mean: &'a [f64],
    cov: &'a [f64],
    dim: usize,
    sensor: u32,
    track: u64,
    status: &'a str,
    reason: &'a str,
    modes: Option<&'a [f64]>,
    noise: Option<NoiseVariances>,
    score: f64,
    turn_rate: Option<(f64, f64)>,
    /// The smoothed estimate's mean and covariance (column-major), same dimension.
    smoothed: Option<(&'a [f64], &'a [f64])>,
    smoothed_modes: Option<&'a [f64]>,
}

impl<'a> Point<'a> {
    /// The estimate `g` at `time`, of track 1 (the single-target job's one track).
    pub fn new<const N: usize>(time: f64, g: &'a Gaussian<N>) -> Self {
        Self {
            time,
            mean: g.mean().as_slice(),
            cov: g.cov().as_slice(),
            dim: N,
            sensor: 0,
            track: 1,
            status: "",
            reason: "",
            modes: None,
            noise: None,
            score: 0.0,
            turn_rate: None,
            smoothed: None,
            smoothed_modes: None,
        }
    }

    /// With the smoothed estimate `g` of the same state (`None`: empty cells).
    pub fn smoothed<const N: usize>(self, g: Option<&'a Gaussian<N>>) -> Self {
        let smoothed = g
            .filter(|_| N == self.dim)
            .map(|g| (g.mean().as_slice(), g.cov().as_slice()));
        Self { smoothed, ..self }
    }

    /// With smoothed IMM mode probabilities (`None`: empty cells).
    pub fn smoothed_modes(self, smoothed_modes: Option<&'a [f64]>) -> Self {
        Self {
            smoothed_modes,
            ..self
        }
    }

    /// A tracker's track: its id, status and deletion reason, of the scan of `sensor`.
    pub fn of_track(self, sensor: u32, track: u64, status: &'a str, reason: &'a str) -> Self {
        Self {
            sensor,
            track,
            status,
            reason,
            ..self
        }
    }

    /// With IMM mode probabilities (`None`: empty cells).
    pub fn modes(self, modes: Option<&'a [f64]>) -> Self {
        Self { modes, ..self }
    }

    /// With the multi-IMM's noise estimate (`None`: empty cells).
    pub fn noise(self, noise: Option<NoiseVariances>) -> Self {
        Self { noise, ..self }
    }

    /// With the aircraft IMM's turn rate and its σ, rad/s (`None`: empty cells).
    pub fn turn_rate(self, turn_rate: Option<(f64, f64)>) -> Self {
        Self { turn_rate, ..self }
    }

    /// With a track score.
    pub fn score(self, score: f64) -> Self {
        Self { score, ..self }
    }

    /// The covariance's entry `(i, i)` (column-major storage).
    fn var(&self, i: usize) -> Option<f64> {
        self.cov.get(i * self.dim + i).copied()
    }

    /// The smoothed covariance's entry `(i, i)`.
    fn smoothed_var(&self, i: usize) -> Option<f64> {
        self.smoothed
            .and_then(|(_, cov)| cov.get(i * self.dim + i).copied())
    }
}

/// A tracks CSV being written: the header, then one line per [`TrackRows::push`].
#[derive(Debug)]
pub struct TrackRows {
    columns: Vec<Column>,
    text: String,
    /// Whether `text` still begins with the header (until the first `write_to`).
    header_held: bool,
    rows: usize,
    reference: Option<Reference>,
}

impl TrackRows {
    /// An empty file with the header of `columns`.
    pub fn new(columns: Vec<Column>) -> Self {
        let names: Vec<String> = columns.iter().map(|c| c.name()).collect();
        let mut text = names.join(",");
        text.push('\n');
        Self {
            columns,
            text,
            header_held: true,
            rows: 0,
            reference: None,
        }
    }

    /// An empty file with the header of `columns` and, with a `reference`, the `lat, lon`
    /// of each row's `x, y` (at the reference's altitude, [`Reference::lat_lon`]) last.
    pub fn with_reference(mut columns: Vec<Column>, reference: Option<&Reference>) -> Self {
        if reference.is_some() {
            columns.extend([Column::Lat, Column::Lon]);
        }
        Self {
            reference: reference.copied(),
            ..Self::new(columns)
        }
    }

    /// Appends the row of `p`.
    pub fn push(&mut self, p: &Point<'_>) {
        let lat_lon = match (self.reference, p.mean.first(), p.mean.get(2)) {
            (Some(r), Some(&x), Some(&y)) => r.lat_lon(x, y).ok(),
            _ => None,
        };
        let out = &mut self.text;
        for (k, c) in self.columns.iter().enumerate() {
            if k > 0 {
                out.push(',');
            }
            let _ = match *c {
                Column::Time => write!(out, "{}", p.time),
                Column::Sensor => write!(out, "{}", p.sensor),
                Column::Track => write!(out, "{}", p.track),
                Column::Status => write!(out, "{}", p.status),
                Column::Reason => write!(out, "{}", p.reason),
                Column::State(i) => cell(out, p.mean.get(i).copied()),
                Column::Variance(i) => cell(out, p.var(i)),
                Column::PositionSigma(a) => cell(out, p.var(2 * a).map(f64::sqrt)),
                Column::Mode(j) => cell(out, p.modes.and_then(|m| m.get(j).copied())),
                Column::SigmaRange => cell(out, p.noise.map(|v| v.range().sqrt())),
                Column::SigmaAzimuthDeg => {
                    cell(out, p.noise.map(|v| v.azimuth().sqrt().to_degrees()))
                }
                Column::Score => write!(out, "{}", p.score),
                Column::TurnRateDeg => cell(out, p.turn_rate.map(|w| w.0.to_degrees())),
                Column::SigmaTurnRateDeg => cell(out, p.turn_rate.map(|w| w.1.to_degrees())),
                Column::Smoothed(i) => cell(out, p.smoothed.and_then(|(m, _)| m.get(i).copied())),
                Column::SmoothedVariance(i) => cell(out, p.smoothed_var(i)),
                Column::SmoothedPositionSigma(a) => cell(out, p.smoothed_var(2 * a).map(f64::sqrt)),
                Column::SmoothedMode(j) => {
                    cell(out, p.smoothed_modes.and_then(|m| m.get(j).copied()))
                }
                Column::Lat => cell(out, lat_lon.map(|ll| ll.0)),
                Column::Lon => cell(out, lat_lon.map(|ll| ll.1)),
            };
        }
        out.push('\n');
        self.rows += 1;
    }

    /// The rows written so far (the header not counted).
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// The rows held (those not yet written by [`TrackRows::write_to`]) as columns of
    /// values, in the header's order: `sensor` and `track` as integers, `status` and
    /// `reason` as text, every other column as `f64`, each exactly the value whose `{}`
    /// text the CSV holds (an empty cell as NaN).
    pub fn columns(&self) -> Vec<(String, ColumnValues)> {
        let names: Vec<String> = self.columns.iter().map(|c| c.name()).collect();
        let body = if self.header_held {
            self.text.split_once('\n').map_or("", |(_, body)| body)
        } else {
            self.text.as_str()
        };
        columns_of_text(&names, body)
    }

    /// The file's text.
    pub fn into_text(self) -> String {
        self.text
    }

    /// Writes the text not yet written (the header first) to `file` and forgets it: the
    /// file as a stream, holding only the rows since the last call.
    ///
    /// # Errors
    /// [`IoError::Io`].
    pub fn write_to(&mut self, file: &mut AtomicFile) -> Result<(), IoError> {
        file.write(self.text.as_bytes())?;
        self.text.clear();
        self.header_held = false;
        Ok(())
    }

    /// The length of the text not yet written (bytes).
    pub fn pending(&self) -> usize {
        self.text.len()
    }
}

/// A number, or nothing.
fn cell(out: &mut String, v: Option<f64>) -> std::fmt::Result {
    v.map_or(Ok(()), |v| write!(out, "{v}"))
}

/// A tracks CSV column's values ([`TrackRows::columns`]).
#[derive(Debug, Clone, PartialEq)]
pub enum ColumnValues {
    /// Numbers; NaN for an empty cell.
    F64(Vec<f64>),
    /// `sensor`, `track`.
    I64(Vec<i64>),
    /// `status`, `reason`.
    Text(Vec<String>),
}

/// The kind of values of the tracks CSV column `name`.
fn empty_column(name: &str) -> ColumnValues {
    match name {
        "sensor" | "track" => ColumnValues::I64(Vec::new()),
        "status" | "reason" => ColumnValues::Text(Vec::new()),
        _ => ColumnValues::F64(Vec::new()),
    }
}

/// The columns `names` of tracks CSV rows `body` (no header; written by [`TrackRows`]).
fn columns_of_text(names: &[String], body: &str) -> Vec<(String, ColumnValues)> {
    let mut out: Vec<(String, ColumnValues)> =
        names.iter().map(|n| (n.clone(), empty_column(n))).collect();
    for line in body.lines().filter(|l| !l.is_empty()) {
        for ((_, col), cell) in out.iter_mut().zip(line.split(',')) {
            match col {
                ColumnValues::F64(v) => v.push(cell.parse().unwrap_or(f64::NAN)),
                ColumnValues::I64(v) => v.push(cell.parse().unwrap_or(0)),
                ColumnValues::Text(v) => v.push(cell.to_owned()),
            }
        }
    }
    out
}

/// The columns of tracks CSV text (header and rows, as [`TrackRows`] writes it and
/// `argus track` writes its file), as [`TrackRows::columns`] gives them.
pub fn text_columns(text: &str) -> Vec<(String, ColumnValues)> {
    let (head, body) = text.split_once('\n').unwrap_or((text, ""));
    let names: Vec<String> = head
        .trim_end_matches('\r')
        .split(',')
        .filter(|n| !n.is_empty())
        .map(str::to_owned)
        .collect();
    columns_of_text(&names, body)
}

#[cfg(test)]
mod tests {
    use super::*;
    use argus_core_math::{Matrix, Vector};

    #[test]
    fn headers_match_the_documented_columns() {
        // docs/FORMATS.md, "tracks CSV".
        let names = |c: Vec<Column>| TrackRows::new(c).into_text();
        assert_eq!(
            names(Column::single(2, 0, false)),
            "t,track,x,vx,y,vy,var_x,var_vx,var_y,var_vy\n"
        );
        assert_eq!(
            names(Column::single(3, 0, false)),
            "t,track,x,vx,y,vy,z,vz,var_x,var_vx,var_y,var_vy,var_z,var_vz\n"
        );
        assert_eq!(
            names(Column::single(2, 3, true)),
            "t,track,x,vx,y,vy,var_x,var_vx,var_y,var_vy,mu_1,mu_2,mu_3,sigma_range,sigma_azimuth_deg\n"
        );
        assert_eq!(
            names(Column::tracker(2, true, true)),
            "t,sensor,track,status,reason,x,vx,y,vy,sigma_x,sigma_y,mu_1,mu_2,sigma_range,sigma_azimuth_deg,score\n"
        );
        // The smoothed columns (--smooth) and the geodetic ones ([reference]).
        let mut c = Column::single(2, 2, false);
        c.extend(Column::smoothed_single(2, 2));
        assert_eq!(
            names(c),
            "t,track,x,vx,y,vy,var_x,var_vx,var_y,var_vy,mu_1,mu_2,xs,vxs,ys,vys,var_xs,var_vxs,var_ys,var_vys,mu_1s,mu_2s\n"
        );
        let mut c = Column::tracker(0, false, false);
        c.extend(Column::smoothed_tracker(0));
        c.extend([Column::Lat, Column::Lon]);
        assert_eq!(
            names(c),
            "t,sensor,track,status,reason,x,vx,y,vy,sigma_x,sigma_y,xs,vxs,ys,vys,sigma_xs,sigma_ys,lat,lon\n"
        );
    }

    #[test]
    fn rows_hold_the_diagonal_and_empty_cells() {
        let g = Gaussian::new(
            Vector::<4>::new(1.0, 2.0, 3.0, 4.0),
            Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(4.0, 0.5, 9.0, 0.25)),
        )
        .unwrap();
        let mut single = TrackRows::new(Column::single(2, 2, false));
        single.push(&Point::new(2.5, &g).modes(Some(&[0.25, 0.75])));
        assert_eq!(single.rows(), 1);
        assert!(
            single
                .into_text()
                .ends_with("\n2.5,1,1,2,3,4,4,0.5,9,0.25,0.25,0.75\n")
        );
        // The tracker: σ = √ of the position variances (exact here), no modes given.
        let mut multi = TrackRows::new(Column::tracker(2, true, false));
        multi.push(&Point::new(5.0, &g).of_track(7, 12, "deleted", "misses"));
        assert!(
            multi
                .into_text()
                .ends_with("\n5,7,12,deleted,misses,1,2,3,4,2,3,,,,\n")
        );
        // A smoothed row: the smoothed mean and σ; a row without one: empty cells.
        let h = Gaussian::new(
            Vector::<4>::new(5.0, 6.0, 7.0, 8.0),
            Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(1.0, 0.25, 4.0, 0.0625)),
        )
        .unwrap();
        let mut c = Column::tracker(0, false, false);
        c.extend(Column::smoothed_tracker(0));
        let mut s = TrackRows::new(c);
        s.push(&Point::new(1.0, &g).smoothed(Some(&h)));
        s.push(&Point::new(2.0, &g).smoothed::<4>(None));
        assert!(
            s.into_text()
                .ends_with("\n1,0,1,,,1,2,3,4,2,3,5,6,7,8,1,2\n2,0,1,,,1,2,3,4,2,3,,,,,,\n")
        );
    }

    #[test]
    fn columns_hold_the_values_of_the_text() {
        let g = Gaussian::new(
            Vector::<4>::new(0.1, 2.0 / 3.0, 3.0, 4.0),
            Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(2.0, 0.5, 9.0, 0.25)),
        )
        .unwrap();
        let mut multi = TrackRows::new(Column::tracker(2, false, false));
        multi.push(&Point::new(5.0, &g).of_track(7, 12, "deleted", "misses"));
        multi.push(&Point::new(6.0, &g).modes(Some(&[0.25, 0.75])));
        let cols = multi.columns();
        let names: Vec<&str> = cols.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(
            names,
            text_columns(&multi.into_text())
                .iter()
                .map(|(n, _)| n.as_str())
                .collect::<Vec<_>>()
        );
        let get = |n: &str| &cols.iter().find(|(c, _)| c == n).unwrap().1;
        assert_eq!(get("t"), &ColumnValues::F64(vec![5.0, 6.0]));
        let (ColumnValues::I64(track), ColumnValues::I64(sensor), ColumnValues::Text(status)) =
            (get("track"), get("sensor"), get("status"))
        else {
            panic!("column kinds")
        };
        assert_eq!(
            (track[0], sensor[0], status[0].as_str()),
            (12, 7, "deleted")
        );
        assert_eq!(get("vx"), &ColumnValues::F64(vec![2.0 / 3.0; 2]));
        assert_eq!(get("sigma_x"), &ColumnValues::F64(vec![2.0_f64.sqrt(); 2]));
        let ColumnValues::F64(mu) = get("mu_1") else {
            panic!()
        };
        assert!(mu[0].is_nan());
        assert!((mu[1] - 0.25).abs() == 0.0);
    }

    #[test]
    fn columns_after_a_write_hold_the_rows_since() {
        // After write_to the text holds rows only: columns() then reads every held row,
        // and before it skips the header, whatever the rows' text is.
        let g = Gaussian::new(Vector::<4>::zeros(), Matrix::<4, 4>::identity()).unwrap();
        let dir = std::env::temp_dir().join(format!("argus-rows-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("t.csv");
        let mut rows = TrackRows::new(Column::tracker(0, false, false));
        rows.push(&Point::new(1.0, &g).of_track(1, 1, "tentative", ""));
        assert_eq!(rows.columns()[0].1, ColumnValues::F64(vec![1.0]));
        let mut file = AtomicFile::create(&path).unwrap();
        rows.write_to(&mut file).unwrap();
        assert!(rows.columns().iter().all(|(_, c)| c
            == &empty_column(match c {
                ColumnValues::I64(_) => "track",
                ColumnValues::Text(_) => "status",
                ColumnValues::F64(_) => "t",
            })));
        rows.push(&Point::new(2.0, &g).of_track(1, 1, "confirmed", ""));
        rows.push(&Point::new(3.0, &g).of_track(1, 1, "confirmed", ""));
        assert_eq!(rows.columns()[0].1, ColumnValues::F64(vec![2.0, 3.0]));
        rows.write_to(&mut file).unwrap();
        file.commit().unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(text.lines().count(), 4, "{text}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
