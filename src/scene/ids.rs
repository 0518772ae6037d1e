//! Handles to a scene's particles and springs.
//!
//! An id is a slot and the generation of what lives in it: a removed particle's slot is
//! reused by a later one, but its old id never names the newcomer. Every call that takes
//! a stale id returns [`Error::Stale`](crate::Error::Stale) and changes nothing.

/// A particle of a [`Scene`](super::Scene).
///
/// ```
/// use stiffspring::scene::{Scene, SceneConfig};
/// use stiffspring::{Error, Parameter};
///
/// let mut s = Scene::<f32, 2, 2, 1>::new(SceneConfig::new(0.01)?);
/// let b = s.add_particle([0.0, 0.0], 1.0)?;
/// s.remove_particle(b)?;
/// let c = s.add_particle([5.0, 0.0], 1.0)?;
/// assert_eq!(b.slot(), c.slot()); // the slot is reused...
/// assert_eq!(s.position(b), Err(Error::Stale { parameter: Parameter::Particle })); // ...the id is not
/// assert_eq!(s.position(c)?, [5.0, 0.0]);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ParticleId {
    pub(crate) slot: u16,
    pub(crate) generation: u32,
}

/// A spring of a [`Scene`](super::Scene); see [`ParticleId`] for the generations.
///
/// ```
/// use stiffspring::scene::{Scene, SceneConfig};
/// use stiffspring::Tuning;
///
/// let mut s = Scene::<f32, 2, 2, 1>::new(SceneConfig::new(0.01)?);
/// let (a, b) = (s.add_particle([0.0, 0.0], 1.0)?, s.add_particle([1.0, 0.0], 1.0)?);
/// let spring = s.add_spring(a, b, 1.0, &Tuning::rigid(0.01)?)?.spring;
/// assert_eq!(s.rest_length(spring)?, 1.0);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SpringId {
    pub(crate) slot: u16,
    pub(crate) generation: u32,
}

impl ParticleId {
    /// The slot index, for arrays parallel to the scene's (`0..P`).
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 1, 4, 4>::new(SceneConfig::new(0.01)?);
    /// assert_eq!(s.add_particle([0.0], 1.0)?.slot(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn slot(self) -> usize {
        self.slot as usize
    }
}

impl SpringId {
    /// The slot index, for arrays parallel to the scene's (`0..K`).
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f32, 1, 4, 4>::new(SceneConfig::new(0.01)?);
    /// let (a, b) = (s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?);
    /// assert_eq!(s.add_spring(a, b, 1.0, &Tuning::rigid(0.01)?)?.spring.slot(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn slot(self) -> usize {
        self.slot as usize
    }
}

/// What [`Scene::add_spring`](super::Scene::add_spring) (and the other calls that check
/// the network limit) did.
///
/// ```
/// use stiffspring::scene::{LimitPolicy, Scene, SceneConfig};
/// use stiffspring::Tuning;
///
/// let config = SceneConfig::new(0.01)?.limit_policy(LimitPolicy::Clamp);
/// let mut s = Scene::<f64, 1, 3, 2>::new(config);
/// let p = [s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?, s.add_particle([2.0], 1.0)?];
/// let rigid = Tuning::rigid(0.01)?;
/// assert_eq!(s.add_spring(p[0], p[1], 1.0, &rigid)?.clamped, 0);
/// // The middle particle now carries two springs: both rigid springs are clamped.
/// assert_eq!(s.add_spring(p[1], p[2], 1.0, &rigid)?.clamped, 2);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Added {
    /// The spring.
    pub spring: SpringId,
    /// How many springs (this one and its neighbours) had their coefficients lowered to
    /// the network limit under [`LimitPolicy::Clamp`](super::LimitPolicy::Clamp); always
    /// 0 under [`LimitPolicy::Reject`](super::LimitPolicy::Reject).
    pub clamped: usize,
}
