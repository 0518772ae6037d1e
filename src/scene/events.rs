//! What a scene's step reports.

use super::{ParticleId, Scene};
use crate::length::LengthKernel;
use crate::scalar::Scalar;

/// What one [`Scene::step`] did: what a redraw of the moving parts needs, and when the
/// scene can stop being stepped.
///
/// ```
/// use stiffspring::scene::{Scene, SceneConfig, SleepThreshold};
///
/// let config = SceneConfig::new(0.01)?.sleep(SleepThreshold::new(0.01, 0.05)?);
/// let mut s = Scene::<f32, 1, 1, 1>::new(config);
/// let p = s.add_particle([0.0], 1.0)?;
/// let mut steps = 0;
/// loop {
///     steps += 1;
///     let motion = s.step();
///     if motion.fell_asleep > 0 {
///         assert_eq!(s.just_fell_asleep().collect::<Vec<_>>(), [p]);
///         break;
///     }
/// }
/// assert_eq!(steps, 5); // still for 0.05 s
/// assert_eq!(s.step().moving, 0); // asleep: nothing to step
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[must_use = "a step reports what to redraw; `let _ =` discards it"]
pub struct SceneMotion {
    /// Free particles stepped (their islands are awake); [`Scene::moving`] names them.
    pub moving: usize,
    /// Particles whose island fell asleep in this step; [`Scene::just_fell_asleep`] names
    /// them.
    pub fell_asleep: usize,
    /// Islands that calls since the previous step woke up (a teleport, an impulse, a new
    /// spring...).
    pub woke: usize,
}

impl<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>>
    Scene<S, D, P, K, L>
{
    /// The particles the next step moves (those of awake islands), with their positions.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?);
    /// let p = s.add_particle([1.0], 1.0)?;
    /// s.add_pinned([0.0])?;
    /// assert_eq!(s.moving().collect::<Vec<_>>(), [(p, [1.0])]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn moving(&self) -> impl Iterator<Item = (ParticleId, [S; D])> + '_ {
        self.free.iter().map(|&p| {
            let p = p as usize;
            (self.id_of(p), self.positions[p].map(S::narrow))
        })
    }

    /// The particles whose island fell asleep in the last step.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?);
    /// assert_eq!(s.just_fell_asleep().count(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn just_fell_asleep(&self) -> impl Iterator<Item = ParticleId> + '_ {
        self.fell_asleep.iter().map(|&p| self.id_of(p as usize))
    }
}
