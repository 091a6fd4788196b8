//! System tracks: CAT062 (I062/010, /070 time of track, /040 track number, /100
//! Cartesian position, /185 Cartesian velocity) to the tracks CSV columns `argus score`
//! reads, and a tracks CSV's confirmed rows to CAT062 (for a display or a recorder).

use std::path::Path;

use argus_asterix::{Cartesian062, Cat062, DataSource, ItemId, Record, TimeOfDay, Velocity062};

use super::Surveillance;
use super::encode::Encoded;
use super::plots::{Clock, DAY};
use crate::error::IoError;

/// Reports per CAT062 block (one block per datagram): 64 of 20 bytes.
const RECORDS_PER_BLOCK: usize = 64;

/// The tracks CSV text `t,track,x,vx,y,vy,status` of the CAT062 records of `s` with a
/// time, a track number, a Cartesian position and a velocity (every row `confirmed`:
/// CAT062 tracks are the system's output), in file order; and how many records had not
/// all four.
pub fn tracks_csv(s: &Surveillance) -> (String, usize, usize) {
    let mut clock = Clock::default();
    let mut text = String::from("t,track,x,vx,y,vy,status\n");
    let (mut rows, mut incomplete) = (0, 0);
    for r in &s.records {
        let Record::Cat062(c) = &r.record else {
            continue;
        };
        let (Some(tod), Some(n), Some(p), Some(v)) =
            (c.time, c.track_number, c.cartesian, c.velocity)
        else {
            incomplete += 1;
            continue;
        };
        let t = clock.at(tod.seconds());
        let ((x, y), (vx, vy)) = (p.metres(), v.mps());
        text.push_str(&format!("{t},{n},{x},{vx},{y},{vy},confirmed\n"));
        rows += 1;
    }
    (text, rows, incomplete)
}

fn quantise(what: &str, v: f64, lsb: f64, max: f64) -> Result<i32, String> {
    let q = (v / lsb).round();
    if !(q.is_finite() && q.abs() <= max) {
        return Err(format!("{what} {v} is outside what CAT062 holds"));
    }
    // |q| ≤ max < 2^31, checked above.
    #[allow(clippy::cast_possible_truncation)]
    Ok(q as i32)
}

/// The confirmed rows of the tracks CSV at `path` as CAT062 records from `source`, in
/// time order: I062/070 `t mod 86 400` (1/128 s), /040 the track (a number 0–65 535),
/// /100 x, y (0.5 m), /185 vx, vy (0.25 m/s).
///
/// # Errors
/// [`IoError::Score`] for a tracks CSV `argus score` would refuse; [`IoError::Encode`]
/// for a track name that is not a number 0–65 535 or a value CAT062 cannot hold.
pub fn encode_tracks(path: &Path, source: DataSource) -> Result<Encoded, IoError> {
    let histories = argus_score::read_tracks(path)?;
    let mut rows = Vec::new();
    for h in &histories {
        let number: u16 = h.name().parse().map_err(|_| {
            IoError::Encode(format!(
                "{}: track '{}' is not a CAT062 track number (0–65 535)",
                path.display(),
                h.name()
            ))
        })?;
        rows.extend(
            h.rows()
                .iter()
                .filter(|r| r.confirmed)
                .map(|r| (number, *r)),
        );
    }
    rows.sort_by(|a, b| a.1.t.total_cmp(&b.1.t));
    let item = ItemId {
        cat: 62,
        name: "070",
    };
    let bad = |n: u16, t: f64, e: String| {
        IoError::Encode(format!("{}: track {n} at t = {t} s: {e}", path.display()))
    };
    let mut records = Vec::with_capacity(rows.len());
    for (n, r) in &rows {
        if r.t < 0.0 {
            return Err(bad(*n, r.t, "ASTERIX times of day need t ≥ 0".into()));
        }
        let time = TimeOfDay::from_seconds(item, r.t.rem_euclid(DAY))
            .map_err(|e| bad(*n, r.t, e.to_string()))?;
        // I062/100: 24-bit two's complement; I062/185: 16-bit.
        let pos = |w, v| quantise(w, v, 0.5, f64::from((1 << 23) - 1)).map_err(|e| bad(*n, r.t, e));
        let vel = |w, v| {
            quantise(w, v, 0.25, f64::from(i16::MAX))
                .map(|q| i16::try_from(q).unwrap_or(0))
                .map_err(|e| bad(*n, r.t, e))
        };
        records.push((
            r.t,
            Cat062 {
                source: Some(source),
                time: Some(time),
                cartesian: Some(Cartesian062 {
                    x: pos("x", r.x)?,
                    y: pos("y", r.y)?,
                }),
                velocity: Some(Velocity062 {
                    vx: vel("vx", r.vx)?,
                    vy: vel("vy", r.vy)?,
                }),
                track_number: Some(*n),
                ..Cat062::default()
            },
        ));
    }
    let mut out = Encoded::default();
    for chunk in records.chunks(RECORDS_PER_BLOCK) {
        let block: Vec<Cat062> = chunk.iter().map(|(_, c)| *c).collect();
        let mut bytes = Vec::new();
        argus_asterix::encode_block(&block, &mut bytes)
            .map_err(|e| IoError::Encode(format!("CAT062 block: {e}")))?;
        out.reports += block.len();
        out.datagrams.push((chunk[chunk.len() - 1].0, bytes));
    }
    Ok(out)
}
