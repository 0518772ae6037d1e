//! The `rope` scene: a 2D rope of 12 particles, pinned at one end, released horizontally
//! under gravity at 240 Hz. Shared by `examples/check_rope.rs` (host and firmware) and the tour.
//!
//! Units are metres, kilograms and seconds; positions stay within ±2 m, well inside the
//! `I16F16` range. Every particle carries at most two springs, so the article's limit is
//! `1/(2 + 1)`: the rope runs at `C_k = C_d = 0.3`.

use stiffspring::length::LengthKernel;
use stiffspring::scene::{ParticleId, Scene, SceneConfig};
use stiffspring::{Error, Scalar, Tuning};

/// The step, in seconds. One Gauss-Seidel pass per step holds a segment with stiffness
/// `C·m_red/dt²` at most, so the static stretch of the top segment is about
/// `(particles below)·g·dt²·2/C`: 13 % at 240 Hz, four times that at 120 Hz.
pub const DT: f64 = 1.0 / 240.0;
/// Particles, the first one pinned.
pub const PARTICLES: usize = 12;
/// Springs between neighbours.
pub const SPRINGS: usize = PARTICLES - 1;
/// Rest length of a segment, in metres.
pub const SEGMENT: f64 = 0.1;
/// Mass of a particle, in kilograms. (The motion does not depend on it: springs are
/// tuned by fractions of the reduced mass, and gravity is an acceleration.)
pub const MASS: f64 = 0.02;
/// Gravity, in m/s².
pub const GRAVITY: [f64; 2] = [0.0, -9.81];
/// Both coefficients, just under the rope's limit of 1/3.
pub const COEFFICIENT: f64 = 0.3;
/// Steps played: two seconds.
pub const STEPS: usize = 480;

/// The rope scene in backend `S` with length kernel `L`, and its particles in order
/// (the pinned one first).
pub type Rope<S, L> = Scene<S, 2, PARTICLES, SPRINGS, L>;

/// Builds the rope, at rest along the x axis.
pub fn build<S: Scalar, L: LengthKernel<S>>() -> Result<(Rope<S, L>, [ParticleId; PARTICLES]), Error>
{
    let config = SceneConfig::new(DT)?.gravity(GRAVITY.map(S::from_f64))?;
    let mut rope = Scene::new(config);
    let tuning = Tuning::from_coefficients(COEFFICIENT, COEFFICIENT, DT)?;
    let mut ids = [rope.add_pinned([S::ZERO, S::ZERO])?; PARTICLES];
    for i in 1..PARTICLES {
        let x = S::from_f64(i as f64 * SEGMENT);
        ids[i] = rope.add_particle([x, S::ZERO], S::from_f64(MASS))?;
        rope.add_spring(ids[i - 1], ids[i], S::from_f64(SEGMENT), &tuning)?;
    }
    Ok((rope, ids))
}
