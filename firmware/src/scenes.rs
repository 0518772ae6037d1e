//! The scenes the dual-target examples play, shared with `tests/golden.rs`, which plays
//! them on the f64 reference model (or, for the knob, the library's `f64` knob) and
//! writes their golden values into [`crate::golden`].

pub mod knob;
pub mod rope;
pub mod value;
