//! Damping of motion: a drag on every free particle's velocity, `dv/dt = −c·v`, beside the
//! springs' damping (which acts only on their stretching).
//!
//! Without it a released rope never sleeps: its springs damp how fast it stretches, and
//! the swing of the whole rope about its pin stretches nothing. Box2D calls the same thing
//! `linearDamping` (and `angularDamping` for bodies); in an
//! [`AngularScene`](super::AngularScene) it acts on the bodies' angular velocities.
//!
//! **Sampled exactly.** A velocity that decays as `e^{−c·t}` keeps the fraction
//! `r = e^{−c·dt}` of itself per step, so each step takes `d·u` off the step velocity `u`
//! with `d = 1 − r = −expm1(−c·dt)`, computed at set-up. A free particle flung at `v`
//! then moves by `v·(1 − e^{−c·t})/c` exactly at every sample (the step velocity it starts
//! with is the first step of that trajectory, [`start_factor`]). The product `d·u` is
//! taken on the scene's state, so fixed point keeps damping a slow particle (in `I16F16`
//! a state's last bit is 2⁻²⁴ of a position's): `0.995·u` rounded to a position's last
//! bit would give `u` back.
//!
//! **What is accepted.** `c ≥ 0` and finite, at most `ln 2/dt` (a step keeps at least
//! half of the velocity: see `MAX_STEP`), and enough for the backend to see: `d` at least
//! the state's resolution relative to a particle moving one position's last bit per step
//! (`2⁻²⁴` in `f32` and `I16F16`, `2⁻³²` in `I32F32`, `2⁻⁵³` in `f64`); a smaller `d`
//! would not change any step velocity and is refused as
//! [`Error::Unrepresentable`] instead of being silently ignored.

use super::limits::Change;
use super::{Kind, ParticleId, Scene};
use crate::error::{Bound, Error, Parameter, Remedy, check};
use crate::length::LengthKernel;
use crate::math;
use crate::scalar::Scalar;

/// The most a step may take off a velocity, as `c·dt`: `ln 2`, a retention of one half.
///
/// A drag stabilises a lone particle but not every network: it lowers the damping a
/// spring's own `C_d` gets through (`r·C_d`) while it adds `1 − r` to every mode. For
/// Jacobi the proof of [`network_limit`](super::network_limit) carries over with
/// `C_d → r·C_d + (1 − r)`, and at the limit it stays within `3 < 4` for any `r`. For
/// Gauss-Seidel the worst geometry's condition becomes
/// `3 − (1 + 2r)·(1 − L)^m + (n − m)·L < 4`, which at `L = ¾·W(n)` holds for every `n`
/// while `r ≥ ½` (at `r = ½` it peaks at 3.63, about `m·L = ln 2`) and fails for small `r`
/// (at `r = 0` every step restarts from rest and the undamped modes need `C_k·n < 2`).
pub(crate) const MAX_STEP: f64 = core::f64::consts::LN_2;

/// A drag rate `c` validated for a scene stepped every `dt`: `d = 1 − e^{−c·dt}`, the
/// fraction of the step velocity one step takes off (0 for no drag).
///
/// # Errors
///
/// [`Error::NotFinite`] or [`Error::OutOfRange`] (naming `parameter`) outside
/// `[0, ln 2/dt]`; [`Error::Unrepresentable`] for a drag too weak for the backend to
/// apply (see the [module docs](self)), with the weakest one it applies as the limit.
pub(crate) fn step_fraction<S: Scalar>(
    rate: f64,
    dt: f64,
    parameter: Parameter,
) -> Result<f64, Error> {
    let rate = check(
        rate,
        parameter,
        Bound::Within {
            min: 0.0,
            max: MAX_STEP / dt,
        },
    )?;
    let d = -math::expm1(-rate * dt);
    if d == 0.0 || acts::<S>(d) {
        return Ok(d);
    }
    // The weakest drag the backend applies, by halving (this runs only when set-up fails).
    let mut least = 0.5;
    while least > f64::MIN_POSITIVE && acts::<S>(0.5 * least) {
        least *= 0.5;
    }
    Err(Error::Unrepresentable {
        parameter,
        backend: S::NAME,
        value: rate,
        // c = −ln(1 − d)/dt ≈ d/dt for the tiny d this is about.
        limit: least / dt,
        remedy: Remedy::LowerRate,
    })
}

