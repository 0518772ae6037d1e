//! Nonlinear stability runs of spring networks on the independent f64 reference
//! network ([`crate::reference::network`]), for the network-limit measurements.
//!
//! A network of a [`Topology`] is started from rest with every free particle displaced by
//! up to a fraction of the shortest rest length ([`Topology::deformed`], seeded) and run
//! for [`STEPS`] steps with every spring at given coefficients, in the library's spring
//! order. A run is **stable** when nothing blows up (every strain stays below 10, every
//! value finite) and its motion at the step rate dies out (see [`Run`]): a network that
//! stays bounded but jitters for ever above its linear limit counts as unstable, a rope
//! that keeps swinging on its undamped transverse modes does not. [`Tracker`] records a
//! run from its strains, so a test can run the library's own scene the same way.

use crate::linear::{Order, Topology};
use crate::reference::network::Network;

/// Steps of every run.
pub const STEPS: usize = 10_000;
/// Deformation seeds per probe.
pub const SEEDS: [u64; 3] = [1, 2, 3];

/// What a run did. `strain` is the largest `|x|/L` over the springs; `ripple` the
/// largest fourth difference of a spring's strain over five consecutive steps
/// (`e(t) − 4e(t−1) + 6e(t−2) − 4e(t−3) + e(t−4)`). A motion of frequency `θ` radians per
/// step and amplitude `a` has a ripple of `(2·sin(θ/2))⁴·a`: `16·a` for the period-2
/// oscillation of a network past its limit, more than `a/4` for any period below nine
/// steps, but under `a/100` for smooth physical motion (`θ < 0.3`: a rope still swinging
/// or whipping on its undamped transverse modes, with the steady strain of its
/// centrifugal tension; a soft network still settling). A long rope with a 1:100 mass
/// gradient whipping after a 50 % deformation sits in between (its light end swings at
/// about ten steps per period, a ripple of 0.05 to 0.2 of its strain).
#[derive(Clone, Copy, Debug)]
pub struct Run {
    /// Largest ripple over the 1 000 steps before the middle of the run.
    pub mid: f64,
    /// Largest ripple over the last 1 000 steps.
    pub end: f64,
    /// Largest strain over the last 1 000 steps.
    pub strain: f64,
    /// A strain reached 10, or a value was not finite.
    pub blew_up: bool,
}

impl Run {
    /// Nothing blew up, and at the end there is no sustained motion at the step rate:
    /// the ripple is at rounding level, or small against the strain, or still falling.
    pub fn stable(&self) -> bool {
        let quiet = self.end <= 1e-9 || self.end <= 0.25 * self.strain;
        !self.blew_up && (quiet || self.end <= 0.5 * self.mid)
    }
}

/// Records the strains of each step into a [`Run`].
pub struct Tracker {
    steps: usize,
    /// The strains of the last four steps, newest first.
    history: [Vec<f64>; 4],
    /// What the run did so far.
    pub run: Run,
}

impl Tracker {
    /// A tracker for a run of `steps` steps starting from `strains`.
    pub fn new(steps: usize, strains: Vec<f64>) -> Self {
        Tracker {
            steps,
            history: [strains.clone(), strains.clone(), strains.clone(), strains],
            run: Run {
                mid: 0.0,
                end: 0.0,
                strain: 0.0,
                blew_up: false,
            },
        }
    }

    /// Records step `t`; false once the run blew up.
    pub fn record(&mut self, t: usize, strains: Vec<f64>) -> bool {
        let (mut ripple, mut strain): (f64, f64) = (0.0, 0.0);
        let [h1, h2, h3, h4] = &self.history;
        for (i, e) in strains.iter().enumerate() {
            if e.is_nan() || e.abs() >= 10.0 {
                self.run.blew_up = true;
                return false;
            }
            let d4 = e - 4.0 * h1[i] + 6.0 * h2[i] - 4.0 * h3[i] + h4[i];
            ripple = ripple.max(d4.abs());
            strain = strain.max(e.abs());
        }
        self.history.rotate_right(1);
        self.history[0] = strains;
        let window = self.steps / 10;
        let half = self.steps / 2;
        if t + window >= half && t < half {
            self.run.mid = self.run.mid.max(ripple);
        }
        if t + window >= self.steps {
            self.run.end = self.run.end.max(ripple);
            self.run.strain = self.run.strain.max(strain);
        }
        true
    }
}

