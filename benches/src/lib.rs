//! Criterion benchmarks live in `benches/benches/`; `cargo xtask bench` runs them.
