//! Reading state vectors from CSV and JSON (records or JSON Lines), plain or gzipped.

use std::fs::File;
use std::io::{BufReader, Read};
use std::path::Path;

use serde_json::Value;

use crate::error::{AdsbError, Location};
use crate::record::StateVector;
use crate::time::{EpochUnit, parse_iso8601};

/// The input format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// CSV with a header naming the columns.
    Csv,
    /// A JSON array of records, or JSON Lines (one record per line).
    Json,
}

impl Format {
    /// The unit of numeric timestamps when none is given: seconds for CSV, and
    /// milliseconds for JSON (pandas' `to_json` default, as in the `traffic` samples).
    #[must_use]
    pub fn default_epoch_unit(self) -> EpochUnit {
        match self {
            Self::Csv => EpochUnit::Seconds,
            Self::Json => EpochUnit::Milliseconds,
        }
    }
}

/// Reads `path`: the format from the extension (`.csv`, `.json`, `.jsonl`), each
/// optionally followed by `.gz`; numeric timestamps in `epoch_unit`, or the
/// format's default ([`Format::default_epoch_unit`]).
///
/// # Errors
/// [`AdsbError::Io`] when the file cannot be read or its extension is unknown, and
/// the errors of [`read_csv`] / [`read_json`].
pub fn read_path(
    path: &Path,
    epoch_unit: Option<EpochUnit>,
) -> Result<Vec<StateVector>, AdsbError> {
    let io = |source| AdsbError::Io {
        path: path.to_path_buf(),
        source,
    };
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or_default()
        .to_ascii_lowercase();
    let (stem, gz) = match name.strip_suffix(".gz") {
        Some(stem) => (stem.to_owned(), true),
        None => (name.clone(), false),
    };
    let format = if stem.ends_with(".csv") {
        Format::Csv
    } else if stem.ends_with(".json") || stem.ends_with(".jsonl") {
        Format::Json
    } else {
        return Err(io(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "unknown extension (expected .csv, .json or .jsonl, optionally .gz)",
        )));
    };
    let file = BufReader::new(File::open(path).map_err(io)?);
    let reader: Box<dyn Read> = if gz {
        Box::new(flate2::read::GzDecoder::new(file))
    } else {
        Box::new(file)
    };
    let unit = epoch_unit.unwrap_or(format.default_epoch_unit());
    match format {
        Format::Csv => read_csv(reader, unit),
        Format::Json => read_json(reader, unit),
    }
}

/// The columns read; others are ignored. The first four are required.
const COLUMNS: [&str; 10] = [
    "timestamp",
    "icao24",
    "latitude",
    "longitude",
    "altitude",
    "groundspeed",
    "track",
    "vertical_rate",
    "callsign",
    "onground",
];

/// Reads CSV with a header. Empty fields and `NaN` are missing values; `timestamp`
/// is a number in `epoch_unit` or an ISO-8601 string.
///
/// # Errors
/// [`AdsbError::MissingColumn`] for a missing required column, [`AdsbError::Field`]
/// naming the line and field of a value that cannot be read or is out of its
/// domain, [`AdsbError::Syntax`] for malformed CSV.
pub fn read_csv<R: Read>(reader: R, epoch_unit: EpochUnit) -> Result<Vec<StateVector>, AdsbError> {
    let mut rdr = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(reader);
    let syntax = |e: csv::Error| AdsbError::Syntax {
        at: Location::Line(e.position().map_or(1, csv::Position::line)),
        message: e.to_string(),
    };
    let header = rdr.headers().map_err(syntax)?.clone();
    let index: Vec<Option<usize>> = COLUMNS
        .iter()
        .map(|c| header.iter().position(|h| h == *c))
        .collect();
    for (i, c) in COLUMNS.iter().enumerate().take(4) {
        if index[i].is_none() {
            return Err(AdsbError::MissingColumn { column: c });
        }
    }
    let mut out = Vec::new();
    let mut record = csv::StringRecord::new();
    while rdr.read_record(&mut record).map_err(syntax)? {
        let at = Location::Line(record.position().map_or(0, csv::Position::line));
        let get = |k: usize| {
            index[k]
                .and_then(|i| record.get(i))
                .filter(|s| !s.is_empty())
        };
        let field = Fields { at, epoch_unit };
        out.push(StateVector {
            time: field.time(get(0).map(Text))?,
            icao24: field.icao24(get(1).map(Text))?,
            latitude: field.number(get(2).map(Text), "latitude", -90.0, 90.0)?,
            longitude: field.number(get(3).map(Text), "longitude", -180.0, 180.0)?,
            altitude_ft: field.number(get(4).map(Text), "altitude", f64::MIN, f64::MAX)?,
            groundspeed_kt: field.number(get(5).map(Text), "groundspeed", 0.0, f64::MAX)?,
            track_deg: field.number(get(6).map(Text), "track", -360.0, 360.0)?,
            vertical_rate_fpm: field.number(
                get(7).map(Text),
                "vertical_rate",
                f64::MIN,
                f64::MAX,
            )?,
            callsign: get(8).map(str::to_owned),
            onground: field.boolean(get(9).map(Text))?,
        });
    }
    Ok(out)
}

