//! A network of particles and springs: ropes, meshes, jelly, drag handles, and angular
//! springs.
//!
//! A [`Scene`] holds up to `P` particles and `K` springs in `D` dimensions (heapless,
//! fixed at compile time), in backend `S`, with length kernel `L` (see
//! [`crate::length`]). Everything a step needs is precomputed when the scene changes:
//!
//! - each particle's inverse mass (0 for a pinned particle);
//! - each spring's gains, its two-body weights `w_a`, `w_b` (eq. 17–20 through
//!   [`BodyWeights`]), and what its length kernel needs;
//! - which springs have a pinned end (they skip the weights and the pinned side), and
//!   which connect two pinned particles (they are kept but never stepped);
//! - which groups of connected particles ("islands") are awake.
//!
//! Positions, velocities, masses, rest lengths, gravity and impulses are all in the
//! scene's number type `S`; only the [`Tuning`]s and the configuration's
//! time step and thresholds are `f64`. Particles and springs are named by generational
//! ids ([`ParticleId`], [`SpringId`]): a stale id is an error, never another particle.
//!
//! # One step, in order
//!
//! 1. **Move**: every awake free particle moves by its kept step velocity and gravity,
//!    `u = ũ + g·dt²`, `x += u`; its drag ([`SceneConfig::linear_damping`],
//!    `d = 1 − e^{−c·dt}`) then takes `d·u` off.
//! 2. **Springs**, at the positions just reached, through the crate's two-body kernel
//!    ([`kernel`](crate::kernel)), each damping its ends' motion and pulling them
//!    toward its rest length for the next step:
//!    - [`Stepper::GaussSeidel`]: the impulse form, spring by spring, in place;
//!    - [`Stepper::Jacobi`]: the force form, every spring from the same state, summed.
//! 3. **Sleep**: an island whose particles all moved less than the sleep threshold for
//!    long enough stops being stepped; it costs nothing until something touches it (an
//!    impulse, a teleport, a velocity, a moved anchor, a new or retuned spring). A
//!    network whose springs damp only their stretching (a rope's swing about its pin)
//!    comes to rest and sleeps only with a drag: for a rope of length `ℓ` under gravity
//!    `g`, `c ≈ 2.4·√(g/ℓ)` ([`SceneConfig::linear_damping`]; about 6 per second for a
//!    metre) with [`SleepThreshold::new(0.01, 0.5)`](SleepThreshold::new) puts a
//!    20-particle rope dragged and let go to sleep 2.3 s after the release, at rest
//!    below its pin (`tests/scene_damping.rs`).
//!
//! # The kept step velocity
//!
//! What a scene keeps for each particle between steps is the step its next step moves it
//! by (less gravity): what its last step left after the springs' damping and the drag,
//! the `ũ = (1 − C_d)·u` of a [`SpringValue`](crate::SpringValue), plus the pull
//! `−C_k·x` its springs have at the current positions. The springs run at the end of a
//! step, so that a step never multiplies a large step velocity by `1 − C_d`: a heavily
//! overdamped spring released at a low rate extrapolates one step back by `e^{2ζω·dt}`
//! (10⁸ of its stretch for ζ = 10 at 12 Hz and 60 Hz), and [`Scene::release`] keeps
//! `P̃·x` instead, below the stretch, as a value does. This is the article's step moved
//! by half a step: from rest, without gravity, the same motion as applying the springs
//! first (`lab/tests/reference_network_selftest.rs`); with gravity, the damping no
//! longer sees it, and a hanging spring rests at its static weight.
//!
//! Set-up calls keep it so: a moved particle or anchor, a new, removed or retuned
//! spring, a new mass take the old pull off and put the new one on, so the next step
//! moves every particle by what its springs pull now (a dragged anchor's particle
//! follows it in the very next step, its springs' damping acting on the anchor's
//! motion). [`Scene::velocity`] reads the next step over `dt`, and
//! [`Scene::set_velocity`] sets it.
//!
//! [`Scene::step`] reports what moved and what fell asleep ([`SceneMotion`]).
//!
//! # Momentum
//!
//! The two bodies of a spring get their velocity changes `−w_a·Δ` and `+w_b·Δ` from the
//! same computation, so two **equal masses** conserve momentum exactly, to the bit, in
//! every backend.
//!
//! # Springs that share particles
//!
//! A lone spring (no other spring on either of its free ends: a body on a spring to a
//! pin, a drag handle, two free bodies) is one spring in the relative coordinate of its
//! ends, accepted wherever a [`SpringValue`](crate::SpringValue) accepts its tuning
//! (Jury's region `C_k + 2·C_d < 4`, the drag of its ends folded into `C_d`): an
//! undersampled exact tuning, 12 Hz undamped at 60 Hz (`C_k = 1.38`), runs as it does in a
//! value. Springs that share particles are not stable that far. When a spring is added or
//! retuned, the scene checks it and its neighbours against [`network_limit`] for the
//! number of springs on their particles, and rejects or clamps by its [`LimitPolicy`].
//!
//! ```
//! use stiffspring::scene::{Scene, SceneConfig};
//! use stiffspring::Tuning;
//!
//! // A 2D rope of 8 particles hanging from a pinned end, at 120 Hz.
//! let dt = 1.0 / 120.0;
//! let mut rope = Scene::<f32, 2, 8, 7>::new(SceneConfig::new(dt)?.gravity([0.0, -9.81])?);
//! let link = Tuning::from_coefficients(0.3, 0.3, dt)?; // within ¾, the limit for two springs per particle
//! let mut last = rope.add_pinned([0.0, 0.0])?;
//! for i in 1..8 {
//!     let next = rope.add_particle([0.1 * i as f32, 0.0], 0.05)?;
//!     rope.add_spring(last, next, 0.1, &link)?;
//!     last = next;
//! }
//! for _ in 0..240 {
//!     let _ = rope.step();
//! }
//! assert!(rope.position(last)?[1] < -0.3); // it swung down
//! # Ok::<(), stiffspring::Error>(())
//! ```