/// True when taking `d·u` off a particle moving one position's last bit per step (one
/// unit per step in floats) changes its step velocity.
fn acts<S: Scalar>(d: f64) -> bool {
    let unit = if S::RESOLUTION > 0.0 {
        S::state_from_f64(S::RESOLUTION)
    } else {
        S::state_from_f64(1.0)
    };
    S::state_sub(unit, S::scale(unit, S::factor(d))) != unit
}

/// The step velocity that starts a particle with drag rate `c` on the trajectory of its
/// velocity `v`: its first displacement, `u = v·(1 − e^{−c·dt})/c` (`v·dt` without
/// drag), the continuous one; each step then keeps `e^{−c·dt}` of it.
pub(crate) fn start_factor(rate: f64, dt: f64) -> f64 {
    if rate > 0.0 {
        -math::expm1(-rate * dt) / rate
    } else {
        dt
    }
}

impl<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>>
    Scene<S, D, P, K, L>
{
    /// Sets the drag on one particle's motion: its velocity decays as `e^{−c·t}` (for a
    /// free particle, beside what its springs do). Particles get the scene's drag
    /// ([`SceneConfig::linear_damping`](super::SceneConfig::linear_damping)) when they are
    /// added; this changes it for one of them (a heavier drag on a rope's tip, none on a
    /// drag handle's body). Its step velocity is kept; the new drag acts from the next
    /// step. A pinned particle keeps it for when it is given a mass.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`]; as [`SceneConfig::linear_damping`](super::SceneConfig::linear_damping)
    /// for the rate, with [`Parameter::LinearDamping`]; [`Error::OutOfRange`] when the
    /// particle's only spring is undersampled (`C_k > 2`, a tuning beyond the article's
    /// square that [`Scene::add_spring`] accepts for a lone spring) and the drag would
    /// take it out of its stable region, with the largest rate that keeps it. Nothing
    /// changes then.
    ///
    /// ```
    /// use stiffspring::scene::{Scene, SceneConfig};
    ///
    /// let dt = 0.01;
    /// let mut s = Scene::<f64, 1, 1, 1>::new(SceneConfig::new(dt)?.no_sleep());
    /// let p = s.add_particle([0.0], 1.0)?;
    /// s.set_linear_damping(p, 2.0)?;
    /// s.set_velocity(p, [1.0])?;
    /// for _ in 0..100 {
    ///     let _ = s.step();
    /// }
    /// // x(1 s) = (1 − e^{−2})/2 and v(1 s) = e^{−2}, exactly at every sample.
    /// let exact = (1.0 - (-2.0f64).exp()) / 2.0;
    /// assert!((s.position(p)?[0] - exact).abs() < 1e-12);
    /// assert!((s.velocity(p)?[0] - (-2.0f64).exp()).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_linear_damping(&mut self, particle: ParticleId, rate: f64) -> Result<(), Error> {
        self.set_drag(particle, rate, Parameter::LinearDamping)
    }

    /// A particle's drag rate `c`, per second.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`] for an id that names no live particle.
    ///
    /// ```
    /// use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 2, 2, 1>::new(SceneConfig::new(0.01)?.linear_damping(1.5)?);
    /// let p = s.add_particle([0.0, 0.0], 1.0)?;
    /// assert_eq!(s.linear_damping(p)?, 1.5);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn linear_damping(&self, particle: ParticleId) -> Result<f64, Error> {
        Ok(self.particles[self.slot(particle)?].damping)
    }

    pub(crate) fn set_drag(
        &mut self,
        particle: ParticleId,
        rate: f64,
        parameter: Parameter,
    ) -> Result<(), Error> {
        let slot = self.slot(particle)?;
        let d = step_fraction::<S>(rate, self.config.dt, parameter)?;
        // A lone spring on the particle (no other spring on either end) is held to Jury's
        // region with the drag in its damping (`Scene::add_spring`): the drag may not
        // take it out.
        let mut least = 0.0f64;
        for i in 0..self.springs.len() {
            let s = self.springs[i];
            let (a, b) = (s.a as usize, s.b as usize);
            if s.kind == Kind::Dead
                || (a != slot && b != slot)
                || self.share_count(a, b, &Change::NONE) > 1
            {
                continue;
            }
            let (ka, kb) = self.stiffening(a, b, &s.rest);
            let (ck, cd) = S::gains_to_f64(&s.gains);
            // a·C_k + 2·(1 − r·(1 − b·C_d)) < 4 needs the smaller retention of the ends
            // above this (`Scene::add_spring` checks the same).
            // With `b·C_d ≥ 1` a drag only lowers the damping's excess over 1: no bound.
            let keep = 1.0 - kb * cd;
            if keep > 0.0 {
                least = least.max((ka * ck - 2.0) / (2.0 * keep));
            }
        }
        if least > 0.0 && 1.0 - d <= least {
            return Err(Error::OutOfRange {
                parameter,
                value: rate,
                bound: Bound::Below {
                    max: -libm::log(least) / self.config.dt,
                },
            });
        }
        self.particles[slot].damping = rate;
        self.drag[slot] = S::factor(d);
        self.reschedule();
        Ok(())
    }
}

