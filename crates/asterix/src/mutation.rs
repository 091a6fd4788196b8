//! Seeded mutation runs over sample block streams: each step damages one
//! record of the samples (or its block's header), decodes the whole stream,
//! and checks what [`decode`] promises — no panic, bounded time, a record
//! whose framing is broken reported by a typed skip naming its byte offset
//! (and item, where one is involved), the records before the damage and the
//! blocks after it kept. Run at a reduced count in the test suite and at ≥ 10⁶ by
//! `cargo xtask mutate`.

use std::collections::BTreeMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::{Duration, Instant};

use crate::block::{Decoded, decode};
use crate::cat021::Cat021;
use crate::cat034::Cat034;
use crate::cat048::Cat048;
use crate::cat062::Cat062;
use crate::record::{Category, decode_record};

/// The mutations, one per step, applied to a randomly chosen record.
pub const OPS: [&str; 6] = [
    "byte flips in the record",
    "truncation inside the record",
    "block length lie (random)",
    "block ends inside the record",
    "FSPEC chain that never ends",
    "unknown category",
];

/// What a run saw.
#[derive(Debug, Clone, Default)]
pub struct MutationReport {
    /// Mutated inputs decoded (one mutated record each).
    pub inputs: u64,
    /// Steps per mutation, in the order of [`OPS`].
    pub per_op: [u64; 6],
    /// Records decoded over all inputs.
    pub records_kept: u64,
    /// Skips by [`crate::DecodeError::reason`].
    pub skips: BTreeMap<&'static str, u64>,
    /// The slowest single decode.
    pub max_decode: Duration,
    /// The step of the slowest decode.
    pub max_decode_step: u64,
    /// Wall time of the run.
    pub elapsed: Duration,
}

/// A broken promise: which step, which mutation, what, and the input.
#[derive(Debug, Clone, thiserror::Error)]
#[error("mutation step {step} ({op}): {what}")]
pub struct MutationFailure {
    /// Step index (with the seed, it reproduces the input).
    pub step: u64,
    /// The mutation, from [`OPS`].
    pub op: &'static str,
    /// What went wrong.
    pub what: String,
    /// The mutated input.
    pub input: Vec<u8>,
}

/// One record of a sample stream: its block and its byte range.
#[derive(Debug, Clone, Copy)]
struct Span {
    block_start: usize,
    block_end: usize,
    start: usize,
    end: usize,
    /// Records decoded from the clean stream before this one.
    before: usize,
    /// Records of this block before this one.
    in_block: usize,
    /// Records decoded from the clean stream in blocks after this one's.
    after_block: usize,
}

/// SplitMix64 (Steele, Lea & Flood 2014): a seeded, portable generator; the
/// run needs reproducibility, not statistical quality.
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform-enough in `[0, n)` for `n ≥ 1` (modulo bias ≤ n/2^64).
    fn below(&mut self, n: usize) -> usize {
        usize::try_from(self.next() % (n.max(1) as u64)).unwrap_or(0)
    }

    fn byte(&mut self) -> u8 {
        self.next().to_le_bytes()[0]
    }
}

/// The end of the record at `pos` of a block of `cat`, if it decodes.
fn record_end(cat: u8, data: &[u8], pos: usize, end: usize) -> Option<usize> {
    fn one<C: Category>(data: &[u8], pos: usize, end: usize) -> Option<usize> {
        decode_record::<C>(data, pos, end)
            .ok()
            .map(|(_, next)| next)
    }
    match cat {
        48 => one::<Cat048>(data, pos, end),
        34 => one::<Cat034>(data, pos, end),
        21 => one::<Cat021>(data, pos, end),
        62 => one::<Cat062>(data, pos, end),
        _ => None,
    }
}

/// The records of a stream that decode, with their blocks (a record after a
/// bad one in its block, and anything after a broken block header, is not listed).
fn spans(data: &[u8]) -> Vec<Span> {
    let mut out = Vec::new();
    let mut pos = 0;
    while pos + 3 <= data.len() {
        let len = usize::from(u16::from_be_bytes([data[pos + 1], data[pos + 2]]));
        if len < 3 || pos + len > data.len() {
            break;
        }
        let (start, end) = (pos, pos + len);
        let mut r = start + 3;
        let first = out.len();
        while r < end {
            let Some(next) = record_end(data[start], data, r, end) else {
                break;
            };
            out.push(Span {
                block_start: start,
                block_end: end,
                start: r,
                end: next,
                before: out.len(),
                in_block: out.len() - first,
                after_block: 0,
            });
            r = next;
        }
        pos = end;
    }
    let total = out.len();
    for i in 0..total {
        let last_in_block = out[i..]
            .iter()
            .take_while(|s| s.block_start == out[i].block_start)
            .count();
        out[i].after_block = total - i - last_in_block;
    }
    out
}

