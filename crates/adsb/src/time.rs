//! Timestamps: epoch numbers or ISO-8601 strings, to seconds since the epoch (UTC).

/// The unit of a numeric timestamp.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EpochUnit {
    /// Seconds since 1970-01-01 UTC (OpenSky's state vectors and CSV exports).
    #[default]
    Seconds,
    /// Milliseconds since 1970-01-01 UTC (pandas' `to_json` default, used by the
    /// `traffic` package's JSON samples).
    Milliseconds,
}

impl EpochUnit {
    /// A numeric timestamp in seconds.
    #[must_use]
    pub fn to_seconds(self, value: f64) -> f64 {
        match self {
            Self::Seconds => value,
            Self::Milliseconds => value / 1000.0,
        }
    }
}

/// Parses `YYYY-MM-DD[T ]hh:mm:ss[.fff][Z|±hh:mm|±hhmm]` to seconds since the epoch.
/// No offset means UTC (the `traffic` package's convention for naive timestamps).
pub(crate) fn parse_iso8601(s: &str) -> Result<f64, String> {
    let bad = || format!("'{s}' is not an ISO-8601 date-time (YYYY-MM-DDThh:mm:ss[.f][Z|±hh:mm])");
    let b = s.trim().as_bytes();
    if b.len() < 19
        || b[4] != b'-'
        || b[7] != b'-'
        || !(b[10] == b'T' || b[10] == b' ')
        || b[13] != b':'
        || b[16] != b':'
    {
        return Err(bad());
    }
    let num = |r: std::ops::Range<usize>| -> Result<i64, String> {
        let t = std::str::from_utf8(&b[r]).map_err(|_| bad())?;
        if t.bytes().all(|c| c.is_ascii_digit()) {
            t.parse().map_err(|_| bad())
        } else {
            Err(bad())
        }
    };
    let (y, mo, d) = (num(0..4)?, num(5..7)?, num(8..10)?);
    let (h, mi, sec) = (num(11..13)?, num(14..16)?, num(17..19)?);
    if !(1..=12).contains(&mo) || !(1..=31).contains(&d) || h > 23 || mi > 59 || sec > 60 {
        return Err(bad());
    }
    let mut i = 19;
    let mut frac = 0.0;
    if i < b.len() && b[i] == b'.' {
        let start = i + 1;
        i = start;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        if i == start {
            return Err(bad());
        }
        let t = std::str::from_utf8(&b[start - 1..i]).map_err(|_| bad())?;
        frac = format!("0{t}").parse::<f64>().map_err(|_| bad())?;
    }
    let offset = match &b[i..] {
        [] | [b'Z'] | [b'z'] => 0,
        [sign @ (b'+' | b'-'), rest @ ..] => {
            let digits: Vec<u8> = rest.iter().copied().filter(|c| *c != b':').collect();
            if digits.len() != 4 || !digits.iter().all(u8::is_ascii_digit) || rest.len() > 5 {
                return Err(bad());
            }
            let v = |k: usize| i64::from(digits[k] - b'0');
            let minutes = (v(0) * 10 + v(1)) * 60 + v(2) * 10 + v(3);
            if *sign == b'+' {
                minutes * 60
            } else {
                -minutes * 60
            }
        }
        _ => return Err(bad()),
    };
    let days = days_from_civil(y, mo, d);
    let secs = days * 86_400 + h * 3600 + mi * 60 + sec - offset;
    // Exact for any date-time this format can write (|secs| < 2^53).
    #[allow(clippy::cast_precision_loss)]
    Ok(secs as f64 + frac)
}

/// Days from 1970-01-01 to the proleptic Gregorian date `y-m-d` (H. Hinnant's
/// `days_from_civil` algorithm, public domain; the formula, written here anew).
fn days_from_civil(y: i64, m: i64, d: i64) -> i64 {
    let y = if m <= 2 { y - 1 } else { y };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let mp = (m + 9) % 12;
    let doy = (153 * mp + 2) / 5 + d - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn iso_forms() {
        // 2021-10-07T13:33:00Z is 1633613580 (the first timestamp of the committed
        // extract, written by pandas as epoch seconds).
        for s in [
            "2021-10-07T13:33:00Z",
            "2021-10-07 13:33:00+00:00",
            "2021-10-07T15:33:00+02:00",
            "2021-10-07 13:33:00",
            "2021-10-07T13:33:00+0000",
        ] {
            assert_eq!(parse_iso8601(s), Ok(1_633_613_580.0), "{s}");
        }
        let f = parse_iso8601("1970-01-01T00:00:00.25Z").unwrap();
        assert!((f - 0.25).abs() < 1e-12);
        assert_eq!(parse_iso8601("2000-03-01T00:00:00Z"), Ok(951_868_800.0));
        for s in [
            "2021-13-07T13:33:00Z",
            "2021-10-07",
            "yesterday",
            "2021-10-07T13:33:00+2",
            "2021-10-07T13:33:00.",
        ] {
            assert!(parse_iso8601(s).is_err(), "{s}");
        }
    }
}