/// Reads a JSON array of records or JSON Lines. `null` is a missing value;
/// `timestamp` is a number in `epoch_unit` or an ISO-8601 string.
///
/// # Errors
/// [`AdsbError::Field`] naming the record and field of a value that cannot be read
/// or is out of its domain, [`AdsbError::Syntax`] for malformed JSON.
pub fn read_json<R: Read>(
    mut reader: R,
    epoch_unit: EpochUnit,
) -> Result<Vec<StateVector>, AdsbError> {
    let mut text = String::new();
    reader
        .read_to_string(&mut text)
        .map_err(|e| AdsbError::Syntax {
            at: Location::Record(0),
            message: e.to_string(),
        })?;
    let records: Vec<Value> = if text.trim_start().starts_with('[') {
        serde_json::from_str(&text).map_err(|e| AdsbError::Syntax {
            at: Location::Record(0),
            message: e.to_string(),
        })?
    } else {
        text.lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty())
            .map(|(i, l)| {
                serde_json::from_str(l).map_err(|e| AdsbError::Syntax {
                    at: Location::Record(i),
                    message: e.to_string(),
                })
            })
            .collect::<Result<_, _>>()?
    };
    records
        .iter()
        .enumerate()
        .map(|(i, v)| json_record(v, Location::Record(i), epoch_unit))
        .collect()
}

fn json_record(v: &Value, at: Location, epoch_unit: EpochUnit) -> Result<StateVector, AdsbError> {
    let obj = v.as_object().ok_or_else(|| AdsbError::Syntax {
        at,
        message: "a record must be a JSON object".to_owned(),
    })?;
    let get = |k: &str| obj.get(k).filter(|v| !v.is_null()).map(Json);
    let field = Fields { at, epoch_unit };
    let callsign = match obj.get("callsign") {
        None | Some(Value::Null) => None,
        Some(Value::String(s)) => Some(s.trim().to_owned()).filter(|s| !s.is_empty()),
        Some(_) => return Err(field.err("callsign", "must be a string".to_owned())),
    };
    Ok(StateVector {
        time: field.time(get("timestamp"))?,
        icao24: field.icao24(get("icao24"))?,
        latitude: field.number(get("latitude"), "latitude", -90.0, 90.0)?,
        longitude: field.number(get("longitude"), "longitude", -180.0, 180.0)?,
        altitude_ft: field.number(get("altitude"), "altitude", f64::MIN, f64::MAX)?,
        groundspeed_kt: field.number(get("groundspeed"), "groundspeed", 0.0, f64::MAX)?,
        track_deg: field.number(get("track"), "track", -360.0, 360.0)?,
        vertical_rate_fpm: field.number(
            get("vertical_rate"),
            "vertical_rate",
            f64::MIN,
            f64::MAX,
        )?,
        callsign,
        onground: field.boolean(get("onground"))?,
    })
}

