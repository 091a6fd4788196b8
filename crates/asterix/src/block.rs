//! Data-block framing (CAT octet, 16-bit LEN, records) and the decode loop
//! that keeps going after a bad record where the framing allows.

use crate::cat021::Cat021;
use crate::cat034::Cat034;
use crate::cat048::Cat048;
use crate::cat062::Cat062;
use crate::error::{DecodeError, EncodeError};
use crate::record::{Category, RecordWriter, decode_record};

/// A decoded record of any supported category.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Record {
    /// A CAT048 monoradar target report.
    Cat048(Cat048),
    /// A CAT034 monoradar service message.
    Cat034(Cat034),
    /// A CAT021 ADS-B report.
    Cat021(Cat021),
    /// A CAT062 system track.
    Cat062(Cat062),
}

/// A skipped block or record: the typed reason and how many bytes were lost.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Skip {
    /// Why.
    pub error: DecodeError,
    /// Bytes skipped because of it (0 when the bytes were still decoded, e.g. a
    /// block LEN that overstates the input).
    pub dropped: usize,
}

/// What [`decode`] found: the good records in input order, and the skips.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Decoded {
    /// Records decoded.
    pub records: Vec<Record>,
    /// Blocks or records skipped, each with its reason.
    pub skipped: Vec<Skip>,
}

/// Decodes a concatenation of ASTERIX data blocks (a raw block file, or one
/// UDP payload). Never panics and always terminates: each step advances.
///
/// - A block of an unknown category is skipped by its LEN.
/// - A LEN below 3 loses the framing: the rest of the input is dropped.
/// - A LEN past the end of the input: the records present are decoded and the
///   lie is reported.
/// - A record whose item lengths cannot be determined (FSPEC chain, undefined
///   FRN, item past the block) loses the record framing: the rest of that
///   block is dropped, the next block is decoded. A record whose framing holds
///   but a value is invalid is skipped alone.
#[must_use]
pub fn decode(data: &[u8]) -> Decoded {
    let mut out = Decoded::default();
    let mut pos = 0;
    while pos < data.len() {
        let have = data.len() - pos;
        if have < 3 {
            out.skipped.push(Skip {
                error: DecodeError::TruncatedHeader { offset: pos, have },
                dropped: have,
            });
            break;
        }
        let cat = data[pos];
        let declared = usize::from(u16::from_be_bytes([data[pos + 1], data[pos + 2]]));
        if declared < 3 {
            out.skipped.push(Skip {
                error: DecodeError::BlockLengthTooShort {
                    offset: pos,
                    declared,
                },
                dropped: have,
            });
            break;
        }
        let end = if declared > have {
            out.skipped.push(Skip {
                error: DecodeError::BlockLengthExceedsInput {
                    offset: pos,
                    declared,
                    available: have,
                },
                dropped: 0,
            });
            data.len()
        } else {
            pos + declared
        };
        match cat {
            48 => decode_records(data, pos + 3, end, &mut out, Record::Cat048),
            34 => decode_records(data, pos + 3, end, &mut out, Record::Cat034),
            21 => decode_records(data, pos + 3, end, &mut out, Record::Cat021),
            62 => decode_records(data, pos + 3, end, &mut out, Record::Cat062),
            _ => out.skipped.push(Skip {
                error: DecodeError::UnknownCategory { offset: pos, cat },
                dropped: end - pos,
            }),
        }
        pos = end;
    }
    out
}

/// Decodes the records of one block into `out` (typed fast path).
fn decode_records<C: Category>(
    data: &[u8],
    start: usize,
    end: usize,
    out: &mut Decoded,
    wrap: fn(C) -> Record,
) {
    let mut pos = start;
    while pos < end {
        match decode_record::<C>(data, pos, end) {
            Ok((r, next)) => {
                out.records.push(wrap(r));
                pos = next;
            }
            Err(fail) => match fail.resume {
                Some(next) => {
                    out.skipped.push(Skip {
                        error: fail.error,
                        dropped: next - pos,
                    });
                    pos = next;
                }
                None => {
                    out.skipped.push(Skip {
                        error: fail.error,
                        dropped: end - pos,
                    });
                    return;
                }
            },
        }
    }
}

/// Encodes `records` as one data block of category `C`.
///
/// # Errors
/// [`EncodeError`] if a value does not fit, or the block exceeds 65 535 bytes.
pub fn encode_block<C: Category>(records: &[C], out: &mut Vec<u8>) -> Result<(), EncodeError> {
    let start = out.len();
    out.extend_from_slice(&[C::UAP.cat, 0, 0]);
    for r in records {
        let mut w = RecordWriter::new(C::UAP);
        r.encode_items(&mut w)?;
        w.finish(out);
    }
    let len = out.len() - start;
    let Ok(len16) = u16::try_from(len) else {
        out.truncate(start);
        return Err(EncodeError::BlockTooLong {
            cat: C::UAP.cat,
            len,
        });
    };
    out[start + 1..start + 3].copy_from_slice(&len16.to_be_bytes());
    Ok(())
}
