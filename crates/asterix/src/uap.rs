//! User Application Profiles (UAPs) and the item length rules they imply.
//!
//! ASTERIX records carry no per-item length: each item's length follows from
//! its format in the category's UAP, so skipping an item the decoder does not
//! interpret needs the format of every FRN. The formats (EUROCONTROL ASTERIX
//! Part 1, section 4.3):
//! - fixed: `n` octets;
//! - extended: a primary part then extensions, each ending in an FX bit (LSB)
//!   that announces the next;
//! - repetitive: a REP octet then REP × `n` octets;
//! - explicit: a LEN octet that counts itself (SP and RE fields);
//! - compound: a primary subfield (an FX chain of presence bits, 7 per octet)
//!   then the present subfields, each with its own format.

use crate::error::ItemId;

/// The length rule of an item or of a compound subfield.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// `n` octets.
    Fixed(usize),
    /// A primary part of `first` octets, then extensions of `ext` octets while
    /// the last octet's LSB (FX) is set.
    Extended {
        /// Primary part length.
        first: usize,
        /// Extension length.
        ext: usize,
    },
    /// A REP octet then REP items of `n` octets.
    Repetitive(usize),
    /// A LEN octet that includes itself.
    Explicit,
    /// A primary subfield (FX chain) then the present subfields; `None` marks
    /// a spare subfield (its presence bit set makes the length unknown).
    Compound(&'static [Option<Format>]),
}

/// One UAP slot: the item at an FRN, or `None` for a spare FRN.
pub type UapSlot = Option<(&'static str, Format)>;

/// A category's UAP: slot `i` holds FRN `i + 1`.
#[derive(Debug, Clone, Copy)]
pub struct Uap {
    /// Category number.
    pub cat: u8,
    /// Slots in FRN order.
    pub slots: &'static [UapSlot],
}

impl Uap {
    /// The longest FSPEC this UAP allows, in octets (7 FRNs per octet).
    #[must_use]
    pub fn max_fspec(&self) -> usize {
        self.slots.len().div_ceil(7)
    }

    /// The item at FRN `frn` (1-based).
    #[must_use]
    pub fn slot(&self, frn: usize) -> UapSlot {
        frn.checked_sub(1)
            .and_then(|i| self.slots.get(i))
            .copied()
            .flatten()
    }

    /// The 1-based FRN of an item name, if the UAP has it.
    #[must_use]
    pub fn frn_of(&self, name: &str) -> Option<usize> {
        self.slots
            .iter()
            .position(|s| s.is_some_and(|(n, _)| n == name))
            .map(|i| i + 1)
    }

    /// The [`ItemId`] of an item name.
    #[must_use]
    pub fn id(&self, name: &'static str) -> ItemId {
        ItemId {
            cat: self.cat,
            name,
        }
    }
}

/// Why an item's length could not be determined.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum LenError {
    /// At least `need` bytes are needed; fewer are present.
    Short { need: usize },
    /// The content breaks the layout.
    Invalid(&'static str),
}

/// The length of an item of format `format` at the start of `bytes` (the rest
/// of the record's block). Never reads past `bytes`; every loop advances.
pub(crate) fn item_len(format: Format, bytes: &[u8]) -> Result<usize, LenError> {
    let need = |n: usize| {
        if bytes.len() < n {
            Err(LenError::Short { need: n })
        } else {
            Ok(n)
        }
    };
    match format {
        Format::Fixed(n) => need(n),
        Format::Extended { first, ext } => {
            let mut end = need(first)?;
            // FX is the LSB of the last octet of each part; `ext` ≥ 1 so `end` grows.
            while bytes[end - 1] & 1 == 1 {
                end = need(end + ext.max(1))?;
            }
            Ok(end)
        }
        Format::Repetitive(n) => {
            need(1)?;
            need(1 + usize::from(bytes[0]) * n)
        }
        Format::Explicit => {
            need(1)?;
            let len = usize::from(bytes[0]);
            if len == 0 {
                return Err(LenError::Invalid("explicit length 0"));
            }
            need(len)
        }
        Format::Compound(subs) => {
            // Primary subfield: FX chain, at most enough octets for the subfields.
            let max_primary = subs.len().div_ceil(7).max(1);
            let mut n_primary = 0;
            loop {
                need(n_primary + 1)?;
                n_primary += 1;
                if bytes[n_primary - 1] & 1 == 0 {
                    break;
                }
                if n_primary == max_primary {
                    return Err(LenError::Invalid(
                        "compound primary subfield FX chain too long",
                    ));
                }
            }
            let mut end = n_primary;
            for (octet, &p) in bytes[..n_primary].iter().enumerate() {
                for bit in 0..7 {
                    if p & (0x80 >> bit) == 0 {
                        continue;
                    }
                    let Some(Some(sub)) = subs.get(octet * 7 + bit) else {
                        return Err(LenError::Invalid("undefined compound subfield present"));
                    };
                    let len = item_len(*sub, &bytes[end..]).map_err(|e| match e {
                        LenError::Short { need } => LenError::Short { need: end + need },
                        other => other,
                    })?;
                    end += len;
                }
            }
            Ok(end)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_of_each_format() {
        assert_eq!(item_len(Format::Fixed(2), &[1, 2, 3]), Ok(2));
        assert_eq!(
            item_len(Format::Fixed(4), &[1, 2, 3]),
            Err(LenError::Short { need: 4 })
        );
        // 0x01 (FX) → one extension; 0x00 ends.
        let ext = Format::Extended { first: 1, ext: 1 };
        assert_eq!(item_len(ext, &[0x01, 0x00, 0xff]), Ok(2));
        assert_eq!(
            item_len(ext, &[0x01, 0x01]),
            Err(LenError::Short { need: 3 })
        );
        // REP 2 × 8 octets = 17.
        let mut rep = vec![2u8];
        rep.extend([0; 16]);
        assert_eq!(item_len(Format::Repetitive(8), &rep), Ok(17));
        assert_eq!(item_len(Format::Explicit, &[3, 0, 0, 9]), Ok(3));
        assert_eq!(
            item_len(Format::Explicit, &[0]),
            Err(LenError::Invalid("explicit length 0"))
        );
        // Compound with subfields 1 (1 octet) and 3 (2 octets) present: 0b1010_0000.
        const SUBS: &[Option<Format>] = &[Some(Format::Fixed(1)), None, Some(Format::Fixed(2))];
        assert_eq!(item_len(Format::Compound(SUBS), &[0xa0, 1, 2, 3]), Ok(4));
        assert!(matches!(
            item_len(Format::Compound(SUBS), &[0x40, 1]),
            Err(LenError::Invalid(_))
        ));
        // An FX chain longer than the subfields allow.
        assert!(matches!(
            item_len(Format::Compound(SUBS), &[0x01, 0x01, 0x00]),
            Err(LenError::Invalid(_))
        ));
    }
}
