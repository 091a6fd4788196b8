//! Interacting multiple model (IMM) estimation — **not built yet**.
//!
//! This crate will hold the IMM of seed 000 (mixing with the spread-of-means term,
//! log-space mode probabilities, combination) over any set of mode-matched
//! filters from `argus-filters`, and the multi-IMM measurement-noise estimator
//! of seed 000 eqs (8)–(14). It exports nothing yet.
