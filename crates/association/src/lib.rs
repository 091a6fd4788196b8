//! Data association in clutter — **not built yet**.
//!
//! This crate will hold the validation gate, the nearest-neighbour,
//! strongest-neighbour, probabilistic-strongest-neighbour and PDA filters, and
//! off-line performance prediction (seed 002). It exports nothing yet.
