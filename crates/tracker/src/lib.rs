//! Multi-target surveillance tracker — **not built yet**.
//!
//! This crate will hold track initiation, confirmation and deletion, global
//! nearest-neighbour and JPDA association, and per-track estimators. It exports
//! nothing yet.
