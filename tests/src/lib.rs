//! Cross-crate and reference-value tests for Argus live in `tests/tests/`.
//!
//! The README's Rust example is compiled and run as a doctest of this crate so
//! that it stays true:
#![doc = include_str!("../../README.md")]
