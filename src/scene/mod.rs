//! A network of particles and springs: ropes, meshes, jelly, and angular springs.
//!
//! A [`Scene`] holds up to `P` particles and `K` springs in `D` dimensions (heapless, fixed
//! at compile time), in backend `S`, with length kernel `L` (see [`crate::length`]).
//! Everything a step needs is precomputed when the scene changes:
//!
//! - each particle's inverse mass (0 for a pinned particle);
//! - each spring's coefficients, its two-body weights `w_a`, `w_b` (eq. 17–20 through
//!   [`BodyWeights`]), and what its length kernel needs;
//! - which springs have a pinned end (they skip the weights and the pinned side), and
//!   which connect two pinned particles (they are dropped: they could move nothing);
//! - which groups of connected particles ("islands") are awake.
//!
//! # One step, in order
//!
//! 1. **Gravity**: every awake free particle's step velocity gains `g·dt²`.
//! 2. **Springs**, through the crate's one kernel
//!    ([`Coefficients::respond`](crate::kernel::Coefficients::respond)):
//!    - [`Stepper::GaussSeidel`]: the impulse form, spring by spring, in place;
//!    - [`Stepper::Jacobi`]: the force form, every spring from the same state, summed.
//! 3. **Positions**: every awake free particle moves by its step velocity.
//! 4. **Anchors**: pinned particles moved this step forget their step velocity.
//! 5. **Sleep**: an island whose particles all stayed below the sleep threshold long
//!    enough stops being stepped; it costs nothing until something touches it (an
//!    impulse, a teleport, a velocity, a moved anchor, a new or retuned spring).
//!
//! Measured on ten 5-particle ropes hanging at 120 Hz, nine of them still and one swinging
//! (`cargo test --release --test scene_behaviour -- --nocapture`): once the nine have
//! fallen asleep a step visits 10 particles and springs instead of 100, **90 % less work**;
//! over the first 30 s, including the 6.8 s the still ropes take to fall asleep, 70 % less.
//!
//! # Momentum
//!
//! The two bodies of a spring get their velocity changes `−w_a·Δ` and `+w_b·Δ` rounded
//! separately and symmetrically, so two **equal masses** conserve momentum exactly, to
//! the bit, in every backend. With unequal masses the roundings no longer cancel:
//! measured on a free 4×4 jelly with masses 0.25 to 4 over 10 000 steps, the drift is
//! 0.15–0.24 LSB·kg per step, which is 22–23 % of `Σ m|v|` in `I16F16` but 3e−6 to 5e−6
//! in `I32F32` and ~1e−6 in `f32`. (Deriving the lighter body's change from the heavier's would cut it
//! about 4×, but needs the mass ratio in the position format, which fails for pinned ends
//! and ratios beyond the format's range; use `I32F32` where momentum matters.)
//!
//! # Springs that share particles
//!
//! One spring is stable for any coefficients in `[0, 1]²`; springs that share particles
//! are not. When a spring is added or retuned, the scene checks it and its neighbours
//! against [`network_limit`] for the number of springs on their particles, and rejects or
//! clamps by its [`LimitPolicy`].
//!
//! ```
//! use stiffspring::scene::{Scene, SceneConfig};
//! use stiffspring::Tuning;
//!
//! // A 2D rope of 8 particles hanging from a pinned end, at 120 Hz.
//! let config = SceneConfig::new(1.0 / 120.0)?.gravity([0.0, -9.81])?;
//! let mut rope = Scene::<f32, 2, 8, 7>::new(config)?;
//! let tuning = Tuning::from_coefficients(0.3, 0.3)?; // within ¾, the limit for two springs per particle
//! let mut last = rope.add_pinned([0.0, 0.0])?;
//! for i in 1..8 {
//!     let next = rope.add_particle([0.1 * i as f32, 0.0], 0.05)?;
//!     rope.add_spring(last, next, 0.1, tuning)?;
//!     last = next;
//! }
//! for _ in 0..240 {
//!     rope.step();
//! }
//! assert!(rope.position(last)?[1] < -0.3); // it swung down
//! # Ok::<(), stiffspring::Error>(())
//! ```

mod angular;
mod config;
mod islands;
mod limits;
mod step;

pub use angular::{Angle, AngularScene, WrappedAngle};
pub use config::{LimitPolicy, SceneConfig, SleepThreshold, Stepper};
pub use limits::network_limit;

use crate::error::{Error, Parameter, positive};
use crate::kernel::{BodyWeights, Coefficients};
use crate::length::{Exact, LengthKernel};
use crate::scalar::Scalar;
use crate::tuning::Tuning;
use heapless::Vec;

/// A particle of a [`Scene`]. Valid until the particle is removed; a removed particle's
/// slot may be reused by a later one.
///
/// ```
/// # use stiffspring::scene::{Scene, SceneConfig};
/// let mut s = Scene::<f32, 2, 2, 1>::new(SceneConfig::new(0.01)?)?;
/// let p = s.add_particle([0.0, 0.0], 1.0)?;
/// assert_eq!(s.position(p)?, [0.0, 0.0]);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ParticleId(u16);

