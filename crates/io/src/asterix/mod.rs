//! ASTERIX in and out of the `argus` command (`docs/FORMATS.md`, "ASTERIX"): a file's
//! content known by its first bytes (pcap, pcapng, raw ASTERIX blocks, else CSV), the
//! ASTERIX records of a capture's UDP payloads or of a block file ([`read`]), CAT048
//! and CAT034 turned into plots and sector messages ([`plots`]), plots written as CAT048
//! and CAT034 ([`encode`]), CAT062 system tracks to and from the tracks CSV ([`tracks`]).
//!
//! Sensor numbers and ASTERIX data sources map one way for every command that has no
//! configuration: `sensor = 256 · SAC + SIC` (so sensor 1 is SAC 0, SIC 1). `argus track`
//! matches a `[[sensor]]` by its `sac`, `sic` keys, or by that mapping of its `id`.

pub mod adsb;
pub mod encode;
pub mod plots;
pub mod tracks;

use std::path::Path;

use argus_asterix::{DataSource, Record, Skip};
use argus_capture::Skipped;

use crate::error::IoError;

/// What a file holds, by content.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Content {
    /// A pcap or pcapng capture.
    Capture,
    /// Concatenated ASTERIX data blocks.
    Blocks,
    /// Anything else: read as CSV.
    Csv,
}

/// The ASTERIX categories decoded.
const CATEGORIES: [u8; 4] = [21, 34, 48, 62];

impl Content {
    /// The content of `bytes`: the capture magics, else a first ASTERIX block of a known
    /// category whose length fits the file and which decodes to at least one record, else
    /// CSV (whose header starts with a column name).
    pub(crate) fn sniff(bytes: &[u8]) -> Self {
        if argus_capture::Format::sniff(bytes) != argus_capture::Format::Other {
            return Self::Capture;
        }
        if let [cat, hi, lo, ..] = bytes
            && CATEGORIES.contains(cat)
        {
            let len = usize::from(u16::from_be_bytes([*hi, *lo]));
            if (3..=bytes.len()).contains(&len)
                && !argus_asterix::decode(&bytes[..len]).records.is_empty()
            {
                return Self::Blocks;
            }
        }
        Self::Csv
    }
}

/// One decoded record and where it came from.
#[derive(Debug, Clone)]
pub struct Timed {
    /// The record.
    pub record: Record,
    /// 1-based number among the file's decoded records (named in errors).
    pub number: u64,
}

/// A file's ASTERIX records, and what was skipped on the way.
#[derive(Debug, Clone, Default)]
pub struct Surveillance {
    /// The records, in file order.
    pub records: Vec<Timed>,
    /// Packets of a capture without a UDP payload.
    pub packets_skipped: Vec<Skipped>,
    /// ASTERIX blocks or records skipped (datagram index, the skip).
    pub asterix_skipped: Vec<(usize, Skip)>,
}

impl Surveillance {
    /// One line telling what was skipped (`None` when nothing was): the counts and the
    /// first reason of each kind.
    pub fn skipped_note(&self, path: &Path) -> Option<String> {
        if self.packets_skipped.is_empty() && self.asterix_skipped.is_empty() {
            return None;
        }
        let mut s = format!("{}: skipped", path.display());
        if let Some(first) = self.packets_skipped.first() {
            s.push_str(&format!(
                " {} packets (first: packet {} at byte {}: {})",
                self.packets_skipped.len(),
                first.packet,
                first.offset,
                first.reason
            ));
        }
        if let Some((d, first)) = self.asterix_skipped.first() {
            if !self.packets_skipped.is_empty() {
                s.push(',');
            }
            s.push_str(&format!(
                " {} ASTERIX blocks or records (first: datagram {d}: {})",
                self.asterix_skipped.len(),
                first.error
            ));
        }
        Some(s)
    }
}

