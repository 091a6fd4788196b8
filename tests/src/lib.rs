//! Cross-crate and reference-value tests for Argus live in `tests/tests/`.