/// A spring of a [`Scene`]. Valid until the spring is removed; a removed spring's slot
/// may be reused by a later one.
///
/// ```
/// # use stiffspring::scene::{Scene, SceneConfig};
/// # use stiffspring::Tuning;
/// let mut s = Scene::<f32, 2, 2, 1>::new(SceneConfig::new(0.01)?)?;
/// let (a, b) = (s.add_particle([0.0, 0.0], 1.0)?, s.add_particle([1.0, 0.0], 1.0)?);
/// let spring = s.add_spring(a, b, 1.0, Tuning::rigid())?.spring;
/// assert_eq!(s.rest_length(spring)?, 1.0);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SpringId(u16);

impl ParticleId {
    /// The slot index, for arrays parallel to the scene's.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 1, 4, 4>::new(SceneConfig::new(0.01)?)?;
    /// assert_eq!(s.add_particle([0.0], 1.0)?.index(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl SpringId {
    /// The slot index, for arrays parallel to the scene's.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f32, 1, 4, 4>::new(SceneConfig::new(0.01)?)?;
    /// let (a, b) = (s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?);
    /// assert_eq!(s.add_spring(a, b, 1.0, Tuning::rigid())?.spring.index(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// What [`Scene::add_spring`] (and the other calls that check the network limit) did.
///
/// ```
/// use stiffspring::scene::{LimitPolicy, Scene, SceneConfig};
/// use stiffspring::Tuning;
///
/// let config = SceneConfig::new(0.01)?.limit_policy(LimitPolicy::Clamp);
/// let mut s = Scene::<f64, 1, 3, 2>::new(config)?;
/// let p = (0..3)
///     .map(|i| s.add_particle([i as f64], 1.0))
///     .collect::<Result<Vec<_>, _>>()?;
/// assert_eq!(s.add_spring(p[0], p[1], 1.0, Tuning::rigid())?.clamped, 0);
/// // The middle particle now carries two springs: both rigid springs are clamped.
/// assert_eq!(s.add_spring(p[1], p[2], 1.0, Tuning::rigid())?.clamped, 2);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Added {
    /// The spring.
    pub spring: SpringId,
    /// How many springs (this one and its neighbours) had their coefficients lowered to
    /// the network limit under [`LimitPolicy::Clamp`]; always 0 under
    /// [`LimitPolicy::Reject`].
    pub clamped: usize,
}

/// Set-up data of one particle.
#[derive(Clone, Copy, Debug, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Particle {
    /// 0 for a pinned particle.
    pub(crate) inverse_mass: f64,
    /// Live springs with this particle as a free end.
    pub(crate) springs: u16,
    /// The slot of its island's root (free particles only).
    pub(crate) island: u16,
    pub(crate) live: bool,
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
    pub(crate) coefficients: Coefficients<S>,
    pub(crate) weights: BodyWeights<S>,
    pub(crate) kind: Kind,
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
/// ```
/// use stiffspring::length::Linearised;
/// use stiffspring::scene::{Scene, SceneConfig};
/// use stiffspring::{I16F16, Tuning};
///
/// // A 3D triangle in fixed point with the root-free kernel.
/// let mut s = Scene::<I16F16, 3, 3, 3, Linearised>::new(SceneConfig::new(1.0 / 60.0)?)?;
/// let one = I16F16::from_num(1);
/// let zero = I16F16::ZERO;
/// let p = [
///     s.add_particle([zero, zero, zero], 1.0)?,
///     s.add_particle([one, zero, zero], 1.0)?,
///     s.add_particle([zero, one, zero], 1.0)?,
/// ];
/// let t = Tuning::from_coefficients(0.2, 0.2)?;
/// for (a, b) in [(0, 1), (1, 2), (2, 0)] {
///     s.add_spring_at_rest(p[a], p[b], t)?;
/// }
/// s.step();
/// assert_eq!(s.position(p[1])?, [one, zero, zero]); // at rest: nothing moves
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Scene<S: Scalar, const D: usize, const P: usize, const K: usize, L = Exact>
where
    L: LengthKernel<S>,
{
    pub(crate) config: SceneConfig<D>,
    pub(crate) positions: Vec<[S; D], P>,
    pub(crate) step_velocities: Vec<[S; D], P>,
    pub(crate) particles: Vec<Particle, P>,
    pub(crate) springs: Vec<Spring<S, L>, K>,
    pub(crate) islands: Vec<Island, P>,
    /// The schedule: awake free particles, and springs of awake islands by kind.
    pub(crate) free: Vec<u16, P>,
    pub(crate) one_sided: Vec<u16, K>,
    pub(crate) two_sided: Vec<u16, K>,
    /// Roots of awake islands (for the sleep check).
    pub(crate) awake_islands: Vec<u16, P>,
    /// Pinned particles moved since the last step (their step velocity is reset after).
    pub(crate) moved_anchors: Vec<u16, P>,
    /// Jacobi's per-particle sums.
    pub(crate) accumulated: Vec<[S; D], P>,
    /// `g·dt²` in step units; `None` when it is zero in the backend, decided at set-up so
    /// that a scene without gravity skips the stage.
    pub(crate) gravity_step: Option<[S; D]>,
    /// The sleep threshold in step units (`v·dt`), widened to an LSB in fixed point.
    pub(crate) sleep_step_velocity: S,
    /// Steps an island must stay quiet to sleep; 0 when sleeping is off.
    pub(crate) sleep_steps: u32,
    /// [`Scalar::NETWORK_MAGNITUDE`] in the backend.
    pub(crate) bound: S,
}

