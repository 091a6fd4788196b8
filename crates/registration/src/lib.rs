//! Multisensor registration — **not built yet**.
//!
//! This crate will hold the biased local filter with its bias-sensitivity
//! matrix, pseudo bias measurements for asynchronous sensors, sequential
//! least-squares bias estimation, compensation, and the EXX baseline (seed 004).
//! It exports nothing yet.