mod angular;
mod build;
mod config;
mod damping;
mod events;
mod ids;
mod limits;
mod motion;
mod pull;
mod schedule;
mod step;

pub use angular::{Angle, AngularScene, WrappedAngle};
pub use config::{LimitPolicy, SceneConfig, SleepThreshold, Stepper};
pub use events::SceneMotion;
pub use ids::{Added, ParticleId, SpringId};
pub use limits::network_limit;

use crate::error::{Error, Parameter};
use crate::kernel::BodyWeights;
use crate::length::{Exact, LengthKernel};
use crate::scalar::Scalar;
use crate::tuning::Tuning;
use heapless::Vec;

/// Set-up data of one particle.
#[derive(Clone, Copy, Debug, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Particle {
    /// 0 for a pinned particle.
    pub(crate) inverse_mass: f64,
    /// The drag rate `c` (per second) on its motion (see [`damping`]).
    pub(crate) damping: f64,
    /// Live springs with this particle as an end.
    pub(crate) springs: u16,
    /// The slot of its island's root (free particles only).
    pub(crate) island: u16,
    pub(crate) live: bool,
    pub(crate) generation: u32,
}

/// How a spring runs in the hot loop.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) enum Kind {
    /// A removed spring's free slot.
    #[default]
    Dead,
    /// Both ends pinned: it can move nothing and is never stepped.
    Inert,
    /// End `a` pinned, `b` free: no weights, only `b` moves.
    OneSided,
    /// Both ends free.
    TwoSided,
}

