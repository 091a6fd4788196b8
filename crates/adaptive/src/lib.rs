//! Adaptive filters — **not built yet**.
//!
//! This crate will hold the decoupled tracking filter with adaptive measurement
//! noise (seed 003) and GLRT maneuver detection with input estimation (seed 001).
//! It exports nothing yet.