impl<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>>
    Scene<S, D, P, K, L>
{
    /// An empty scene.
    ///
    /// # Errors
    ///
    /// None today beyond the configuration's own checks; the `Result` leaves room for
    /// checks of later options. Capacities above 65 535 do not compile (ids are 16 bits).
    ///
    /// ```
    /// use stiffspring::scene::{Scene, SceneConfig};
    /// let scene = Scene::<f32, 3, 16, 32>::new(SceneConfig::new(0.01)?)?;
    /// assert_eq!(scene.particle_count(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn new(config: SceneConfig<D>) -> Result<Self, Error> {
        const {
            assert!(P <= u16::MAX as usize && K <= u16::MAX as usize);
        }
        let dt = config.dt;
        let mut g = [S::ZERO; D];
        for (g, a) in g.iter_mut().zip(config.gravity) {
            *g = S::from_f64(a * dt * dt);
        }
        let gravity_step = g.iter().any(|g| *g != S::ZERO).then_some(g);
        let (sleep_step_velocity, sleep_steps) = match config.sleep {
            // In fixed point a braced network does not stop dead: it ends in limit cycles
            // whose step velocities measured 2 to 4 LSB (tests/fixed_point_limits.rs), so
            // the threshold is at least 8 LSB there and every island can fall asleep.
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
                    S::from_f64((t.velocity() * dt).max(8.0 * S::RESOLUTION)),
                    steps.max(1),
                )
            }
            None => (S::ZERO, 0),
        };
        Ok(Scene {
            config,
            positions: Vec::new(),
            step_velocities: Vec::new(),
            particles: Vec::new(),
            springs: Vec::new(),
            islands: Vec::new(),
            free: Vec::new(),
            one_sided: Vec::new(),
            two_sided: Vec::new(),
            awake_islands: Vec::new(),
            moved_anchors: Vec::new(),
            accumulated: Vec::new(),
            gravity_step,
            sleep_step_velocity,
            sleep_steps,
            bound: S::from_f64(S::NETWORK_MAGNITUDE),
        })
    }

    /// Adds a free particle of mass `mass` at rest at `position`.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] / [`Error::NotPositive`] with [`Parameter::Mass`];
    /// [`Error::NotFinite`] / [`Error::OutOfRange`] with [`Parameter::Position`];
    /// [`Error::CapacityFull`]. Nothing is added then.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 2, 1, 1>::new(SceneConfig::new(0.01)?)?;
    /// let p = s.add_particle([1.0, 2.0], 0.5)?;
    /// assert_eq!(s.position(p)?, [1.0, 2.0]);
    /// assert!(s.add_particle([0.0, 0.0], 1.0).is_err()); // full
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn add_particle(&mut self, position: [S; D], mass: f64) -> Result<ParticleId, Error> {
        let mass = positive(mass, Parameter::Mass)?;
        let inverse_mass = 1.0 / mass;
        if inverse_mass <= 0.0 || !inverse_mass.is_finite() {
            // A mass so large its inverse underflows would silently become pinned; one so
            // small that it overflows would give its springs no weights at all.
            return Err(Error::OutOfRange(Parameter::Mass));
        }
        self.insert_particle(position, inverse_mass)
    }

    /// Adds a pinned particle at `position`: an anchor that springs pull on but that
    /// never moves unless [`Scene::set_position`] moves it.
    ///
    /// # Errors
    ///
    /// As [`Scene::add_particle`], without the mass.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 2, 4, 4>::new(SceneConfig::new(0.01)?.gravity([0.0, -10.0])?)?;
    /// let anchor = s.add_pinned([0.0, 0.0])?;
    /// s.step();
    /// assert_eq!(s.position(anchor)?, [0.0, 0.0]);
    /// assert!(s.is_pinned(anchor)?);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn add_pinned(&mut self, position: [S; D]) -> Result<ParticleId, Error> {
        self.insert_particle(position, 0.0)
    }

    fn insert_particle(
        &mut self,
        position: [S; D],
        inverse_mass: f64,
    ) -> Result<ParticleId, Error> {
        check_position(&position)?;
        let particle = Particle {
            inverse_mass,
            springs: 0,
            island: 0,
            live: true,
        };
        let slot = match self.particles.iter().position(|p| !p.live) {
            Some(slot) => {
                self.particles[slot] = particle;
                self.positions[slot] = position;
                self.step_velocities[slot] = [S::ZERO; D];
                slot
            }
            None => {
                if self.particles.is_full() {
                    return Err(Error::CapacityFull);
                }
                // Every per-particle vector has the same length and capacity P; the check
                // above found room, so these pushes succeed.
                let ok = self.particles.push(particle).is_ok()
                    & self.positions.push(position).is_ok()
                    & self.step_velocities.push([S::ZERO; D]).is_ok()
                    & self.islands.push(Island::default()).is_ok()
                    & self.accumulated.push([S::ZERO; D]).is_ok();
                if !ok {
                    return Err(Error::CapacityFull);
                }
                self.particles.len() - 1
            }
        };
        self.particles[slot].island = slot as u16;
        self.islands[slot] = Island {
            awake: true,
            ..Island::default()
        };
        self.rebuild();
        Ok(ParticleId(slot as u16))
    }

    /// Removes a particle and every spring attached to it.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown particle.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f32, 1, 4, 4>::new(SceneConfig::new(0.01)?)?;
    /// let (a, b) = (s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?);
    /// s.add_spring(a, b, 1.0, Tuning::rigid())?;
    /// s.remove_particle(a)?;
    /// assert_eq!((s.particle_count(), s.spring_count()), (1, 0));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn remove_particle(&mut self, particle: ParticleId) -> Result<(), Error> {
        let slot = self.slot(particle)?;
        self.wake_around(slot);
        for i in 0..self.springs.len() {
            let s = self.springs[i];
            if s.kind != Kind::Dead && (s.a as usize == slot || s.b as usize == slot) {
                self.kill_spring(i);
            }
        }
        self.particles[slot].live = false;
        self.rebuild();
        Ok(())
    }

    /// Adds a distance spring of rest length `rest_length` between two particles (in an
    /// [`AngularScene`], an angular spring of rest angle `rest_length`, any finite value).
    ///
    /// The spring and its neighbours are checked against [`network_limit`] and handled
    /// by the scene's [`LimitPolicy`]. A spring between two pinned particles is kept (it
    /// acts again if one of them gets a mass) but never stepped.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown particle;
    /// [`Error::SameParticle`]; [`Error::NotFinite`] / [`Error::NotPositive`] /
    /// [`Error::OutOfRange`] (beyond [`Scalar::NETWORK_MAGNITUDE`]) with
    /// [`Parameter::RestLength`]; [`Error::ExceedsNetworkLimit`] under
    /// [`LimitPolicy::Reject`]; [`Error::CapacityFull`]. Nothing changes then.
    ///
    /// ```
    /// use stiffspring::scene::{LimitPolicy, Scene, SceneConfig};
    /// use stiffspring::{Error, Tuning};
    ///
    /// let mut s = Scene::<f32, 2, 3, 2>::new(SceneConfig::new(0.01)?)?;
    /// let p = (0..3)
    ///     .map(|i| s.add_particle([i as f32, 0.0], 1.0))
    ///     .collect::<Result<Vec<_>, _>>()?;
    /// s.add_spring(p[0], p[1], 1.0, Tuning::rigid())?;
    /// // The middle particle would carry two springs: the limit is ¾ (Gauss-Seidel).
    /// assert_eq!(s.add_spring(p[1], p[2], 1.0, Tuning::rigid()), Err(Error::ExceedsNetworkLimit));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn add_spring(
        &mut self,
        a: ParticleId,
        b: ParticleId,
        rest_length: f64,
        tuning: Tuning,
    ) -> Result<Added, Error> {
        let (sa, sb) = (self.slot(a)?, self.slot(b)?);
        if sa == sb {
            return Err(Error::SameParticle);
        }
        let rest_length = if L::SIGNED_REST {
            crate::error::finite(rest_length, Parameter::RestLength)?
        } else {
            positive(rest_length, Parameter::RestLength)?
        };
        if rest_length.abs() > S::NETWORK_MAGNITUDE {
            return Err(Error::OutOfRange(Parameter::RestLength));
        }
        let slot = match self.springs.iter().position(|s| s.kind == Kind::Dead) {
            Some(slot) => slot,
            None if self.springs.is_full() => return Err(Error::CapacityFull),
            None => self.springs.len(),
        };
        // The share counts with the new spring on both ends, for it and its neighbours.
        let change = Change {
            extra: [Some(sa), Some(sb)],
            freed: None,
        };
        let (tuning, clamped_self) = self.checked(tuning, self.share_count(sa, sb, &change))?;
        let clamps = self.check_neighbours(&[sa, sb], &change)?;
        let spring = Spring {
            a: sa as u16,
            b: sb as u16,
            rest: L::rest(rest_length),
            coefficients: Coefficients::new(&tuning),
            weights: BodyWeights::default(),
            kind: Kind::TwoSided,
        };
        if slot == self.springs.len() {
            if self.springs.push(spring).is_err() {
                return Err(Error::CapacityFull);
            }
        } else {
            self.springs[slot] = spring;
        }
        self.particles[sa].springs += 1;
        self.particles[sb].springs += 1;
        self.classify(slot);
        let clamped = usize::from(clamped_self) + clamps.len();
        self.apply_clamps(clamps);
        self.wake_around(sa);
        self.wake_around(sb);
        self.rebuild();
        Ok(Added {
            spring: SpringId(slot as u16),
            clamped,
        })
    }

    /// Adds a spring whose rest length is the particles' current distance.
    ///
    /// # Errors
    ///
    /// As [`Scene::add_spring`]; [`Error::NotPositive`] with [`Parameter::RestLength`]
    /// when the particles coincide.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f64, 2, 2, 1>::new(SceneConfig::new(0.01)?)?;
    /// let (a, b) = (s.add_particle([0.0, 0.0], 1.0)?, s.add_particle([3.0, 4.0], 1.0)?);
    /// let added = s.add_spring_at_rest(a, b, Tuning::rigid())?;
    /// assert_eq!(s.rest_length(added.spring)?, 5.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn add_spring_at_rest(
        &mut self,
        a: ParticleId,
        b: ParticleId,
        tuning: Tuning,
    ) -> Result<Added, Error> {
        let (pa, pb) = (self.position(a)?, self.position(b)?);
        let mut square = 0.0;
        for k in 0..D {
            let d = pb[k].to_f64() - pa[k].to_f64();
            square += d * d;
        }
        self.add_spring(a, b, crate::tuning::sqrt_f64(square), tuning)
    }

    /// Adds a pinned particle at `point` and a spring from it to `particle`: an anchor
    /// spring. Move the anchor with [`Scene::set_position`].
    ///
    /// # Errors
    ///
    /// As [`Scene::add_pinned`] and [`Scene::add_spring`]; nothing is added then.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f32, 2, 2, 1>::new(SceneConfig::new(0.01)?)?;
    /// let p = s.add_particle([1.0, 0.0], 1.0)?;
    /// let (anchor, _) = s.add_anchor([0.0, 0.0], p, 0.5, Tuning::rigid())?;
    /// s.step();
    /// assert_eq!(s.position(p)?, [0.5, 0.0]); // rigid: at rest length in one step
    /// # let _ = anchor;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn add_anchor(
        &mut self,
        point: [S; D],
        particle: ParticleId,
        rest_length: f64,
        tuning: Tuning,
    ) -> Result<(ParticleId, Added), Error> {
        self.slot(particle)?;
        let anchor = self.add_pinned(point)?;
        match self.add_spring(anchor, particle, rest_length, tuning) {
            Ok(added) => Ok((anchor, added)),
            Err(e) => {
                // Undo the anchor, so that nothing is added on failure.
                let _ = self.remove_particle(anchor);
                Err(e)
            }
        }
    }

    /// Removes a spring.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown spring.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?)?;
    /// let (a, b) = (s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?);
    /// let added = s.add_spring(a, b, 1.0, Tuning::rigid())?;
    /// s.remove_spring(added.spring)?;
    /// assert_eq!(s.spring_count(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn remove_spring(&mut self, spring: SpringId) -> Result<(), Error> {
        let slot = self.spring_slot(spring)?;
        let (a, b) = (self.springs[slot].a as usize, self.springs[slot].b as usize);
        self.kill_spring(slot);
        self.wake_around(a);
        self.wake_around(b);
        self.rebuild();
        Ok(())
    }

    /// Retunes a spring, checked against the network limit like a new one.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown spring;
    /// [`Error::ExceedsNetworkLimit`] under [`LimitPolicy::Reject`].
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?)?;
    /// let (a, b) = (s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?);
    /// let added = s.add_spring(a, b, 1.0, Tuning::rigid())?;
    /// s.set_tuning(added.spring, Tuning::from_coefficients(0.1, 0.2)?)?;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_tuning(&mut self, spring: SpringId, tuning: Tuning) -> Result<Added, Error> {
        let slot = self.spring_slot(spring)?;
        let (a, b) = (self.springs[slot].a as usize, self.springs[slot].b as usize);
        let degree = self.share_count(a, b, &Change::NONE);
        let (tuning, clamped) = self.checked(tuning, degree)?;
        self.springs[slot].coefficients = Coefficients::new(&tuning);
        self.wake_around(a);
        self.wake_around(b);
        self.rebuild();
        Ok(Added {
            spring,
            clamped: usize::from(clamped),
        })
    }

    /// Changes a particle's mass (`Some(mass)`) or pins it (`None`); the weights of its
    /// springs are recomputed. Its velocity is kept (a newly pinned particle stops).
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`]; [`Error::NotFinite`] /
    /// [`Error::NotPositive`] with [`Parameter::Mass`]; [`Error::ExceedsNetworkLimit`]
    /// when freeing a pinned particle raises its springs' share count above what their
    /// coefficients allow (under [`LimitPolicy::Reject`]). Nothing changes then.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 1, 1, 1>::new(SceneConfig::new(0.01)?)?;
    /// let p = s.add_pinned([0.0])?;
    /// s.set_mass(p, Some(2.0))?;
    /// assert!(!s.is_pinned(p)?);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_mass(&mut self, particle: ParticleId, mass: Option<f64>) -> Result<(), Error> {
        let slot = self.slot(particle)?;
        let inverse_mass = match mass {
            Some(m) => {
                let inverse = 1.0 / positive(m, Parameter::Mass)?;
                if inverse <= 0.0 || !inverse.is_finite() {
                    return Err(Error::OutOfRange(Parameter::Mass));
                }
                inverse
            }
            None => 0.0,
        };
        // Freeing a pinned particle makes its springs count on it: check them first.
        let change = Change {
            extra: [None, None],
            freed: (self.particles[slot].inverse_mass == 0.0 && inverse_mass > 0.0).then_some(slot),
        };
        let clamps = self.check_neighbours(&[slot], &change)?;
        self.particles[slot].inverse_mass = inverse_mass;
        if inverse_mass == 0.0 {
            self.step_velocities[slot] = [S::ZERO; D];
        }
        for i in 0..self.springs.len() {
            let s = &self.springs[i];
            if s.kind != Kind::Dead && (s.a as usize == slot || s.b as usize == slot) {
                self.classify(i);
            }
        }
        self.apply_clamps(clamps);
        self.wake_around(slot);
        self.rebuild();
        Ok(())
    }

    /// Moves a particle. A free particle teleports and keeps its velocity; a pinned one
    /// is an anchor being moved: for this step its step velocity is the distance moved,
    /// so the damping of its springs sees the anchor's motion, and it is zero again after.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`]; [`Error::NotFinite`] /
    /// [`Error::OutOfRange`] with [`Parameter::Position`]. Nothing changes then.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 2, 1, 1>::new(SceneConfig::new(0.01)?)?;
    /// let p = s.add_particle([0.0, 0.0], 1.0)?;
    /// s.set_position(p, [2.0, 1.0])?;
    /// assert_eq!(s.position(p)?, [2.0, 1.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_position(&mut self, particle: ParticleId, position: [S; D]) -> Result<(), Error> {
        let slot = self.slot(particle)?;
        check_position(&position)?;
        if self.particles[slot].inverse_mass == 0.0 {
            let old = self.positions[slot];
            let mut moved = [S::ZERO; D];
            for k in 0..D {
                moved[k] = position[k].sub(old[k]);
            }
            self.step_velocities[slot] = moved;
            if !self.moved_anchors.contains(&(slot as u16)) {
                // Capacity P and distinct slots: always room.
                let _ = self.moved_anchors.push(slot as u16);
            }
        }
        self.positions[slot] = position;
        if self.wake_around(slot) {
            self.reschedule();
        }
        Ok(())
    }

    /// Sets a free particle's velocity, in units per second.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`]; [`Error::Pinned`];
    /// [`Error::NotFinite`] / [`Error::OutOfRange`] with [`Parameter::Velocity`].
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f64, 1, 1, 1>::new(SceneConfig::new(0.5)?)?;
    /// let p = s.add_particle([0.0], 1.0)?;
    /// s.set_velocity(p, [2.0])?;
    /// s.step();
    /// assert_eq!(s.position(p)?, [1.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_velocity(&mut self, particle: ParticleId, velocity: [S; D]) -> Result<(), Error> {
        let slot = self.free_slot(particle)?;
        let mut u = [S::ZERO; D];
        for k in 0..D {
            u[k] = step_value(velocity[k].to_f64() * self.config.dt, Parameter::Velocity)?;
        }
        self.step_velocities[slot] = u;
        if self.wake_around(slot) {
            self.reschedule();
        }
        Ok(())
    }

    /// Gives a free particle an impulse `j` (mass · units per second): its velocity
    /// changes by `j/m`.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`]; [`Error::Pinned`];
    /// [`Error::NotFinite`] / [`Error::OutOfRange`] with [`Parameter::Impulse`].
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f64, 1, 1, 1>::new(SceneConfig::new(0.5)?)?;
    /// let p = s.add_particle([0.0], 2.0)?;
    /// s.apply_impulse(p, [4.0])?; // Δv = 2 per second
    /// assert_eq!(s.velocity(p)?, [2.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn apply_impulse(&mut self, particle: ParticleId, impulse: [f64; D]) -> Result<(), Error> {
        let slot = self.free_slot(particle)?;
        let scale = self.particles[slot].inverse_mass * self.config.dt;
        let mut u = self.step_velocities[slot];
        for k in 0..D {
            if !impulse[k].is_finite() {
                return Err(Error::NotFinite(Parameter::Impulse));
            }
            u[k] = step_value(u[k].to_f64() + impulse[k] * scale, Parameter::Impulse)?;
        }
        self.step_velocities[slot] = u;
        if self.wake_around(slot) {
            self.reschedule();
        }
        Ok(())
    }

    /// A particle's position.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown particle.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 2, 1, 1>::new(SceneConfig::new(0.01)?)?;
    /// let p = s.add_particle([1.0, 2.0], 1.0)?;
    /// assert_eq!(s.position(p)?, [1.0, 2.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn position(&self, particle: ParticleId) -> Result<[S; D], Error> {
        Ok(self.positions[self.slot(particle)?])
    }

    /// A particle's step velocity `u = v·dt`.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown particle.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 2, 1, 1>::new(SceneConfig::new(0.01)?)?;
    /// let p = s.add_particle([1.0, 2.0], 1.0)?;
    /// assert_eq!(s.step_velocity(p)?, [0.0, 0.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn step_velocity(&self, particle: ParticleId) -> Result<[S; D], Error> {
        Ok(self.step_velocities[self.slot(particle)?])
    }

    /// A particle's velocity in units per second, `u/dt`.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown particle.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f64, 1, 1, 1>::new(SceneConfig::new(0.1)?)?;
    /// let p = s.add_particle([0.0], 1.0)?;
    /// s.set_velocity(p, [3.0])?;
    /// assert!((s.velocity(p)?[0] - 3.0).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn velocity(&self, particle: ParticleId) -> Result<[S; D], Error> {
        let u = self.step_velocity(particle)?;
        let mut v = [S::ZERO; D];
        for k in 0..D {
            v[k] = S::from_f64(u[k].to_f64() / self.config.dt);
        }
        Ok(v)
    }

    /// True for a pinned particle.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown particle.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 2, 1, 1>::new(SceneConfig::new(0.01)?)?;
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
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown particle.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 2, 1, 1>::new(SceneConfig::new(0.01)?)?;
    /// let p = s.add_particle([0.0, 0.0], 1.0)?;
    /// for _ in 0..60 {
    ///     s.step();
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
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown spring.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?)?;
    /// let (a, b) = (s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?);
    /// let added = s.add_spring(a, b, 0.75, Tuning::rigid())?;
    /// assert_eq!(s.rest_length(added.spring)?, 0.75);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn rest_length(&self, spring: SpringId) -> Result<f64, Error> {
        Ok(L::rest_length(
            &self.springs[self.spring_slot(spring)?].rest,
        ))
    }

    /// The particles at the two ends of a spring.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown spring.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?)?;
    /// let (a, b) = (s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?);
    /// let added = s.add_spring(a, b, 1.0, Tuning::rigid())?;
    /// let (x, y) = s.ends(added.spring)?;
    /// assert!((x, y) == (a, b) || (x, y) == (b, a));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn ends(&self, spring: SpringId) -> Result<(ParticleId, ParticleId), Error> {
        let s = &self.springs[self.spring_slot(spring)?];
        Ok((ParticleId(s.a), ParticleId(s.b)))
    }

    /// The tuning a spring runs with (after any clamping, in the backend's precision).
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown spring.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f64, 1, 2, 1>::new(SceneConfig::new(0.01)?)?;
    /// let (a, b) = (s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?);
    /// let added = s.add_spring(a, b, 1.0, Tuning::rigid())?;
    /// assert_eq!(s.tuning(added.spring)?, Tuning::rigid());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn tuning(&self, spring: SpringId) -> Result<Tuning, Error> {
        Ok(self.springs[self.spring_slot(spring)?]
            .coefficients
            .tuning())
    }

    /// Live particles, in slot order, with their positions.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?)?;
    /// s.add_particle([4.0], 1.0)?;
    /// assert_eq!(s.particles().map(|(_, p)| p[0]).sum::<f32>(), 4.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn particles(&self) -> impl Iterator<Item = (ParticleId, [S; D])> + '_ {
        self.particles
            .iter()
            .zip(self.positions.iter())
            .enumerate()
            .filter(|(_, (p, _))| p.live)
            .map(|(i, (_, x))| (ParticleId(i as u16), *x))
    }

    /// Live springs, in slot order, with their ends.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?)?;
    /// let (a, b) = (s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?);
    /// s.add_spring(a, b, 1.0, Tuning::rigid())?;
    /// assert_eq!(s.springs().count(), 1);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn springs(&self) -> impl Iterator<Item = (SpringId, ParticleId, ParticleId)> + '_ {
        self.springs
            .iter()
            .enumerate()
            .filter(|(_, s)| s.kind != Kind::Dead)
            .map(|(i, s)| (SpringId(i as u16), ParticleId(s.a), ParticleId(s.b)))
    }

    /// The number of live particles.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?)?;
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
    /// let s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?)?;
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
    /// let mut s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?)?;
    /// s.add_particle([0.0], 1.0)?;
    /// s.add_pinned([1.0])?;
    /// assert_eq!(s.active(), (1, 0));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn active(&self) -> (usize, usize) {
        (self.free.len(), self.one_sided.len() + self.two_sided.len())
    }

    /// The total momentum of the free particles, `Σ m·v` (pinned particles have
    /// unbounded mass and are left out), in `f64`.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f64, 1, 2, 1>::new(SceneConfig::new(0.1)?)?;
    /// let p = s.add_particle([0.0], 2.0)?;
    /// s.set_velocity(p, [1.5])?;
    /// assert!((s.momentum()[0] - 3.0).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn momentum(&self) -> [f64; D] {
        let mut total = [0.0; D];
        for (p, u) in self.particles.iter().zip(self.step_velocities.iter()) {
            if p.live && p.inverse_mass > 0.0 {
                for k in 0..D {
                    total[k] += u[k].to_f64() / (p.inverse_mass * self.config.dt);
                }
            }
        }
        total
    }

    /// The configuration the scene was built with.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?)?;
    /// assert_eq!(s.config().dt(), 0.01);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn config(&self) -> &SceneConfig<D> {
        &self.config
    }

    // ----- set-up helpers -----

    fn slot(&self, particle: ParticleId) -> Result<usize, Error> {
        let slot = particle.0 as usize;
        match self.particles.get(slot) {
            Some(p) if p.live => Ok(slot),
            _ => Err(Error::OutOfRange(Parameter::Index)),
        }
    }

    fn free_slot(&self, particle: ParticleId) -> Result<usize, Error> {
        let slot = self.slot(particle)?;
        if self.particles[slot].inverse_mass == 0.0 {
            Err(Error::Pinned)
        } else {
            Ok(slot)
        }
    }

    fn spring_slot(&self, spring: SpringId) -> Result<usize, Error> {
        let slot = spring.0 as usize;
        match self.springs.get(slot) {
            Some(s) if s.kind != Kind::Dead => Ok(slot),
            _ => Err(Error::OutOfRange(Parameter::Index)),
        }
    }

    /// The share count `n` of a spring between slots `a` and `b` under `change`: the
    /// springs on its busiest free end (pinned ends do not move, so springs meeting there
    /// do not compete).
    fn share_count(&self, a: usize, b: usize, change: &Change) -> u16 {
        let mut n = 0;
        for p in [a, b] {
            let free = self.particles[p].inverse_mass > 0.0 || change.freed == Some(p);
            if free {
                let extra = change.extra.iter().filter(|&&e| e == Some(p)).count() as u16;
                n = n.max(self.particles[p].springs + extra);
            }
        }
        n
    }

    /// The tuning as the policy allows it for share count `degree`, and whether it was
    /// clamped.
    fn checked(&self, tuning: Tuning, degree: u16) -> Result<(Tuning, bool), Error> {
        let limit = network_limit(degree as usize, self.config.stepper);
        let (ck, cd) = (tuning.stiffness(), tuning.damping());
        // A stored spring's coefficients are the requested ones rounded to the backend's
        // coefficient format (24 significant bits in f32, 29 fractional bits in I16F16),
        // so a spring tuned exactly at the limit may read back a hair above it; a
        // relative slack of 1e−6, far below any stability margin, keeps it accepted.
        let slack = limit * 1e-6;
        if ck <= limit + slack && cd <= limit + slack {
            return Ok((tuning, false));
        }
        match self.config.policy {
            LimitPolicy::Reject => Err(Error::ExceedsNetworkLimit),
            LimitPolicy::Clamp => {
                let clamped = Tuning::from_coefficients(ck.min(limit), cd.clamp(0.0, limit))?;
                Ok((clamped, true))
            }
        }
    }

    /// Checks every live spring touching `slots` against its limit under `change`, and
    /// returns the clamps to apply once the change commits (empty under
    /// [`LimitPolicy::Reject`], which fails instead).
    fn check_neighbours(
        &self,
        slots: &[usize],
        change: &Change,
    ) -> Result<Vec<(u16, Tuning), K>, Error> {
        let mut clamps: Vec<(u16, Tuning), K> = Vec::new();
        for (i, s) in self.springs.iter().enumerate() {
            let (a, b) = (s.a as usize, s.b as usize);
            if s.kind == Kind::Dead || !(slots.contains(&a) || slots.contains(&b)) {
                continue;
            }
            let degree = self.share_count(a, b, change);
            let (tuning, clamped) = self.checked(s.coefficients.tuning(), degree)?;
            if clamped {
                // At most K springs: always room.
                let _ = clamps.push((i as u16, tuning));
            }
        }
        Ok(clamps)
    }

    fn apply_clamps(&mut self, clamps: Vec<(u16, Tuning), K>) {
        for (i, tuning) in clamps {
            self.springs[i as usize].coefficients = Coefficients::new(&tuning);
        }
    }

    /// Marks a spring dead and takes it off its ends' share counts.
    fn kill_spring(&mut self, slot: usize) {
        let s = self.springs[slot];
        for p in [s.a as usize, s.b as usize] {
            self.particles[p].springs = self.particles[p].springs.saturating_sub(1);
        }
        self.springs[slot].kind = Kind::Dead;
    }

    /// Sets a spring's kind and weights from its ends' inverse masses; a one-sided
    /// spring is oriented with its pinned end as `a`.
    fn classify(&mut self, slot: usize) {
        let s = self.springs[slot];
        let (ia, ib) = (
            self.particles[s.a as usize].inverse_mass,
            self.particles[s.b as usize].inverse_mass,
        );
        let spring = &mut self.springs[slot];
        match (ia > 0.0, ib > 0.0) {
            (false, false) => spring.kind = Kind::Inert,
            (false, true) => spring.kind = Kind::OneSided,
            (true, false) => {
                // Swap so that the pinned end is `a`; the extension |d| is symmetric.
                core::mem::swap(&mut spring.a, &mut spring.b);
                spring.kind = Kind::OneSided;
            }
            (true, true) => {
                spring.kind = Kind::TwoSided;
                // Both inverse masses are finite and positive here: cannot fail.
                spring.weights = BodyWeights::from_inverse_masses(ia, ib).unwrap_or_default();
            }
        }
    }
}

/// A hypothetical change to the share counts: one more spring on each `extra` slot, and a
/// pinned particle that becomes free.
struct Change {
    extra: [Option<usize>; 2],
    freed: Option<usize>,
}

impl Change {
    const NONE: Change = Change {
        extra: [None, None],
        freed: None,
    };
}

/// Positions must be finite and within the backend's network magnitude.
fn check_position<S: Scalar, const D: usize>(position: &[S; D]) -> Result<(), Error> {
    crate::value::check_within(position, S::NETWORK_MAGNITUDE, Parameter::Position)
}

/// A step quantity (`v·dt`, `u + j/m·dt`) converted to the backend, or an error if it is
/// not finite or beyond the network magnitude.
fn step_value<S: Scalar>(value: f64, what: Parameter) -> Result<S, Error> {
    if !value.is_finite() {
        Err(Error::NotFinite(what))
    } else if value.abs() > S::NETWORK_MAGNITUDE {
        Err(Error::OutOfRange(what))
    } else {
        Ok(S::from_f64(value))
    }
}
