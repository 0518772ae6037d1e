//! Building and changing a scene: particles, springs, anchors, masses, tunings.
//!
//! Every call here validates all of its input first and changes nothing when it fails.

use super::limits::Change;
use super::{Added, Island, Kind, Particle, ParticleId, Scene, Spring, SpringId};
use crate::error::{Bound, Error, Parameter};
use crate::input::gains_of;
use crate::kernel::BodyWeights;
use crate::length::LengthKernel;
use crate::scalar::Scalar;
use crate::tuning::Tuning;

/// A spring's validated set-up data, before it is placed.
struct NewSpring<S: Scalar, L: LengthKernel<S>> {
    rest: L::Rest,
    gains: S::Gains,
    release: f64,
    coefficients: (f64, f64),
}

impl<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>>
    Scene<S, D, P, K, L>
{
    /// Adds a free particle of mass `mass` at rest at `position`.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for the mass (it must be positive,
    /// with a finite inverse) or the position; [`Error::CapacityFull`]. Nothing is added
    /// then.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 2, 1, 1>::new(SceneConfig::new(0.01)?);
    /// let p = s.add_particle([1.0, 2.0], 0.5)?;
    /// assert_eq!(s.position(p)?, [1.0, 2.0]);
    /// assert!(s.add_particle([0.0, 0.0], 1.0).is_err()); // full
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn add_particle(&mut self, position: [S; D], mass: S) -> Result<ParticleId, Error> {
        let inverse_mass = inverse_mass(mass)?;
        self.insert_particle(position, inverse_mass)
    }

    /// Adds a pinned particle at `position`: an anchor that springs pull on but that
    /// never moves unless [`Scene::set_position`] moves it (a drag handle, the arbor of a
    /// clock spring).
    ///
    /// # Errors
    ///
    /// As [`Scene::add_particle`], without the mass.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 2, 4, 4>::new(SceneConfig::new(0.01)?.gravity([0.0, -10.0])?);
    /// let anchor = s.add_pinned([0.0, 0.0])?;
    /// let _ = s.step();
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
        for p in position {
            check_network(p, Parameter::Position)?;
        }
        let slot = self.free_particle_slot()?;
        let generation = self.particles.get(slot).map_or(0, |p| p.generation);
        let particle = Particle {
            inverse_mass,
            damping: self.config.damping.0,
            springs: 0,
            island: slot as u16,
            live: true,
            generation,
        };
        let state = position.map(|p| p.widen());
        if slot == self.particles.len() {
            // Every per-particle vector has the same length and capacity P, and
            // `free_particle_slot` found room: these pushes succeed.
            let _ = self.particles.push(particle);
            let _ = self.positions.push(state);
            let _ = self.remainders.push([Default::default(); D]);
            let _ = self.velocities.push([S::STATE_ZERO; D]);
            let _ = self.drag.push(S::factor(self.config.damping.1));
            let _ = self.islands.push(Island::default());
            let _ = self.accumulated.push([S::STATE_ZERO; D]);
        } else {
            self.particles[slot] = particle;
            self.positions[slot] = state;
            self.remainders[slot] = [Default::default(); D];
            self.velocities[slot] = [S::STATE_ZERO; D];
            self.drag[slot] = S::factor(self.config.damping.1);
        }
        self.islands[slot] = Island {
            awake: true,
            ..Island::default()
        };
        self.rebuild();
        Ok(self.id_of(slot))
    }

    /// The slot a new particle would take, or [`Error::CapacityFull`].
    fn free_particle_slot(&self) -> Result<usize, Error> {
        match self.particles.iter().position(|p| !p.live) {
            Some(slot) => Ok(slot),
            None if self.particles.len() < P => Ok(self.particles.len()),
            None => Err(Error::CapacityFull { capacity: P }),
        }
    }

    /// Removes a particle and every spring attached to it. Its id (and theirs) becomes
    /// stale.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`] for an id that names no live particle.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f32, 1, 4, 4>::new(SceneConfig::new(0.01)?);
    /// let (a, b) = (s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?);
    /// s.add_spring(a, b, 1.0, &Tuning::rigid(0.01)?)?;
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
        let p = &mut self.particles[slot];
        p.live = false;
        p.generation = p.generation.wrapping_add(1);
        self.rebuild();
        Ok(())
    }

    /// Adds a distance spring of rest length `rest_length` between two particles (in an
    /// [`AngularScene`](super::AngularScene), an angular spring of rest angle
    /// `rest_length`, any finite value).
    ///
    /// A rest length of zero makes a *point spring* that pulls the particles together:
    /// with a pinned end it is a drag handle or mouse spring (move the pin with
    /// [`Scene::set_position`]). It acts on every axis at once,
    /// `Δu = −(C_k·d + C_d·Δv)` per component of the separation `d` and the relative
    /// velocity `Δv`, with no length and no axis: a distance spring of zero length would
    /// damp only along its axis and let a particle orbit its handle for ever, and its
    /// axis is undefined where the ends meet. Any length kernel takes it (the
    /// [`Linearised`](crate::length::Linearised) one otherwise needs a positive rest
    /// length).
    ///
    /// The spring and its neighbours are checked against
    /// [`network_limit`](super::network_limit) and handled by the scene's
    /// [`LimitPolicy`](super::LimitPolicy). A spring between two pinned particles is kept
    /// (it acts again if one of them gets a mass) but never stepped.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`] for a particle; [`Error::SameParticle`];
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] with [`Parameter::RestLength`];
    /// [`Error::TimeStepMismatch`] when the tuning is sampled at another `dt` than the
    /// scene's; [`Error::Unrepresentable`] when the backend cannot hold the tuning;
    /// [`Error::ExceedsNetworkLimit`] under [`LimitPolicy::Reject`](super::LimitPolicy::Reject);
    /// [`Error::CapacityFull`]. Nothing changes then.
    ///
    /// ```
    /// use stiffspring::scene::{Scene, SceneConfig};
    /// use stiffspring::{Error, Tuning};
    ///
    /// let mut s = Scene::<f32, 2, 3, 2>::new(SceneConfig::new(0.01)?);
    /// let p = [s.add_particle([0.0, 0.0], 1.0)?, s.add_particle([1.0, 0.0], 1.0)?, s.add_particle([2.0, 0.0], 1.0)?];
    /// let rigid = Tuning::rigid(0.01)?;
    /// s.add_spring(p[0], p[1], 1.0, &rigid)?;
    /// // The middle particle would carry two springs: the limit is ¾ (Gauss-Seidel).
    /// assert!(matches!(s.add_spring(p[1], p[2], 1.0, &rigid), Err(Error::ExceedsNetworkLimit { .. })));
    /// // Tuned for 60 Hz, added to a scene stepped at 100 Hz:
    /// let t60 = Tuning::from_frequency(2.0, 0.7, 1.0 / 60.0)?;
    /// assert!(matches!(s.add_spring(p[1], p[2], 1.0, &t60), Err(Error::TimeStepMismatch { .. })));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn add_spring(
        &mut self,
        a: ParticleId,
        b: ParticleId,
        rest_length: S,
        tuning: &Tuning,
    ) -> Result<Added, Error> {
        let (sa, sb) = (self.slot(a)?, self.slot(b)?);
        if sa == sb {
            return Err(Error::SameParticle);
        }
        let new = self.new_spring(rest_length, tuning)?;
        let slot = self.free_spring_slot()?;
        // The share counts with the new spring on both ends, for it and its neighbours.
        let change = Change {
            extra: [Some(sa), Some(sb)],
            freed: None,
        };
        let factors = self.stiffening(sa, sb, &new.rest);
        let (coefficients, clamped_self) = self.checked(
            new.coefficients,
            self.share_count(sa, sb, &change),
            factors,
            (sa, sb),
        )?;
        let clamps = self.check_neighbours(&[sa, sb], &change)?;
        let gains = if clamped_self {
            self.gains_at(coefficients)?
        } else {
            new.gains
        };
        Ok(self.place_spring(
            slot,
            sa,
            sb,
            new.rest,
            gains,
            new.release,
            clamped_self,
            clamps,
        ))
    }

    /// Places a validated spring in `slot` and applies the clamps that go with it.
    #[allow(clippy::too_many_arguments)]
    fn place_spring(
        &mut self,
        slot: usize,
        sa: usize,
        sb: usize,
        rest: L::Rest,
        gains: S::Gains,
        release: f64,
        clamped_self: bool,
        clamps: heapless::Vec<(u16, S::Gains), K>,
    ) -> Added {
        let generation = self.springs.get(slot).map_or(0, |s| s.generation);
        let spring = Spring {
            a: sa as u16,
            b: sb as u16,
            rest,
            gains,
            weights: BodyWeights::default(),
            kind: Kind::TwoSided,
            release,
            generation,
            swapped: false,
            point: !L::SIGNED_REST && L::rest_length(&rest).to_f64() == 0.0,
        };
        if slot == self.springs.len() {
            // `free_spring_slot` found room.
            let _ = self.springs.push(spring);
        } else {
            self.springs[slot] = spring;
        }
        self.particles[sa].springs += 1;
        self.particles[sb].springs += 1;
        self.classify(slot);
        let clamped = usize::from(clamped_self) + clamps.len();
        for (i, gains) in clamps {
            self.retune(i as usize, gains);
        }
        self.apply_pull(slot, true);
        self.wake_around(sa);
        self.wake_around(sb);
        self.rebuild();
        Added {
            spring: SpringId {
                slot: slot as u16,
                generation,
            },
            clamped,
        }
    }

    /// Validates a spring's rest length and tuning for this scene.
    fn new_spring(&self, rest_length: S, tuning: &Tuning) -> Result<NewSpring<S, L>, Error> {
        let r = rest_length.to_f64();
        let bound = if L::SIGNED_REST {
            Bound::MagnitudeAtMost { max: S::MAX }
        } else if L::ZERO_REST {
            Bound::Within {
                min: 0.0,
                max: S::MAX,
            }
        } else {
            Bound::Within {
                min: S::RESOLUTION.max(f64::MIN_POSITIVE),
                max: S::MAX,
            }
        };
        crate::error::check(r, Parameter::RestLength, bound)?;
        let dt = self.config.dt;
        // Tunings built the same way at the same dt are equal to the bit; the slack
        // forgives a dt computed another way (1/60 against 0.016666…7).
        if (tuning.dt() - dt).abs() > 1e-9 * dt {
            return Err(Error::TimeStepMismatch {
                expected: dt,
                found: tuning.dt(),
            });
        }
        let gains = gains_of::<S>(tuning)?;
        // P̃ of the kept start ũ = P̃·x (see `Scene::release`); 0 for raw coefficients.
        let release = match tuning.oscillator() {
            Some(_) => tuning.start_weights().0,
            None => 0.0,
        };
        Ok(NewSpring {
            rest: L::rest(rest_length),
            gains,
            release,
            coefficients: S::gains_to_f64(&gains),
        })
    }

    /// The slot a new spring would take, or [`Error::CapacityFull`].
    fn free_spring_slot(&self) -> Result<usize, Error> {
        match self.springs.iter().position(|s| s.kind == Kind::Dead) {
            Some(slot) => Ok(slot),
            None if self.springs.len() < K => Ok(self.springs.len()),
            None => Err(Error::CapacityFull { capacity: K }),
        }
    }

    /// Adds a spring whose rest length is the particles' current distance.
    ///
    /// # Errors
    ///
    /// As [`Scene::add_spring`].
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f64, 2, 2, 1>::new(SceneConfig::new(0.01)?);
    /// let (a, b) = (s.add_particle([0.0, 0.0], 1.0)?, s.add_particle([3.0, 4.0], 1.0)?);
    /// let added = s.add_spring_at_rest(a, b, &Tuning::rigid(0.01)?)?;
    /// assert_eq!(s.rest_length(added.spring)?, 5.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn add_spring_at_rest(
        &mut self,
        a: ParticleId,
        b: ParticleId,
        tuning: &Tuning,
    ) -> Result<Added, Error> {
        let (sa, sb) = (self.slot(a)?, self.slot(b)?);
        let d = self.separation(sa, sb);
        // An angle kernel's rest value is the signed difference it measures from a zero
        // rest; a distance kernel's the exact distance, whatever kernel measures it.
        let rest = if L::SIGNED_REST {
            L::measure(&d, &L::rest(S::ZERO)).0
        } else {
            S::norm(&d)
        };
        self.add_spring(a, b, S::narrow(rest), tuning)
    }

    /// Adds a pinned particle at `point` and a spring from it to `particle`: an anchor,
    /// or with a zero rest length a drag handle. Move the anchor with
    /// [`Scene::set_position`].
    ///
    /// # Errors
    ///
    /// As [`Scene::add_pinned`] and [`Scene::add_spring`]. Everything is checked before
    /// anything is added, so nothing is added (and nothing wakes) then.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f32, 2, 2, 1>::new(SceneConfig::new(0.01)?);
    /// let p = s.add_particle([1.0, 0.0], 1.0)?;
    /// let (handle, _) = s.add_anchor([0.0, 0.0], p, 0.0, &Tuning::rigid(0.01)?)?;
    /// let _ = s.step();
    /// assert_eq!(s.position(p)?, [0.0, 0.0]); // rigid, zero length: on the handle in one step
    /// s.set_position(handle, [3.0, 0.0])?; // drag
    /// let _ = (s.step(), s.step()); // the damper matches the handle's motion, then stops
    /// assert_eq!(s.position(p)?, [3.0, 0.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn add_anchor(
        &mut self,
        point: [S; D],
        particle: ParticleId,
        rest_length: S,
        tuning: &Tuning,
    ) -> Result<(ParticleId, Added), Error> {
        let target = self.slot(particle)?;
        for p in point {
            check_network(p, Parameter::Position)?;
        }
        let anchor_slot = self.free_particle_slot()?;
        let slot = self.free_spring_slot()?;
        let new = self.new_spring(rest_length, tuning)?;
        // The anchor is pinned: only the particle's end counts the new spring.
        let change = Change {
            extra: [Some(target), None],
            freed: None,
        };
        let degree = self.share_count_of(target, &change);
        // The pin goes exactly at `point`: the stretch is measured from there.
        let mut d = [S::STATE_ZERO; D];
        for k in 0..D {
            d[k] = S::state_sub(self.positions[target][k], point[k].widen());
        }
        let length = L::rest_length(&new.rest).to_f64();
        let factors = if L::SIGNED_REST || length <= 0.0 {
            (1.0, 1.0)
        } else {
            L::stiffening(S::state_to_f64(S::norm(&d)) / length)
        };
        let (coefficients, clamped_self) =
            self.checked(new.coefficients, degree, factors, (target, target))?;
        let clamps = self.check_neighbours(&[target], &change)?;
        let gains = if clamped_self {
            self.gains_at(coefficients)?
        } else {
            new.gains
        };
        // Everything is checked: from here on nothing fails.
        let anchor = self.insert_particle(point, 0.0)?;
        debug_assert_eq!(anchor.slot(), anchor_slot);
        let added = self.place_spring(
            slot,
            anchor.slot(),
            target,
            new.rest,
            gains,
            new.release,
            clamped_self,
            clamps,
        );
        Ok((anchor, added))
    }

    /// Removes a spring; its id becomes stale.
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
    /// [`Error::Stale`] for an id that names no live spring; as [`Scene::add_spring`]
    /// for the tuning. Nothing changes then.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// # use stiffspring::Tuning;
    /// let mut s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?);
    /// let (a, b) = (s.add_particle([0.0], 1.0)?, s.add_particle([1.0], 1.0)?);
    /// let added = s.add_spring(a, b, 1.0, &Tuning::rigid(0.01)?)?;
    /// s.set_tuning(added.spring, &Tuning::from_coefficients(0.1, 0.2, 0.01)?)?;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_tuning(&mut self, spring: SpringId, tuning: &Tuning) -> Result<Added, Error> {
        let slot = self.spring_slot(spring)?;
        let (a, b) = (self.springs[slot].a as usize, self.springs[slot].b as usize);
        let s = self.springs[slot];
        let rest = if s.swapped {
            L::flipped(&s.rest)
        } else {
            s.rest
        };
        let new = self.new_spring(L::rest_length(&rest), tuning)?;
        let degree = self.share_count(a, b, &Change::NONE);
        let factors = self.stiffening(a, b, &s.rest);
        let (coefficients, clamped) = self.checked(new.coefficients, degree, factors, (a, b))?;
        let gains = if clamped {
            self.gains_at(coefficients)?
        } else {
            new.gains
        };
        self.retune(slot, gains);
        self.springs[slot].release = new.release;
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
    /// [`Error::Stale`]; [`Error::NotFinite`] or [`Error::OutOfRange`] for the mass;
    /// [`Error::ExceedsNetworkLimit`] when freeing a pinned particle raises its springs'
    /// share count above what their coefficients allow (under
    /// [`LimitPolicy::Reject`](super::LimitPolicy::Reject)). Nothing changes then.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 1, 1, 1>::new(SceneConfig::new(0.01)?);
    /// let p = s.add_pinned([0.0])?;
    /// s.set_mass(p, Some(2.0))?;
    /// assert!(!s.is_pinned(p)?);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_mass(&mut self, particle: ParticleId, mass: Option<S>) -> Result<(), Error> {
        let slot = self.slot(particle)?;
        let inverse = match mass {
            Some(m) => inverse_mass(m)?,
            None => 0.0,
        };
        // Freeing a pinned particle makes its springs count on it: check them first.
        let change = Change {
            extra: [None, None],
            freed: (self.particles[slot].inverse_mass == 0.0 && inverse > 0.0).then_some(slot),
        };
        let clamps = self.check_neighbours(&[slot], &change)?;
        // The springs' pulls change with their weights: off before, on after.
        self.repulling(slot, |scene| {
            scene.particles[slot].inverse_mass = inverse;
            if inverse == 0.0 {
                scene.velocities[slot] = [S::STATE_ZERO; D];
            }
            for i in 0..scene.springs.len() {
                let s = &scene.springs[i];
                if s.kind != Kind::Dead && (s.a as usize == slot || s.b as usize == slot) {
                    scene.classify(i);
                }
            }
            for (i, gains) in clamps {
                scene.springs[i as usize].gains = gains;
            }
        });
        self.wake_around(slot);
        self.rebuild();
        Ok(())
    }

    /// Gives spring slot `i` new gains, moving its pull with them.
    fn retune(&mut self, i: usize, gains: S::Gains) {
        self.apply_pull(i, false);
        self.springs[i].gains = gains;
        self.apply_pull(i, true);
    }

    /// Marks a spring dead, takes it off its ends' share counts and makes its id stale.
    fn kill_spring(&mut self, slot: usize) {
        self.apply_pull(slot, false);
        let s = self.springs[slot];
        for p in [s.a as usize, s.b as usize] {
            self.particles[p].springs = self.particles[p].springs.saturating_sub(1);
        }
        let s = &mut self.springs[slot];
        s.kind = Kind::Dead;
        s.generation = s.generation.wrapping_add(1);
    }
}

/// `1/mass`, or why not: the mass must be finite and positive and its inverse finite and
/// non-zero (a mass whose inverse underflows would silently become pinned).
/// `value` as a component of a scene's position: finite and within
/// [`Scalar::NETWORK_MAX`], the bound the step keeps positions in (a float particle placed
/// beyond it would be moved there by its first step).
pub(crate) fn check_network<S: Scalar>(value: S, parameter: Parameter) -> Result<S, Error> {
    // Fixed point always passes: its range is within the bound.
    crate::input::check_magnitude(value, S::NETWORK_MAX, parameter)
}

fn inverse_mass<S: Scalar>(mass: S) -> Result<f64, Error> {
    let m = crate::error::positive(mass.to_f64(), Parameter::Mass)?;
    let inverse = 1.0 / m;
    if inverse > 0.0 && inverse.is_finite() {
        Ok(inverse)
    } else {
        Err(Error::OutOfRange {
            parameter: Parameter::Mass,
            value: m,
            bound: Bound::Within {
                min: f64::MIN_POSITIVE,
                max: f64::MAX,
            },
        })
    }
}
