//! Record framing: the FSPEC (FX-chained presence bits) and the UAP-driven walk
//! over a record's items, plus the matching record writer.

use crate::error::{DecodeError, EncodeError};
use crate::uap::{LenError, Uap, item_len};

/// A category whose records this crate decodes and encodes.
pub trait Category: Sized + Default {
    /// The category's UAP.
    const UAP: Uap;

    /// Decodes the item at `frn` (1-based) from exactly its bytes. Items the
    /// type does not interpret return `Ok(())` (they were skipped by length).
    ///
    /// # Errors
    /// A description of what breaks the item's layout.
    fn decode_item(&mut self, frn: usize, bytes: &[u8]) -> Result<(), &'static str>;

    /// Writes the record's items in FRN order.
    ///
    /// # Errors
    /// [`EncodeError`] if a value does not fit its item.
    fn encode_items(&self, w: &mut RecordWriter) -> Result<(), EncodeError>;
}

/// A record that failed: the error, and where the next record starts if the
/// framing survived (the failure was in an item's value, not its length).
#[derive(Debug)]
pub(crate) struct RecordFail {
    pub(crate) error: DecodeError,
    pub(crate) resume: Option<usize>,
}

/// The longest FSPEC any UAP here has (CAT062: 35 FRNs → 5 octets); sized with room.
const FSPEC_CAP: usize = 8;

/// Decodes the record starting at `pos` in `data`, not reading at or past
/// `end` (the block's end). Offsets are absolute in `data`. Returns the
/// record and the offset just past it.
pub(crate) fn decode_record<C: Category>(
    data: &[u8],
    pos: usize,
    end: usize,
) -> Result<(C, usize), RecordFail> {
    let uap = C::UAP;
    let lost = |error| RecordFail {
        error,
        resume: None,
    };
    // FSPEC: at most `max_fspec` octets, never past the block.
    let max = uap.max_fspec().min(FSPEC_CAP);
    let mut fspec = [0u8; FSPEC_CAP];
    let mut n = 0;
    loop {
        if n == max || pos + n >= end {
            return Err(lost(DecodeError::FspecUnterminated {
                offset: pos,
                cat: uap.cat,
                max,
            }));
        }
        fspec[n] = data[pos + n];
        n += 1;
        if fspec[n - 1] & 1 == 0 {
            break;
        }
    }
    if fspec[..n].iter().all(|&b| b & 0xfe == 0) {
        // Length known (the FSPEC alone): the next record can still be framed.
        return Err(RecordFail {
            error: DecodeError::EmptyRecord {
                offset: pos,
                cat: uap.cat,
            },
            resume: Some(pos + n),
        });
    }
    let mut cur = pos + n;
    let mut record = C::default();
    let mut value_error = None;
    for (octet, &bits) in fspec[..n].iter().enumerate() {
        for bit in 0..7 {
            if bits & (0x80 >> bit) == 0 {
                continue;
            }
            let frn = octet * 7 + bit + 1;
            let Some((name, format)) = uap.slot(frn) else {
                return Err(lost(DecodeError::UndefinedFrn {
                    offset: pos,
                    cat: uap.cat,
                    frn,
                }));
            };
            let item = uap.id(name);
            let rest = &data[cur..end];
            let len = item_len(format, rest).map_err(|e| {
                lost(match e {
                    LenError::Short { need } => DecodeError::ItemOverrun {
                        offset: cur,
                        item,
                        need,
                        have: rest.len(),
                    },
                    LenError::Invalid(what) => DecodeError::InvalidItem {
                        offset: cur,
                        item,
                        what,
                    },
                })
            })?;
            if let Err(what) = record.decode_item(frn, &rest[..len])
                && value_error.is_none()
            {
                value_error = Some(DecodeError::InvalidItem {
                    offset: cur,
                    item,
                    what,
                });
            }
            cur += len;
        }
    }
    match value_error {
        None => Ok((record, cur)),
        Some(error) => Err(RecordFail {
            error,
            resume: Some(cur),
        }),
    }
}

/// Builds one record: items are added in increasing FRN order, then
/// [`RecordWriter::finish`] writes FSPEC and items.
#[derive(Debug)]
pub struct RecordWriter {
    uap: Uap,
    fspec: [u8; FSPEC_CAP],
    last_frn: usize,
    body: Vec<u8>,
}

impl RecordWriter {
    /// An empty record of the given UAP.
    #[must_use]
    pub fn new(uap: Uap) -> Self {
        Self {
            uap,
            fspec: [0; FSPEC_CAP],
            last_frn: 0,
            body: Vec::with_capacity(64),
        }
    }

    /// Appends the item at `frn` with its encoded bytes.
    ///
    /// # Errors
    /// [`EncodeError::FrnOrder`] if `frn` is not above the last one or not in the UAP.
    pub fn put(&mut self, frn: usize, bytes: &[u8]) -> Result<(), EncodeError> {
        if frn <= self.last_frn || self.uap.slot(frn).is_none() || frn > FSPEC_CAP * 7 {
            return Err(EncodeError::FrnOrder {
                cat: self.uap.cat,
                frn,
            });
        }
        let i = frn - 1;
        self.fspec[i / 7] |= 0x80 >> (i % 7);
        self.last_frn = frn;
        self.body.extend_from_slice(bytes);
        Ok(())
    }

    /// Writes FSPEC (FX set on all but the last non-empty octet) and the items to `out`.
    pub fn finish(self, out: &mut Vec<u8>) {
        let n = self
            .fspec
            .iter()
            .rposition(|&b| b != 0)
            .map_or(1, |i| i + 1);
        for (i, &b) in self.fspec[..n].iter().enumerate() {
            out.push(if i + 1 < n { b | 1 } else { b });
        }
        out.extend_from_slice(&self.body);
    }
}