/// Applies mutation `op` to the record `s` of `m`.
fn mutate(m: &mut Vec<u8>, s: Span, op: usize, rng: &mut SplitMix) {
    let len_at = |m: &mut Vec<u8>, v: usize| {
        let v = u16::try_from(v).unwrap_or(u16::MAX);
        m[s.block_start + 1..s.block_start + 3].copy_from_slice(&v.to_be_bytes());
    };
    match op {
        0 => {
            for _ in 0..=rng.below(3) {
                let i = s.start + rng.below(s.end - s.start);
                m[i] ^= rng.byte() | 1;
            }
        }
        1 => m.truncate(s.start + rng.below(s.end - s.start)),
        2 => len_at(m, usize::from(u16::from_le_bytes([rng.byte(), rng.byte()]))),
        3 => len_at(
            m,
            s.start + 1 + rng.below(s.end - s.start - 1) - s.block_start,
        ),
        4 => {
            let n = 1 + rng.below(8);
            for b in &mut m[s.start..(s.start + n).min(s.block_end)] {
                *b |= 1;
            }
        }
        _ => {
            // A category byte none of the four decoded ones.
            let mut c = rng.byte();
            while matches!(c, 21 | 34 | 48 | 62) {
                c = c.wrapping_add(1);
            }
            m[s.block_start] = c;
        }
    }
}

/// Checks one decode of a mutated input against the clean one.
fn check(clean: &Decoded, s: Span, op: usize, m: &[u8], d: &Decoded) -> Result<(), String> {
    let dropped: usize = d.skipped.iter().map(|k| k.dropped).sum();
    if dropped > m.len() {
        return Err(format!("{dropped} bytes dropped of {}", m.len()));
    }
    for k in &d.skipped {
        if k.error.offset() > m.len() || k.error.to_string().is_empty() {
            return Err(format!(
                "skip {:?} outside the {}-byte input",
                k.error,
                m.len()
            ));
        }
        if let Some(item) = k.error.item()
            && !matches!(item.cat, 21 | 34 | 48 | 62)
        {
            return Err(format!(
                "skip {:?} names an item of no known category",
                k.error
            ));
        }
    }
    // Records before the damage are kept as they were: the blocks before it
    // always, and the records before it in its block when the header is intact.
    let kept_before = if matches!(op, 0 | 1 | 4) {
        s.before
    } else {
        s.before - s.in_block
    };
    if d.records.len() < kept_before || d.records[..kept_before] != clean.records[..kept_before] {
        return Err(format!(
            "the {kept_before} records before the damage are not kept"
        ));
    }
    // Damage inside a record, or an unknown category, leaves the later blocks' framing.
    if matches!(op, 0 | 4 | 5) {
        let n = s.after_block;
        let (dl, cl) = (d.records.len(), clean.records.len());
        if dl < n || d.records[dl - n..] != clean.records[cl - n..] {
            return Err(format!("the {n} records of the later blocks are not kept"));
        }
    }
    // A record lost is a record reported, where the mutation must break the
    // framing (truncation, a block ending inside the record, an unknown
    // category). A flip or a length lie can leave a valid framing of other
    // values, which no decoder can tell (ASTERIX carries no checksum).
    let new_skip = d.skipped.iter().any(|k| !clean.skipped.contains(k));
    if matches!(op, 1 | 3 | 5) && !new_skip {
        return Err("the damaged record was not reported".to_owned());
    }
    // Damage inside one record: its skips lie inside its block.
    if matches!(op, 0 | 4) {
        for k in d.skipped.iter().filter(|k| !clean.skipped.contains(k)) {
            let o = k.error.offset();
            if k.error.item().is_some() && !(s.block_start..=s.block_end).contains(&o) {
                return Err(format!("item skip {:?} outside the damaged block", k.error));
            }
        }
    }
    Ok(())
}

/// Runs `count` mutation steps over `base` with `seed`. `progress` is called
/// every 10 000 steps with the step count (a watchdog's heartbeat).
///
/// # Errors
/// [`MutationFailure`] at the first broken promise, or when `base` has no
/// decodable record to mutate (step 0).
pub fn run(
    base: &[u8],
    seed: u64,
    count: u64,
    progress: &mut dyn FnMut(u64),
) -> Result<MutationReport, MutationFailure> {
    let start = Instant::now();
    let clean = decode(base);
    let spans = spans(base);
    if spans.is_empty() {
        return Err(MutationFailure {
            step: 0,
            op: "none",
            what: "the samples hold no decodable record".to_owned(),
            input: base.to_vec(),
        });
    }
    let mut rng = SplitMix(seed);
    let mut report = MutationReport::default();
    let mut m = Vec::with_capacity(base.len());
    for step in 0..count {
        let s = spans[rng.below(spans.len())];
        let op = rng.below(OPS.len());
        m.clear();
        m.extend_from_slice(base);
        mutate(&mut m, s, op, &mut rng);
        let t = Instant::now();
        let d = catch_unwind(AssertUnwindSafe(|| decode(&m))).map_err(|_| MutationFailure {
            step,
            op: OPS[op],
            what: "decode panicked".to_owned(),
            input: m.clone(),
        })?;
        let took = t.elapsed();
        if took > report.max_decode {
            report.max_decode = took;
            report.max_decode_step = step;
        }
        check(&clean, s, op, &m, &d).map_err(|what| MutationFailure {
            step,
            op: OPS[op],
            what,
            input: m.clone(),
        })?;
        report.inputs += 1;
        report.per_op[op] += 1;
        report.records_kept += d.records.len() as u64;
        for k in &d.skipped {
            *report.skips.entry(k.error.reason()).or_default() += 1;
        }
        if (step + 1) % 10_000 == 0 {
            progress(step + 1);
        }
    }
    report.elapsed = start.elapsed();
    Ok(report)
}