/// The strain `x/L` of every spring of `net` (the first one infinite once a velocity is
/// not finite).
pub fn reference_strains(net: &Network<2>) -> Vec<f64> {
    let mut strains: Vec<f64> = (0..net.springs.len())
        .map(|s| net.extension(s) / net.springs[s].rest)
        .collect();
    if net
        .particles
        .iter()
        .any(|p| !(p.vel[0].is_finite() && p.vel[1].is_finite()))
    {
        strains[0] = f64::INFINITY;
    }
    strains
}

/// The reference network of `top`, deformed, with per-spring coefficients, in the
/// library's order.
pub fn reference_network(
    top: &Topology,
    ck: &[f64],
    cd: &[f64],
    fraction: f64,
    seed: u64,
) -> Network<2> {
    let mut net = Network::<2>::new();
    for (i, p) in top.deformed(fraction, seed).into_iter().enumerate() {
        if top.is_free(i) {
            net.add_particle(p, [0.0; 2], 1.0 / top.inverse_masses[i]);
        } else {
            net.add_pinned(p);
        }
    }
    for s in top.library_order() {
        let (a, b) = top.springs[s];
        let d = [
            top.positions[b][0] - top.positions[a][0],
            top.positions[b][1] - top.positions[a][1],
        ];
        net.add_spring(a, b, d[0].hypot(d[1]), ck[s], cd[s]);
    }
    net
}

/// One run of the reference network of `top` from `fraction` deformation (seed `seed`),
/// [`STEPS`] steps.
pub fn reference_run(
    top: &Topology,
    ck: &[f64],
    cd: &[f64],
    order: Order,
    fraction: f64,
    seed: u64,
) -> Run {
    // Any dt: the map depends on the coefficients only.
    let dt = 0.01;
    let mut net = reference_network(top, ck, cd, fraction, seed);
    let mut tracker = Tracker::new(STEPS, reference_strains(&net));
    for t in 0..STEPS {
        match order {
            Order::GaussSeidel => net.step_gauss_seidel(dt),
            Order::Jacobi => net.step_jacobi(dt),
        }
        if !tracker.record(t, reference_strains(&net)) {
            break;
        }
    }
    tracker.run
}

/// Stable from every seed at `(c, c)` on every spring.
pub fn nonlinear_stable(top: &Topology, order: Order, fraction: f64, c: f64) -> bool {
    let m = top.springs.len();
    let (ck, cd) = (vec![c; m], vec![c; m]);
    SEEDS
        .iter()
        .all(|&seed| reference_run(top, &ck, &cd, order, fraction, seed).stable())
}

/// The largest `C ≤ hi` stable from `fraction` deformation, to `tol`: bisection, then
/// a check of `½`, `¾` and `0.9` of the result; if one of those is unstable (stability
/// need not be monotone in `C` far from the rest state), the search repeats below it.
pub fn nonlinear_limit(top: &Topology, order: Order, fraction: f64, tol: f64, hi: f64) -> f64 {
    let mut hi = hi;
    if nonlinear_stable(top, order, fraction, hi) {
        return hi;
    }
    loop {
        let mut lo = 0.0;
        while hi - lo > tol {
            let mid = 0.5 * (lo + hi);
            if nonlinear_stable(top, order, fraction, mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        match [0.9, 0.75, 0.5]
            .iter()
            .map(|f| f * lo)
            .find(|&c| c > tol && !nonlinear_stable(top, order, fraction, c))
        {
            Some(c) => hi = c,
            None => return lo,
        }
    }
}
