//! The safe coefficient for springs that share particles.
//!
//! A single spring is stable for any `(C_k, C_d)` in `[0, 1]²`. Springs that share a
//! particle compete: each corrects its own extension and disturbs its neighbours'. The
//! article's rule of thumb (eq. 29) is `C_max ≈ 1/(n + 1)`, with `n` the largest number of
//! springs on either particle of a spring. This function starts from it; the stress tests
//! (`STABILITY.md`) measure the true limits per topology and stepper.

use super::config::Stepper;

/// The largest `C_k` and `C_d` the scene accepts for a spring whose particles carry at
/// most `springs_per_particle` springs (counting itself), with the given stepper.
///
/// ```
/// use stiffspring::scene::{network_limit, Stepper};
///
/// // A lone spring: the article's unconditionally stable square.
/// assert_eq!(network_limit(1, Stepper::GaussSeidel), 1.0);
/// // A rope (two springs per inner particle): 1/3.
/// assert!((network_limit(2, Stepper::GaussSeidel) - 1.0 / 3.0).abs() < 1e-12);
/// ```
pub fn network_limit(springs_per_particle: usize, stepper: Stepper) -> f64 {
    match (springs_per_particle, stepper) {
        // One spring per particle: the single-spring guarantee holds whatever the order.
        (0 | 1, _) => 1.0,
        // Eq. 29.
        (n, _) => 1.0 / (n as f64 + 1.0),
    }
}