/// A CSV field's text.
struct Text<'a>(&'a str);
/// A JSON value.
struct Json<'a>(&'a Value);

/// A field value of either input.
trait FieldValue {
    /// As a number: `Ok(None)` for NaN, `Err` with a message for anything else.
    fn number(&self) -> Result<Option<f64>, String>;
    /// As text, when it is text.
    fn text(&self) -> Option<&str>;
    /// As a boolean.
    fn boolean(&self) -> Result<bool, String>;
}

impl FieldValue for Text<'_> {
    fn number(&self) -> Result<Option<f64>, String> {
        match self.0.parse::<f64>() {
            Ok(v) if v.is_nan() => Ok(None),
            Ok(v) if v.is_finite() => Ok(Some(v)),
            _ => Err(format!("'{}' is not a finite number", self.0)),
        }
    }
    fn text(&self) -> Option<&str> {
        Some(self.0)
    }
    fn boolean(&self) -> Result<bool, String> {
        match self.0.to_ascii_lowercase().as_str() {
            "true" | "1" => Ok(true),
            "false" | "0" => Ok(false),
            _ => Err(format!("'{}' is not a boolean (true/false)", self.0)),
        }
    }
}

impl FieldValue for Json<'_> {
    fn number(&self) -> Result<Option<f64>, String> {
        self.0
            .as_f64()
            .map(Some)
            .ok_or_else(|| format!("{} is not a number", self.0))
    }
    fn text(&self) -> Option<&str> {
        self.0.as_str()
    }
    fn boolean(&self) -> Result<bool, String> {
        self.0
            .as_bool()
            .ok_or_else(|| format!("{} is not a boolean", self.0))
    }
}

/// Field conversions that name the record and field on error.
struct Fields {
    at: Location,
    epoch_unit: EpochUnit,
}

impl Fields {
    fn err(&self, field: &'static str, message: String) -> AdsbError {
        AdsbError::Field {
            at: self.at,
            field,
            message,
        }
    }

    fn time(&self, v: Option<impl FieldValue>) -> Result<f64, AdsbError> {
        let v = v.ok_or_else(|| self.err("timestamp", "missing".to_owned()))?;
        let numeric = v.number();
        match (numeric, v.text()) {
            (Ok(Some(x)), _) => Ok(self.epoch_unit.to_seconds(x)),
            (_, Some(s)) => parse_iso8601(s).map_err(|m| self.err("timestamp", m)),
            (Ok(None), None) => Err(self.err("timestamp", "missing".to_owned())),
            (Err(m), None) => Err(self.err("timestamp", m)),
        }
    }

    fn icao24(&self, v: Option<impl FieldValue>) -> Result<String, AdsbError> {
        let v = v.ok_or_else(|| self.err("icao24", "missing".to_owned()))?;
        let s = v
            .text()
            .ok_or_else(|| self.err("icao24", "must be text (hex digits)".to_owned()))?;
        let s = s.trim().to_ascii_lowercase();
        if s.is_empty() || s.len() > 6 || !s.bytes().all(|c| c.is_ascii_hexdigit()) {
            return Err(self.err("icao24", format!("'{s}' is not a 24-bit hex address")));
        }
        Ok(s)
    }

    fn number(
        &self,
        v: Option<impl FieldValue>,
        field: &'static str,
        lo: f64,
        hi: f64,
    ) -> Result<Option<f64>, AdsbError> {
        let Some(v) = v else { return Ok(None) };
        let x = v.number().map_err(|m| self.err(field, m))?;
        match x {
            Some(x) if !(lo..=hi).contains(&x) => {
                Err(self.err(field, format!("{x} is outside [{lo}, {hi}]")))
            }
            x => Ok(x),
        }
    }

    fn boolean(&self, v: Option<impl FieldValue>) -> Result<Option<bool>, AdsbError> {
        v.map(|v| v.boolean().map_err(|m| self.err("onground", m)))
            .transpose()
    }
}
