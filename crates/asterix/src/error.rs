//! Typed decode and encode errors. Every decode error names the byte offset
//! (from the start of the input given to the decoder) and, where one is
//! involved, the data item.

use std::fmt;

/// A data item of a category, e.g. `I048/040`, or a special field (`SP`, `RE`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ItemId {
    /// Category number (48 for CAT048).
    pub cat: u8,
    /// Item name inside the category: `"040"`, `"SP"`, `"RE"`.
    pub name: &'static str,
}

impl fmt::Display for ItemId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "I{:03}/{}", self.cat, self.name)
    }
}

/// Why a block or a record could not be decoded.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum DecodeError {
    /// Fewer than the 3 header bytes (CAT, LEN) remain.
    #[error("truncated block header at byte {offset}: {have} of 3 bytes")]
    TruncatedHeader {
        /// Offset of the block start.
        offset: usize,
        /// Bytes present.
        have: usize,
    },
    /// The block's LEN is below the 3-byte header.
    #[error("block at byte {offset} declares length {declared}, below the 3-byte header")]
    BlockLengthTooShort {
        /// Offset of the block start.
        offset: usize,
        /// LEN field.
        declared: usize,
    },
    /// The block's LEN runs past the end of the input.
    #[error("block at byte {offset} declares length {declared} but only {available} bytes remain")]
    BlockLengthExceedsInput {
        /// Offset of the block start.
        offset: usize,
        /// LEN field.
        declared: usize,
        /// Bytes left in the input from the block start.
        available: usize,
    },
    /// A category this crate has no UAP for; the block is skipped whole.
    #[error("unknown category {cat} in block at byte {offset}")]
    UnknownCategory {
        /// Offset of the block start.
        offset: usize,
        /// CAT byte.
        cat: u8,
    },
    /// The FSPEC's FX chain runs past the UAP's length or the block's end.
    #[error("CAT{cat:03} FSPEC at byte {offset} not terminated within {max} octets or the block")]
    FspecUnterminated {
        /// Offset of the record (its FSPEC) start.
        offset: usize,
        /// Category.
        cat: u8,
        /// Longest FSPEC the UAP allows.
        max: usize,
    },
    /// The FSPEC has no bit set.
    #[error("CAT{cat:03} record at byte {offset} has an empty FSPEC")]
    EmptyRecord {
        /// Offset of the record start.
        offset: usize,
        /// Category.
        cat: u8,
    },
    /// The FSPEC sets an FRN the UAP leaves spare or undefined: its length is unknown.
    #[error("CAT{cat:03} record at byte {offset} sets FRN {frn}, undefined in the UAP")]
    UndefinedFrn {
        /// Offset of the record start.
        offset: usize,
        /// Category.
        cat: u8,
        /// Field reference number.
        frn: usize,
    },
    /// An item (by its length rule) runs past the end of the block.
    #[error("{item} at byte {offset} needs {need} bytes but only {have} remain in the block")]
    ItemOverrun {
        /// Offset of the item start.
        offset: usize,
        /// The item.
        item: ItemId,
        /// Bytes needed (known so far).
        need: usize,
        /// Bytes left in the block.
        have: usize,
    },
    /// An item's content breaks its layout (explicit length 0, undefined
    /// compound subfield, a value outside its defined range).
    #[error("{item} at byte {offset}: {what}")]
    InvalidItem {
        /// Offset of the item start.
        offset: usize,
        /// The item.
        item: ItemId,
        /// What is wrong.
        what: &'static str,
    },
}

impl DecodeError {
    /// The byte offset the error refers to.
    #[must_use]
    pub fn offset(&self) -> usize {
        match self {
            Self::TruncatedHeader { offset, .. }
            | Self::BlockLengthTooShort { offset, .. }
            | Self::BlockLengthExceedsInput { offset, .. }
            | Self::UnknownCategory { offset, .. }
            | Self::FspecUnterminated { offset, .. }
            | Self::EmptyRecord { offset, .. }
            | Self::UndefinedFrn { offset, .. }
            | Self::ItemOverrun { offset, .. }
            | Self::InvalidItem { offset, .. } => *offset,
        }
    }

    /// The reason's name (the variant), for counting skips by reason.
    #[must_use]
    pub fn reason(&self) -> &'static str {
        match self {
            Self::TruncatedHeader { .. } => "TruncatedHeader",
            Self::BlockLengthTooShort { .. } => "BlockLengthTooShort",
            Self::BlockLengthExceedsInput { .. } => "BlockLengthExceedsInput",
            Self::UnknownCategory { .. } => "UnknownCategory",
            Self::FspecUnterminated { .. } => "FspecUnterminated",
            Self::EmptyRecord { .. } => "EmptyRecord",
            Self::UndefinedFrn { .. } => "UndefinedFrn",
            Self::ItemOverrun { .. } => "ItemOverrun",
            Self::InvalidItem { .. } => "InvalidItem",
        }
    }

    /// The item the error refers to, if any.
    #[must_use]
    pub fn item(&self) -> Option<ItemId> {
        match self {
            Self::ItemOverrun { item, .. } | Self::InvalidItem { item, .. } => Some(*item),
            _ => None,
        }
    }
}

/// Why a value could not be encoded.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum EncodeError {
    /// A physical value outside what the item's field can hold, or not finite.
    #[error("{item}: {what} = {value} is outside the encodable range")]
    OutOfRange {
        /// The item.
        item: ItemId,
        /// Which field.
        what: &'static str,
        /// The offending value.
        value: f64,
    },
    /// The block would exceed the 16-bit LEN field (65 535 bytes).
    #[error("CAT{cat:03} block of {len} bytes exceeds the 65535-byte LEN field")]
    BlockTooLong {
        /// Category.
        cat: u8,
        /// Length the block would have.
        len: usize,
    },
    /// Items were added out of FRN order or the FRN is not in the UAP.
    #[error("CAT{cat:03}: FRN {frn} added out of order or not in the UAP")]
    FrnOrder {
        /// Category.
        cat: u8,
        /// Field reference number.
        frn: usize,
    },
}