/// Reads `path` as ASTERIX when its content is a capture or block file (`None`: CSV).
///
/// # Errors
/// [`IoError::Io`]; [`IoError::Capture`] for a capture whose header or link type
/// cannot be read.
pub fn read(path: &Path) -> Result<Option<Surveillance>, IoError> {
    use std::io::Read as _;
    // The content is known from the first block at most (LEN ≤ 65 535): a CSV file is
    // not read further here, so that `argus track` still streams it.
    let mut file = std::fs::File::open(path).map_err(|e| IoError::io(path, e))?;
    let mut head = Vec::new();
    (&mut file)
        .take(SNIFF_BYTES)
        .read_to_end(&mut head)
        .map_err(|e| IoError::io(path, e))?;
    if Content::sniff(&head) == Content::Csv {
        return Ok(None);
    }
    file.read_to_end(&mut head)
        .map_err(|e| IoError::io(path, e))?;
    read_bytes(&head, path)
}

/// Bytes enough to know a file's content: one whole ASTERIX block.
const SNIFF_BYTES: u64 = 65_536;

/// [`read`] on bytes in memory; `path` names them in errors.
///
/// # Errors
/// As [`read`].
pub(crate) fn read_bytes(bytes: &[u8], path: &Path) -> Result<Option<Surveillance>, IoError> {
    let mut out = Surveillance::default();
    // The capture times are not used: I048/140 and I034/030 give each record's time.
    let push = |datagram: usize, payload: &[u8], out: &mut Surveillance| {
        let d = argus_asterix::decode(payload);
        for record in d.records {
            let number = out.records.len() as u64 + 1;
            out.records.push(Timed { record, number });
        }
        out.asterix_skipped
            .extend(d.skipped.into_iter().map(|s| (datagram, s)));
    };
    match Content::sniff(bytes) {
        Content::Csv => return Ok(None),
        Content::Blocks => push(0, bytes, &mut out),
        Content::Capture => {
            let c = argus_capture::read(bytes).map_err(|source| IoError::Capture {
                file: path.to_path_buf(),
                source,
            })?;
            for (k, d) in c.datagrams.iter().enumerate() {
                push(k, d.payload, &mut out);
            }
            out.packets_skipped = c.skipped;
        }
    }
    Ok(Some(out))
}

/// The sensor number of a data source without a configuration: `256 · SAC + SIC`.
pub fn sensor_of(source: DataSource) -> u32 {
    u32::from(source.sac) * 256 + u32::from(source.sic)
}

/// The data source of a sensor number without a configuration (the inverse of
/// [`sensor_of`]); `None` above 65 535.
pub(crate) fn source_of(sensor: u32) -> Option<DataSource> {
    let v = u16::try_from(sensor).ok()?;
    let [sac, sic] = v.to_be_bytes();
    Some(DataSource { sac, sic })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn content_is_known_by_its_first_bytes() {
        // A one-record CAT034 block: FSPEC 0x80 (I034/010 only), SAC 0, SIC 1.
        let block = [34u8, 0, 6, 0x80, 0, 1];
        assert_eq!(Content::sniff(&block), Content::Blocks);
        // CSV, also with a quoted header (its first byte is '"', 34, CAT034's number):
        // the LEN it would give does not decode to a record.
        assert_eq!(Content::sniff(b"t,sensor,range,azimuth\n"), Content::Csv);
        assert_eq!(Content::sniff(b"\"t\",\"sensor\"\n0,1\n"), Content::Csv);
        // A block header whose LEN runs past the file, or below 3: not blocks.
        assert_eq!(Content::sniff(&[48u8, 0, 9, 0x80]), Content::Csv);
        assert_eq!(Content::sniff(&[48u8, 0, 2]), Content::Csv);
        assert_eq!(
            Content::sniff(&0xa1b2_c3d4u32.to_le_bytes()),
            Content::Capture
        );
        assert_eq!(Content::sniff(&[]), Content::Csv);
    }

    #[test]
    fn sensors_and_data_sources_map_both_ways() {
        assert_eq!(sensor_of(DataSource { sac: 0, sic: 1 }), 1);
        assert_eq!(sensor_of(DataSource { sac: 25, sic: 12 }), 25 * 256 + 12);
        for id in [0, 1, 255, 256, 6412, 65_535] {
            assert_eq!(source_of(id).map(sensor_of), Some(id));
        }
        assert_eq!(source_of(65_536), None);
    }
}
