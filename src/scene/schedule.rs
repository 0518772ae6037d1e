//! Islands and the schedule: which particles and springs a step touches, and how each
//! spring runs.
//!
//! An island is a group of free particles connected by springs (pinned particles do not
//! connect: they do not move, so nothing passes through them). Islands sleep as a whole,
//! like Box2D's: when every particle of an island stayed slower than the sleep threshold
//! for the sleep time, its velocities are zeroed and it leaves the schedule, so a scene
//! that is mostly at rest costs only its moving parts. Touching a particle (or a pinned
//! particle's springs) wakes its island.

use super::{Chain, Island, Kind, Scene};
use crate::kernel::BodyWeights;
use crate::length::LengthKernel;
use crate::scalar::Scalar;
use heapless::Vec;

impl<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>>
    Scene<S, D, P, K, L>
{
    /// Sets a spring's kind and weights from its ends' inverse masses; a one-sided
    /// spring is oriented with its pinned end as `a`.
    pub(crate) fn classify(&mut self, slot: usize) {
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
                // (An angular spring's is not: its rest angle changes sign with it.)
                core::mem::swap(&mut spring.a, &mut spring.b);
                spring.rest = L::flipped(&spring.rest);
                spring.swapped = !spring.swapped;
                spring.kind = Kind::OneSided;
            }
            (true, true) => {
                spring.kind = Kind::TwoSided;
                // Both inverse masses are finite and positive here: cannot fail.
                spring.weights = BodyWeights::from_inverse_masses(ia, ib).unwrap_or_default();
            }
        }
    }

    /// Recomputes the islands after a change of topology or of who is pinned, then the
    /// schedule. A new island is awake if any of its particles was in an awake island.
    /// Set-up only: O(P + K).
    pub(crate) fn rebuild(&mut self) {
        let n = self.particles.len();
        let mut parent: Vec<u16, P> = Vec::new();
        for i in 0..n {
            // Capacity P ≥ n: always room.
            let _ = parent.push(i as u16);
        }
        fn find(parent: &mut [u16], mut i: usize) -> usize {
            while parent[i] as usize != i {
                // Path halving.
                parent[i] = parent[parent[i] as usize];
                i = parent[i] as usize;
            }
            i
        }
        for s in self.springs.iter() {
            if s.kind == Kind::TwoSided {
                let (ra, rb) = (
                    find(&mut parent, s.a as usize),
                    find(&mut parent, s.b as usize),
                );
                if ra != rb {
                    parent[ra.max(rb)] = ra.min(rb) as u16;
                }
            }
        }
        let mut awake: Vec<bool, P> = Vec::new();
        for _ in 0..n {
            let _ = awake.push(false);
        }
        for p in 0..n {
            let particle = self.particles[p];
            if particle.live && particle.inverse_mass > 0.0 {
                let root = find(&mut parent, p);
                awake[root] |= self.islands[particle.island as usize].awake;
            }
        }
        for p in 0..n {
            let root = find(&mut parent, p);
            self.particles[p].island = root as u16;
        }
        for (root, island) in self.islands.iter_mut().enumerate() {
            let was = island.awake;
            *island = Island {
                awake: awake[root],
                moving: false,
                quiet: if was && awake[root] { island.quiet } else { 0 },
            };
        }
        self.reschedule();
    }

    /// Rebuilds the lists a step iterates from the islands' sleep flags. O(P + K), run
    /// only when something falls asleep, wakes up or changes.
    pub(crate) fn reschedule(&mut self) {
        self.free.clear();
        self.dragged = false;
        self.awake_islands.clear();
        self.one_sided.clear();
        self.two_sided.clear();
        self.one_sided_points.clear();
        self.two_sided_points.clear();
        self.chains.clear();
        for (p, particle) in self.particles.iter().enumerate() {
            if particle.live && particle.inverse_mass > 0.0 {
                let island = particle.island as usize;
                if self.islands[island].awake {
                    // Each list has the capacity of what it lists: always room.
                    let _ = self.free.push(p as u16);
                    self.dragged |= particle.damping > 0.0;
                    if island == p {
                        let _ = self.awake_islands.push(p as u16);
                    }
                }
            }
        }
        for (i, s) in self.springs.iter().enumerate() {
            // The free end decides: `b` for one-sided springs, either for two-sided ones.
            let island = self.particles[s.b as usize].island as usize;
            let awake = self.islands[island].awake;
            let list = match (s.kind, s.point) {
                (Kind::OneSided, false) => &mut self.one_sided,
                (Kind::TwoSided, false) => &mut self.two_sided,
                (Kind::OneSided, true) => &mut self.one_sided_points,
                (Kind::TwoSided, true) => &mut self.two_sided_points,
                _ => continue,
            };
            if awake {
                let _ = list.push(i as u16);
                if s.kind == Kind::TwoSided && !s.point {
                    // Ends at consecutive slots, the second being the next spring's
                    // first, in consecutive spring slots: one more spring of the chain.
                    let consecutive = s.b as usize == s.a as usize + 1;
                    match self.chains.last_mut() {
                        Some(Chain {
                            spring,
                            count,
                            particle: Some(first),
                        }) if consecutive
                            && *spring as usize + *count as usize == i
                            && *first as usize + *count as usize == s.a as usize =>
                        {
                            *count += 1;
                        }
                        _ => {
                            let _ = self.chains.push(Chain {
                                spring: i as u16,
                                count: 1,
                                particle: consecutive.then_some(s.a),
                            });
                        }
                    }
                }
            }
        }
    }

    /// Wakes the island of a free particle, or of every free particle sprung to a pinned
    /// one. Returns whether anything was asleep (then the schedule must be rebuilt).
    pub(crate) fn wake_around(&mut self, slot: usize) -> bool {
        if self.particles[slot].inverse_mass > 0.0 {
            return self.wake_island(self.particles[slot].island as usize);
        }
        let mut woke = false;
        for i in 0..self.springs.len() {
            let s = self.springs[i];
            if s.kind == Kind::Dead || (s.a as usize != slot && s.b as usize != slot) {
                continue;
            }
            for end in [s.a as usize, s.b as usize] {
                if self.particles[end].inverse_mass > 0.0 {
                    woke |= self.wake_island(self.particles[end].island as usize);
                }
            }
        }
        woke
    }

    fn wake_island(&mut self, root: usize) -> bool {
        let island = &mut self.islands[root];
        island.quiet = 0;
        let woke = !core::mem::replace(&mut island.awake, true);
        self.woken += usize::from(woke);
        woke
    }
}
