//! The `argus` command (placeholder).
fn main() {}