/// One spring, as the hot loop reads it.
#[derive(Clone, Copy, Debug, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Spring<S: Scalar, L: LengthKernel<S>> {
    pub(crate) a: u16,
    pub(crate) b: u16,
    pub(crate) rest: L::Rest,
    pub(crate) gains: S::Gains,
    pub(crate) weights: BodyWeights<S>,
    pub(crate) kind: Kind,
    /// `P` of the exact start `u = P·x` of a spring released from rest (0 for raw
    /// coefficients); see [`Scene::release`].
    pub(crate) release: f64,
    pub(crate) generation: u32,
    /// The ends were swapped (to put a pinned end first) since the spring was added.
    pub(crate) swapped: bool,
    /// A zero-length distance spring: it pulls its ends together along every axis at
    /// once, `Δ = −(C_k·d + C_d·Δu)` per component, with no length and no axis (see
    /// [`Scene::add_spring`]).
    pub(crate) point: bool,
}

/// A stretch of the schedule's two-sided distance springs that the Gauss-Seidel loop runs
/// without a bounds check per spring (see `Scene::reschedule`).
///
/// A chain is `count` springs in consecutive slots `spring..spring + count`, spring
/// `spring + j` joining particles `particle + j` and `particle + j + 1`: a rope built in
/// order. Its loop slices the springs, positions and velocities once (one bounds check
/// per chain) and walks them together, keeping the shared end's position and velocity
/// in registers from one spring to the next, so nothing is loaded twice. Anything else
/// is a chain of one spring with `particle: None`, run through its own indices.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Chain {
    /// The slot of the first spring.
    pub(crate) spring: u16,
    /// Springs in the chain, at least 1.
    pub(crate) count: u16,
    /// The slot of the first spring's end `a`; `None` for a lone spring (count 1) whose
    /// ends are not consecutive.
    pub(crate) particle: Option<u16>,
}

/// Sleep state of one island (indexed by the slot of its root particle).
#[derive(Clone, Copy, Debug, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Island {
    pub(crate) awake: bool,
    /// A particle of the island moved faster than the threshold this step.
    pub(crate) moving: bool,
    /// Consecutive quiet steps.
    pub(crate) quiet: u32,
}

/// A network of up to `P` particles and `K` springs in `D` dimensions, in backend `S`,
/// measuring distance springs with kernel `L`. See the [module docs](self).
///
/// Code generic over the backend needs no bound beyond `S: Scalar`: the default kernel,
/// [`Exact`], works for every backend.
///
/// ```
/// use stiffspring::length::Linearised;
/// use stiffspring::scene::{Scene, SceneConfig};
/// use stiffspring::{Scalar, Tuning, I16F16};
///
/// // A 3D triangle in fixed point with the root-free kernel.
/// let dt = 1.0 / 60.0;
/// let mut s = Scene::<I16F16, 3, 3, 3, Linearised>::new(SceneConfig::new(dt)?);
/// let (one, zero) = (I16F16::ONE, I16F16::ZERO);
/// let p = [
///     s.add_particle([zero, zero, zero], one)?,
///     s.add_particle([one, zero, zero], one)?,
///     s.add_particle([zero, one, zero], one)?,
/// ];
/// let t = Tuning::from_coefficients(0.2, 0.2, dt)?;
/// for (a, b) in [(0, 1), (1, 2), (2, 0)] {
///     s.add_spring_at_rest(p[a], p[b], &t)?;
/// }
/// let _ = s.step();
/// assert_eq!(s.position(p[1])?, [one, zero, zero]); // at rest: nothing moves
///
/// fn generic<S: Scalar>() -> Scene<S, 2, 4, 4> {
///     Scene::new(SceneConfig::new(0.01).unwrap())
/// }
/// # let _ = generic::<f32>();
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Scene<S: Scalar, const D: usize, const P: usize, const K: usize, L = Exact>
where
    L: LengthKernel<S>,
{
    pub(crate) config: SceneConfig<S, D>,
    pub(crate) positions: Vec<[S::State; D], P>,
    /// What each position carries beside it (`f32`: its rounding remainder; nothing in the
    /// other backends, see [`Scalar::Remainder`]).
    pub(crate) remainders: Vec<[S::Remainder; D], P>,
    pub(crate) velocities: Vec<[S::State; D], P>,
    /// Each particle's drag in its step form `d = 1 − e^{−c·dt}` (see [`damping`]).
    pub(crate) drag: Vec<S::Factor, P>,
    /// Some awake free particle has a drag: the step applies them (decided at set-up, so
    /// that a scene without drag skips the stage).
    pub(crate) dragged: bool,
    pub(crate) particles: Vec<Particle, P>,
    pub(crate) springs: Vec<Spring<S, L>, K>,
    pub(crate) islands: Vec<Island, P>,
    /// The schedule: awake free particles, and springs of awake islands by kind.
    pub(crate) free: Vec<u16, P>,
    pub(crate) one_sided: Vec<u16, K>,
    pub(crate) two_sided: Vec<u16, K>,
    pub(crate) one_sided_points: Vec<u16, K>,
    pub(crate) two_sided_points: Vec<u16, K>,
    /// `two_sided` as chains, in the same order (Gauss-Seidel's loop).
    pub(crate) chains: Vec<Chain, K>,
    /// Roots of awake islands (for the sleep check).
    pub(crate) awake_islands: Vec<u16, P>,
    /// Jacobi's per-particle sums.
    pub(crate) accumulated: Vec<[S::State; D], P>,
    /// `g·dt²` in the state format; `None` when it is zero, decided at set-up so that a
    /// scene without gravity skips the stage.
    pub(crate) gravity_step: Option<[S::State; D]>,
    /// The sleep threshold in step units (`v·dt`), at least a position's last bit.
    pub(crate) sleep_step_velocity: S::State,
    /// Steps an island must stay quiet to sleep; 0 when sleeping is off.
    pub(crate) sleep_steps: u32,
    /// Particles whose island fell asleep in the last step.
    pub(crate) fell_asleep: Vec<u16, P>,
    /// Islands woken by set-up calls since the last step.
    pub(crate) woken: usize,
}