impl<S: Scalar, const P: usize, const K: usize, L: LengthKernel<S>> Scene<S, 1, P, K, L> {
    /// [`Scene::set_linear_damping`] for a body of an
    /// [`AngularScene`](super::AngularScene): its angular velocity decays as `e^{−c·t}`.
    /// Its errors name [`Parameter::AngularDamping`].
    ///
    /// # Errors
    ///
    /// As [`Scene::set_linear_damping`], with [`Parameter::AngularDamping`].
    ///
    /// ```
    /// use stiffspring::scene::{AngularScene, SceneConfig};
    /// use stiffspring::{Error, Parameter};
    ///
    /// let mut s = AngularScene::<f32, 2, 1>::new(SceneConfig::new(1e-3)?);
    /// let wheel = s.add_particle([0.0], 0.01)?;
    /// s.set_angular_damping(wheel, 0.5)?;
    /// assert!(matches!(
    ///     s.set_angular_damping(wheel, f64::NAN),
    ///     Err(Error::NotFinite { parameter: Parameter::AngularDamping })
    /// ));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_angular_damping(&mut self, body: ParticleId, rate: f64) -> Result<(), Error> {
        self.set_drag(body, rate, Parameter::AngularDamping)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_weakest_drag_each_backend_applies() {
        let dt = 1e-3;
        for (weak, parameter) in [
            (1e-9, Parameter::LinearDamping),
            (1e-9, Parameter::AngularDamping),
        ] {
            match step_fraction::<f32>(weak, dt, parameter) {
                Err(Error::Unrepresentable {
                    parameter: p,
                    limit,
                    ..
                }) => {
                    assert_eq!(p, parameter);
                    // 2⁻²⁴ per step at 1 kHz.
                    assert!((limit - 2f64.powi(-24) / dt).abs() < 1e-12, "{limit}");
                }
                other => panic!("{other:?}"),
            }
        }
        assert!(step_fraction::<f64>(1e-9, dt, Parameter::LinearDamping).is_ok());
        assert_eq!(
            step_fraction::<f32>(0.0, dt, Parameter::LinearDamping),
            Ok(0.0)
        );
        assert!(matches!(
            step_fraction::<f32>(-1.0, dt, Parameter::LinearDamping),
            Err(Error::OutOfRange {
                parameter: Parameter::LinearDamping,
                ..
            })
        ));
        assert!(matches!(
            step_fraction::<f32>(f64::NAN, dt, Parameter::LinearDamping),
            Err(Error::NotFinite {
                parameter: Parameter::LinearDamping
            })
        ));
        assert!(step_fraction::<f32>(MAX_STEP / dt, dt, Parameter::LinearDamping).is_ok());
        assert!(step_fraction::<f32>(1.01 * MAX_STEP / dt, dt, Parameter::LinearDamping).is_err());
    }

    #[test]
    fn the_start_factor_is_the_first_step_of_the_decay() {
        let (c, dt) = (3.0, 0.01);
        let d = step_fraction::<f64>(c, dt, Parameter::LinearDamping).unwrap();
        assert!((d / c - start_factor(c, dt)).abs() < 1e-18);
        assert!((start_factor(c, dt) - (1.0 - (-c * dt).exp()) / c).abs() < 1e-16);
        assert_eq!(start_factor(0.0, dt), dt);
    }
}
