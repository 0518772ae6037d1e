//! The lab: the instruments that stiffspring's tests, examples and benches measure the
//! library with. Host only (`std`), never a dependency of the library, and independent
//! of it: nothing here names a `stiffspring` item, so the instruments stay put while the
//! library's API changes.
//!
//! | module | what it is |
//! |---|---|
//! | [`reference`](mod@reference) | the independent f64 models of the seed article's springs and networks, written from its equations |
//! | [`linear`] | the linearised step matrix of a network and its eigenvalues (nalgebra) |
//! | [`nonlinear`] | nonlinear stability runs of a network on the reference model |
//! | [`rng`] | a seeded, portable random generator (rand's xoshiro256++) for reproducible inputs |
//! | [`knob`] | a simulated rotor (exact zero-order hold, encoder) and SmartKnob-style PD detents |
//! | [`measure`] | interleaved timing of several candidates on a noisy machine |
//! | [`pareto`] | the 1D value scenes, the peer crates and textbook baselines they are timed against |
//! | [`xpbd`] | XPBD with small steps, and network models in physical units with their fine-step reference |
//! | [`plot`] | SVG charts on plotters |
//! | [`precision`] | the precision study of issue 10: every candidate representation of one spring against the analytic oscillator |
//! | [`table`] | terminal, Markdown and CSV tables |
//! | [`golden`] | golden values kept as Rust source: render, compare, regenerate |

pub mod golden;
pub mod knob;
pub mod linear;
pub mod measure;
pub mod nonlinear;
pub mod pareto;
pub mod plot;
pub mod precision;
pub mod reference;
pub mod rng;
pub mod table;
pub mod xpbd;