impl<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>>
    Scene<S, D, P, K, L>
{
    /// An empty scene. Capacities above 65 535 do not compile (ids are 16 bits).
    ///
    /// ```
    /// use stiffspring::scene::{Scene, SceneConfig};
    /// let scene = Scene::<f32, 3, 16, 32>::new(SceneConfig::new(0.01)?);
    /// assert_eq!(scene.particle_count(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn new(config: SceneConfig<S, D>) -> Self {
        const {
            assert!(P <= u16::MAX as usize && K <= u16::MAX as usize);
        }
        let dt = config.dt;
        let mut g = [S::STATE_ZERO; D];
        for (g, a) in g.iter_mut().zip(config.gravity) {
            *g = S::state_from_f64(a.to_f64() * dt * dt);
        }
        let gravity_step = g.iter().any(|g| *g != S::STATE_ZERO).then_some(g);
        let (sleep_step_velocity, sleep_steps) = match config.sleep {
            Some(t) => {
                // ⌈time/dt⌉ without `ceil` (not in `core`); `as` saturates huge ratios.
                let ratio = t.time() / dt;
                let steps = ratio as u32;
                let steps = if (steps as f64) < ratio {
                    steps.saturating_add(1)
                } else {
                    steps
                };
                (
                    S::state_from_f64((t.velocity() * dt).max(S::RESOLUTION)),
                    steps.max(1),
                )
            }
            None => (S::STATE_ZERO, 0),
        };
        Scene {
            config,
            positions: Vec::new(),
            remainders: Vec::new(),
            velocities: Vec::new(),
            drag: Vec::new(),
            dragged: false,
            particles: Vec::new(),
            springs: Vec::new(),
            islands: Vec::new(),
            free: Vec::new(),
            one_sided: Vec::new(),
            two_sided: Vec::new(),
            one_sided_points: Vec::new(),
            two_sided_points: Vec::new(),
            chains: Vec::new(),
            awake_islands: Vec::new(),
            accumulated: Vec::new(),
            gravity_step,
            sleep_step_velocity,
            sleep_steps,
            fell_asleep: Vec::new(),
            woken: 0,
        }
    }

    /// A particle's position.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`] for an id that names no live particle.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 2, 1, 1>::new(SceneConfig::new(0.01)?);
    /// let p = s.add_particle([1.0, 2.0], 1.0)?;
    /// assert_eq!(s.position(p)?, [1.0, 2.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn position(&self, particle: ParticleId) -> Result<[S; D], Error> {
        Ok(self.positions[self.slot(particle)?].map(S::narrow))
    }

    /// A particle's position as the scene holds it, in `f64`: in `f32` the position plus
    /// the rounding remainder the scene carries beside it (see [`Scalar::Remainder`]); in
    /// fixed point the wide state, with its guard bits below a position's last bit (exact
    /// for `I16F16`'s Q24.40 within ±2¹³ units, to 53 bits for `I32F32`'s Q64.64); in
    /// `f64` exactly [`Scene::position`]. For measurements (the energy of a drifting
    /// network, a comparison with a reference model), not for drawing.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`] for an id that names no live particle.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 1, 1, 1>::new(SceneConfig::new(1.0)?.no_sleep());
    /// let p = s.add_particle([1.0e4], 1.0)?;
    /// s.set_velocity(p, [1.0e-4])?;
    /// for _ in 0..4 {
    ///     let _ = s.step();
    /// }
    /// // Each step is below half an ulp of 10⁴ (4.9e−4): the f32 position stays, and the
    /// // scene holds the 4·10⁻⁴ it moved.
    /// assert_eq!(s.position(p)?, [10000.0]);
    /// assert!((s.precise_position(p)?[0] - 10000.0004).abs() < 1e-9);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn precise_position(&self, particle: ParticleId) -> Result<[f64; D], Error> {
        let slot = self.slot(particle)?;
        let (x, r) = (self.positions[slot], self.remainders[slot]);
        let mut p = [0.0; D];
        for k in 0..D {
            p[k] = S::state_to_f64(x[k]) + S::remainder_to_f64(r[k]);
        }
        Ok(p)
    }

    /// The separation `p_b − p_a` of two slots, with their remainders.
    pub(crate) fn separation(&self, a: usize, b: usize) -> [S::State; D] {
        let mut d = [S::STATE_ZERO; D];
        for k in 0..D {
            d[k] = S::difference_carrying(
                self.positions[b][k],
                self.remainders[b][k],
                self.positions[a][k],
                self.remainders[a][k],
            );
        }
        d
    }

    /// A particle's velocity in units per second: the distance its next step moves it,
    /// over `dt` (with a drag, over the step of the decay, so that a free particle reads
    /// its continuous velocity `v·e^{−c·t}` exactly; see
    /// [`Scene::set_linear_damping`]). It includes what the springs pull into that step
    /// (a scene applies its springs at the end of a step, see the [module
    /// docs](self#the-kept-step-velocity)), so a particle at rest reads 0, and a pinned
    /// particle always reads 0.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`] for an id that names no live particle.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f64, 1, 1, 1>::new(SceneConfig::new(0.1)?);
    /// let p = s.add_particle([0.0], 1.0)?;
    /// s.set_velocity(p, [3.0])?;
    /// assert!((s.velocity(p)?[0] - 3.0).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn velocity(&self, particle: ParticleId) -> Result<[S; D], Error> {
        let slot = self.slot(particle)?;
        let u = self.next_step(slot);
        let per_second = S::factor(1.0 / self.start_factor(slot));
        Ok(u.map(|u| S::narrow(S::scale(u, per_second))))
    }

    /// The step the next step moves `slot` by: its kept step velocity and gravity (0 for
    /// a pinned particle).
    pub(crate) fn next_step(&self, slot: usize) -> [S::State; D] {
        let mut u = self.velocities[slot];
        if let (Some(g), true) = (self.gravity_step, self.particles[slot].inverse_mass > 0.0) {
            for k in 0..D {
                u[k] = S::state_add(u[k], g[k]);
            }
        }
        u
    }

    /// The step velocity per unit of velocity of a particle (`dt` without drag; see
    /// [`damping::start_factor`]).
    pub(crate) fn start_factor(&self, slot: usize) -> f64 {
        damping::start_factor(self.particles[slot].damping, self.config.dt)
    }

    /// True for a pinned particle.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`] for an id that names no live particle.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 2, 1, 1>::new(SceneConfig::new(0.01)?);
    /// let p = s.add_particle([0.0, 0.0], 1.0)?;
    /// assert!(!s.is_pinned(p)?);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn is_pinned(&self, particle: ParticleId) -> Result<bool, Error> {
        Ok(self.particles[self.slot(particle)?].inverse_mass == 0.0)
    }

    /// True when a free particle's island is asleep (pinned particles are never stepped
    /// and report `false`).
    ///
    /// # Errors
    ///
    /// [`Error::Stale`] for an id that names no live particle.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 2, 1, 1>::new(SceneConfig::new(0.01)?);
    /// let p = s.add_particle([0.0, 0.0], 1.0)?;
    /// for _ in 0..60 {
    ///     let _ = s.step();
    /// }
    /// assert!(s.is_asleep(p)?); // at rest for half a second
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn is_asleep(&self, particle: ParticleId) -> Result<bool, Error> {
        let p = self.particles[self.slot(particle)?];
        Ok(p.inverse_mass > 0.0 && !self.islands[p.island as usize].awake)
    }

    /// The rest length of a spring.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`] for an id that names no live spring.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?);
    /// let (a, b) = (s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?);
    /// let added = s.add_spring(a, b, 0.75, &Tuning::rigid(0.01)?)?;
    /// assert_eq!(s.rest_length(added.spring)?, 0.75);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn rest_length(&self, spring: SpringId) -> Result<S, Error> {
        let s = &self.springs[self.spring_slot(spring)?];
        let rest = if s.swapped {
            L::flipped(&s.rest)
        } else {
            s.rest
        };
        Ok(L::rest_length(&rest))
    }

    /// The particles at the two ends of a spring.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`] for an id that names no live spring.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?);
    /// let (a, b) = (s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?);
    /// let added = s.add_spring(a, b, 1.0, &Tuning::rigid(0.01)?)?;
    /// assert_eq!(s.ends(added.spring)?, (a, b));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn ends(&self, spring: SpringId) -> Result<(ParticleId, ParticleId), Error> {
        let s = &self.springs[self.spring_slot(spring)?];
        let (a, b) = (self.id_of(s.a as usize), self.id_of(s.b as usize));
        Ok(if s.swapped { (b, a) } else { (a, b) })
    }

    /// The coefficients a spring runs with (after any clamping, in the backend's
    /// precision), as a raw tuning at the scene's `dt`.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`] for an id that names no live spring.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f64, 1, 2, 1>::new(SceneConfig::new(0.01)?);
    /// let (a, b) = (s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?);
    /// let added = s.add_spring(a, b, 1.0, &Tuning::rigid(0.01)?)?;
    /// assert_eq!(s.tuning(added.spring)?, Tuning::rigid(0.01)?);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn tuning(&self, spring: SpringId) -> Result<Tuning, Error> {
        let (ck, cd) = S::gains_to_f64(&self.springs[self.spring_slot(spring)?].gains);
        Tuning::from_coefficients_extended(ck, cd, self.config.dt)
    }

    /// Live particles, in slot order, with their positions.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?);
    /// s.add_particle([4.0], 1.0)?;
    /// assert_eq!(s.particles().map(|(_, p)| p[0]).sum::<f32>(), 4.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn particles(&self) -> impl Iterator<Item = (ParticleId, [S; D])> + '_ {
        (0..self.particles.len())
            .filter(|&i| self.particles[i].live)
            .map(|i| (self.id_of(i), self.positions[i].map(S::narrow)))
    }

    /// Live springs, in slot order, with their ends.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?);
    /// let (a, b) = (s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?);
    /// s.add_spring(a, b, 1.0, &Tuning::rigid(0.01)?)?;
    /// assert_eq!(s.springs().count(), 1);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn springs(&self) -> impl Iterator<Item = (SpringId, ParticleId, ParticleId)> + '_ {
        self.springs
            .iter()
            .enumerate()
            .filter(|(_, s)| s.kind != Kind::Dead)
            .map(|(i, s)| {
                (
                    SpringId {
                        slot: i as u16,
                        generation: s.generation,
                    },
                    self.id_of(s.a as usize),
                    self.id_of(s.b as usize),
                )
            })
    }

    /// The number of live particles.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?);
    /// assert_eq!(s.particle_count(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn particle_count(&self) -> usize {
        self.particles.iter().filter(|p| p.live).count()
    }

    /// The number of live springs.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?);
    /// assert_eq!(s.spring_count(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn spring_count(&self) -> usize {
        self.springs.iter().filter(|s| s.kind != Kind::Dead).count()
    }

    /// The work one step does now: awake free particles and stepped springs.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?);
    /// s.add_particle([0.0], 1.0)?;
    /// s.add_pinned([1.0])?;
    /// assert_eq!(s.active(), (1, 0));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn active(&self) -> (usize, usize) {
        let springs = self.one_sided.len()
            + self.two_sided.len()
            + self.one_sided_points.len()
            + self.two_sided_points.len();
        (self.free.len(), springs)
    }

    /// The total momentum of the free particles, `Σ m·v` (pinned particles have
    /// unbounded mass and are left out), in `f64`.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f64, 1, 2, 1>::new(SceneConfig::new(0.1)?);
    /// let p = s.add_particle([0.0], 2.0)?;
    /// s.set_velocity(p, [1.5])?;
    /// assert!((s.momentum()[0] - 3.0).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn momentum(&self) -> [f64; D] {
        let mut total = [0.0; D];
        for (slot, p) in self.particles.iter().enumerate() {
            if p.live && p.inverse_mass > 0.0 {
                let (u, per_step) = (
                    self.next_step(slot),
                    p.inverse_mass * self.start_factor(slot),
                );
                for k in 0..D {
                    total[k] += S::state_to_f64(u[k]) / per_step;
                }
            }
        }
        total
    }

    /// The configuration the scene was built with.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?);
    /// assert_eq!(s.config().dt(), 0.01);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn config(&self) -> &SceneConfig<S, D> {
        &self.config
    }

    // ----- id helpers -----

    pub(crate) fn slot(&self, particle: ParticleId) -> Result<usize, Error> {
        let slot = particle.slot as usize;
        match self.particles.get(slot) {
            Some(p) if p.live && p.generation == particle.generation => Ok(slot),
            _ => Err(Error::Stale {
                parameter: Parameter::Particle,
            }),
        }
    }

    pub(crate) fn free_slot(&self, particle: ParticleId) -> Result<usize, Error> {
        let slot = self.slot(particle)?;
        if self.particles[slot].inverse_mass == 0.0 {
            Err(Error::Pinned)
        } else {
            Ok(slot)
        }
    }

    pub(crate) fn spring_slot(&self, spring: SpringId) -> Result<usize, Error> {
        let slot = spring.slot as usize;
        match self.springs.get(slot) {
            Some(s) if s.kind != Kind::Dead && s.generation == spring.generation => Ok(slot),
            _ => Err(Error::Stale {
                parameter: Parameter::Spring,
            }),
        }
    }

    pub(crate) fn id_of(&self, slot: usize) -> ParticleId {
        ParticleId {
            slot: slot as u16,
            generation: self.particles[slot].generation,
        }
    }
}
