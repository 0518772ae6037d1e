//! The pull of a scene's springs: what their stiffness adds to the step velocities of
//! their ends at the current positions, and how set-up keeps it in the kept step
//! velocity.
//!
//! A scene keeps, for every free particle, the step velocity its next step moves it by
//! (see the [scene docs](super#the-kept-step-velocity)): the kept velocity `ũ` (what is
//! left of its last step after the springs' and the drag's damping, the `ũ = (1 − C_d)·u`
//! of a value) plus the pull `−C_k·x` of each of its springs at the current positions,
//! split by the weights. The step computes both at the end of a step; set-up calls that
//! change a pull (a moved particle or anchor, a new, removed or retuned spring, a new
//! mass, a pin) take the old pull off and put the new one on, so the next step moves
//! every particle by exactly what its springs pull now, and `ũ` is kept.

use super::{Kind, Scene};
use crate::length::LengthKernel;
use crate::scalar::Scalar;

/// The pull of one spring: the change of each end's step velocity (the pinned end of a
/// one-sided spring, `a`, gets none).
pub(crate) struct Pull<S: Scalar, const D: usize> {
    pub(crate) a: usize,
    pub(crate) on_a: Option<[S::State; D]>,
    pub(crate) b: usize,
    pub(crate) on_b: [S::State; D],
}

impl<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>>
    Scene<S, D, P, K, L>
{
    /// The pull of spring slot `i` at the current positions: `Δ = −C_k·x` along its axis
    /// (per component `−C_k·dᵢ` for a point spring), split by its weights as the step
    /// splits it; `None` for a dead spring or one between two pinned particles.
    pub(crate) fn pull(&self, i: usize) -> Option<Pull<S, D>> {
        let s = &self.springs[i];
        if !matches!(s.kind, Kind::OneSided | Kind::TwoSided) {
            return None;
        }
        let (a, b) = (s.a as usize, s.b as usize);
        let d = self.separation(a, b);
        // Per component: the change of the relative step velocity.
        let mut relative = [S::STATE_ZERO; D];
        if s.point {
            for k in 0..D {
                relative[k] = S::state_sub(S::STATE_ZERO, S::spring_term(&s.gains, d[k]));
            }
        } else {
            let (x, n) = L::measure(&d, &s.rest);
            let delta = S::state_sub(S::STATE_ZERO, S::spring_term(&s.gains, x));
            for k in 0..D {
                relative[k] = S::state_mul_coef(delta, n[k]);
            }
        }
        if s.kind == Kind::OneSided {
            return Some(Pull {
                a,
                on_a: None,
                b,
                on_b: relative,
            });
        }
        let (mut on_a, mut on_b) = ([S::STATE_ZERO; D], [S::STATE_ZERO; D]);
        for k in 0..D {
            (on_a[k], on_b[k]) = s.weights.split(relative[k]);
        }
        Some(Pull {
            a,
            on_a: Some(on_a),
            b,
            on_b,
        })
    }

    /// Adds (`sign > 0`) or takes off the pull of spring slot `i` to its ends' kept step
    /// velocities.
    pub(crate) fn apply_pull(&mut self, i: usize, add: bool) {
        let Some(pull) = self.pull(i) else {
            return;
        };
        let apply = |u: &mut [S::State; D], change: &[S::State; D]| {
            for k in 0..D {
                u[k] = if add {
                    S::state_add(u[k], change[k])
                } else {
                    S::state_sub(u[k], change[k])
                };
            }
        };
        apply(&mut self.velocities[pull.b], &pull.on_b);
        if let Some(on_a) = pull.on_a {
            apply(&mut self.velocities[pull.a], &on_a);
        }
    }

    /// Takes the pulls of every live spring touching `slot` off, runs `change`, and puts
    /// them back on as they are after it (for the springs that touch `slot` then).
    pub(crate) fn repulling<T>(&mut self, slot: usize, change: impl FnOnce(&mut Self) -> T) -> T {
        let touches = |s: &Self, i: usize| {
            let spring = &s.springs[i];
            spring.kind != Kind::Dead && (spring.a as usize == slot || spring.b as usize == slot)
        };
        for i in 0..self.springs.len() {
            if touches(self, i) {
                self.apply_pull(i, false);
            }
        }
        let result = change(self);
        for i in 0..self.springs.len() {
            if touches(self, i) {
                self.apply_pull(i, true);
            }
        }
        result
    }
}
