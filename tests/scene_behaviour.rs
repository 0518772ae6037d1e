//! How a [`Scene`] behaves beyond its arithmetic: islands that sleep and wake, and pinned
//! particles that cost nothing. (The network-limit policy is `tests/scene_limit_policy.rs`,
//! coincident ends `tests/coincident_ends.rs`.)
//!
//! - **Sleeping.** Ten ropes hang from their anchors under gravity; nine settle, one keeps
//!   swinging. The work a step does is read from [`Scene::active`] (awake free particles,
//!   stepped springs), a deterministic proxy for its cost (no wall clock): each stepped
//!   spring is one kernel call, each awake particle one integration. Touching a sleeping
//!   rope in any way wakes exactly that rope, all of it.
//! - **Pinned.** Springs between two pinned particles are never stepped; a spring with a
//!   pinned end moves only its free end; a pinned particle moves only by `set_position`.
//!
//! `cargo test --release --test scene_behaviour -- --nocapture` prints the savings.

use stiffspring::scene::{ParticleId, Scene, SceneConfig, SpringId, Stepper};
use stiffspring::{Error, I16F16, I32F32, Scalar, Tuning};

fn v2<S: Scalar>(x: f64, y: f64) -> [S; 2] {
    [S::from_f64(x), S::from_f64(y)]
}

fn f2<S: Scalar>(p: [S; 2]) -> [f64; 2] {
    [p[0].to_f64(), p[1].to_f64()]
}

fn sc<S: Scalar>(x: f64) -> S {
    S::from_f64(x)
}

/// Raw coefficients at the time step `dt`.
fn coefficients(ck: f64, cd: f64, dt: f64) -> Tuning {
    Tuning::from_coefficients(ck, cd, dt).unwrap()
}

/// The time step of every scene here but the ropes'.
const DT: f64 = 0.01;

fn rigid(dt: f64) -> Tuning {
    Tuning::rigid(dt).unwrap()
}

// ---------------------------------------------------------------------------
// Sleeping
// ---------------------------------------------------------------------------

const ROPES: usize = 10;
const LINKS: usize = 5;

/// Ten ropes of five free particles, each from its own anchor, one metre apart, under
/// gravity at 120 Hz with the default sleep threshold (1 mm/s for 0.5 s). Rope 0 starts
/// horizontal and swings; the others hang straight down and only settle.
struct Ropes<S: Scalar> {
    scene: Scene<S, 2, 64, 64>,
    anchors: Vec<ParticleId>,
    links: Vec<Vec<ParticleId>>,
    springs: Vec<Vec<SpringId>>,
}

/// The ropes' time step.
const ROPE_DT: f64 = 1.0 / 120.0;

impl<S: Scalar> Ropes<S> {
    fn new(sleep: bool) -> Self {
        let mut config = SceneConfig::new(ROPE_DT)
            .unwrap()
            .gravity(v2(0.0, -9.81))
            .unwrap();
        if !sleep {
            config = config.no_sleep();
        }
        let mut scene = Scene::new(config);
        let (mut anchors, mut links, mut springs) = (Vec::new(), Vec::new(), Vec::new());
        for r in 0..ROPES {
            let x0 = r as f64;
            let anchor = scene.add_pinned(v2(x0, 0.0)).unwrap();
            let (mut last, mut ids, mut sids) = (anchor, Vec::new(), Vec::new());
            for i in 1..=LINKS {
                let d = 0.1 * i as f64;
                let p = if r == 0 { v2(x0 + d, 0.0) } else { v2(x0, -d) };
                let id = scene.add_particle(p, sc(0.05)).unwrap();
                let added = scene
                    .add_spring(last, id, sc(0.1), &coefficients(0.3, 0.3, ROPE_DT))
                    .unwrap();
                assert_eq!(added.clamped, 0);
                ids.push(id);
                sids.push(added.spring);
                last = id;
            }
            anchors.push(anchor);
            links.push(ids);
            springs.push(sids);
        }
        Ropes {
            scene,
            anchors,
            links,
            springs,
        }
    }

    /// Which ropes have an awake particle; panics if a rope is partly awake (an island
    /// sleeps and wakes as a whole).
    fn awake(&self) -> Vec<usize> {
        let mut awake = Vec::new();
        for (r, links) in self.links.iter().enumerate() {
            let states: Vec<bool> = links
                .iter()
                .filter(|&&p| self.scene.position(p).is_ok())
                .map(|&p| !self.scene.is_asleep(p).unwrap())
                .collect();
            assert!(
                states.iter().all(|&s| s == states[0]),
                "rope {r} partly awake: {states:?}"
            );
            if states[0] {
                awake.push(r);
            }
        }
        awake
    }

    fn steps(&mut self, n: usize) {
        for _ in 0..n {
            let _ = self.scene.step();
        }
    }
}

/// Work of one step, in the proxy's units: one per awake particle, one per spring.
fn work((particles, springs): (usize, usize)) -> usize {
    particles + springs
}

fn settled<S: Scalar>() -> Ropes<S> {
    let mut ropes = Ropes::<S>::new(true);
    assert_eq!(ropes.scene.active(), (ROPES * LINKS, ROPES * LINKS));
    assert_eq!(ropes.awake(), (0..ROPES).collect::<Vec<_>>());
    ropes.steps(1200); // 10 s
    assert_eq!(
        ropes.awake(),
        vec![0],
        "{}: only the swinging rope awake",
        S::NAME
    );
    assert_eq!(ropes.scene.active(), (LINKS, LINKS), "{}", S::NAME);
    ropes
}

/// The steps of [`sleeping_saves_work`]'s run: 30 s at 120 Hz.
const SAVING_STEPS: usize = 3600;

/// What sleeping saved in one backend: the work of a step with all ropes awake and with
/// the nine at rest asleep, the seconds until all nine slept, and the work over the
/// whole run without and with sleeping.
struct Saving {
    backend: &'static str,
    before: usize,
    after: usize,
    all_asleep_after: f64,
    without: usize,
    with: usize,
}

impl Saving {
    /// The docs' cells: work per step, all asleep after, work over the run.
    fn cells(&self) -> Vec<String> {
        let saved = |a: usize, b: usize| 100.0 * (1.0 - b as f64 / a as f64);
        vec![
            format!(
                "{} → {} ({:.0} % saved)",
                self.before,
                self.after,
                saved(self.before, self.after)
            ),
            format!("{:.1} s", self.all_asleep_after),
            format!(
                "{} → {} ({:.0} % saved)",
                lab::table::grouped(self.without),
                lab::table::grouped(self.with),
                saved(self.without, self.with)
            ),
        ]
    }
}

/// Sleeping saves the work of the ropes at rest; the figure for the docs.
fn sleeping_saves_work<S: Scalar>() -> Saving {
    let (mut sleeping, mut always) = (Ropes::<S>::new(true), Ropes::<S>::new(false));
    let (mut with, mut without) = (0, 0);
    let mut fell_asleep_at = None;
    let mut reported = Vec::new();
    for step in 0..SAVING_STEPS {
        with += work(sleeping.scene.active());
        without += work(always.scene.active());
        // The step reports what it moved and what fell asleep, and names them.
        let motion = sleeping.scene.step();
        assert_eq!(motion.moving, sleeping.scene.active().0, "{}", S::NAME);
        assert_eq!(
            motion.fell_asleep,
            sleeping.scene.just_fell_asleep().count()
        );
        reported.extend(sleeping.scene.just_fell_asleep());
        let _ = always.scene.step();
        if fell_asleep_at.is_none() && sleeping.awake() == vec![0] {
            fell_asleep_at = Some(step + 1);
        }
    }
    // Each resting rope fell asleep once, every particle of it, and never woke.
    reported.sort();
    let mut resting: Vec<ParticleId> = sleeping.links[1..].iter().flatten().copied().collect();
    resting.sort();
    assert_eq!(reported, resting, "{}", S::NAME);
    let before = work(always.scene.active());
    let after = work(sleeping.scene.active());
    // The swinging rope is stepped exactly as without sleeping (it never slept).
    for (a, b) in sleeping.links[0].iter().zip(&always.links[0]) {
        assert_eq!(
            f2(sleeping.scene.position(*a).unwrap()),
            f2(always.scene.position(*b).unwrap())
        );
    }
    assert_eq!(after * ROPES, before, "{}", S::NAME);
    Saving {
        backend: S::NAME,
        before,
        after,
        all_asleep_after: fell_asleep_at.unwrap() as f64 * ROPE_DT,
        without,
        with,
    }
}

#[test]
fn ropes_at_rest_fall_asleep_and_cost_nothing() {
    let rows = [
        sleeping_saves_work::<f64>(),
        sleeping_saves_work::<f32>(),
        sleeping_saves_work::<I32F32>(),
        sleeping_saves_work::<I16F16>(),
    ];
    let printed: Vec<String> = rows
        .iter()
        .map(|r| {
            format!(
                "| {} | {} | {} |",
                r.backend,
                ROPES - 1,
                r.cells().join(" | ")
            )
        })
        .collect();
    println!(
        "\nTen ropes of 5 particles + 5 springs under gravity, 9 hanging at rest, 1 swinging, \
         120 Hz, default sleep threshold (1 mm/s for 0.5 s). Work = awake particles + stepped springs.\n\
         | backend | ropes asleep | work per step, all awake → 9 asleep | all 9 asleep after | work over 30 s, no sleep → sleep |\n\
         |---|---|---|---|---|\n{}",
        printed.join("\n")
    );
    // docs/networks.md's table: backends with the same figures share a row.
    let mut table: Vec<Vec<String>> = Vec::new();
    for r in &rows {
        let cells = r.cells();
        match table.last_mut() {
            Some(last) if last[1..] == cells[..] => last[0] = format!("{}, {}", last[0], r.backend),
            _ => table.push([vec![r.backend.to_string()], cells].concat()),
        }
    }
    let header = [
        "backend",
        &format!("work per step, all awake → {} asleep", ROPES - 1),
        &format!("all {} asleep after", ROPES - 1),
        &format!(
            "work over {} s, without → with sleeping",
            SAVING_STEPS as f64 * ROPE_DT
        ),
    ];
    let path = lab::table::write_figures(
        "networks/sleeping.md",
        &lab::table::markdown(&header, &table),
    );
    println!("wrote {}", path.display());
}

/// Sleeping particles are not stepped: bit-identical positions, with gravity on.
fn asleep_means_frozen<S: Scalar>() {
    let mut ropes = settled::<S>();
    let before: Vec<[f64; 2]> = ropes.links[1..]
        .iter()
        .flatten()
        .map(|&p| f2(ropes.scene.position(p).unwrap()))
        .collect();
    ropes.steps(600);
    let after: Vec<[f64; 2]> = ropes.links[1..]
        .iter()
        .flatten()
        .map(|&p| f2(ropes.scene.position(p).unwrap()))
        .collect();
    assert_eq!(before, after);
    for &p in ropes.links[1..].iter().flatten() {
        assert_eq!(f2(ropes.scene.velocity(p).unwrap()), [0.0, 0.0]);
    }
    // And they slept near their discrete equilibrium: hanging down, stretched.
    for links in &ropes.links[1..] {
        let last = f2(ropes.scene.position(links[LINKS - 1]).unwrap());
        assert!(last[1] < -0.5, "{}: {last:?}", S::NAME);
    }
}

#[test]
fn sleeping_particles_do_not_move() {
    asleep_means_frozen::<f64>();
    asleep_means_frozen::<f32>();
    asleep_means_frozen::<I32F32>();
    asleep_means_frozen::<I16F16>();
}

/// One way of touching rope 3 (or 3 and 4).
type Touch<S> = fn(&mut Ropes<S>);

/// A touch, the ropes awake right after it, the work the scene does then, and whether
/// the touched ropes come to rest again (touches that push a rope sideways start a
/// pendulum swing, which the springs' damping along their axes hardly damps).
type Case<S> = (&'static str, Touch<S>, Vec<usize>, (usize, usize), bool);

fn touches<S: Scalar>() -> Vec<Case<S>> {
    let five = (2 * LINKS, 2 * LINKS);
    vec![
        (
            "impulse",
            |r| {
                r.scene
                    .apply_impulse(r.links[3][2], v2(0.0, 0.001))
                    .unwrap()
            },
            vec![0, 3],
            five,
            true,
        ),
        (
            "set_velocity",
            |r| r.scene.set_velocity(r.links[3][4], v2(0.0, 0.1)).unwrap(),
            vec![0, 3],
            five,
            true,
        ),
        (
            "set_position (free particle)",
            |r| {
                let p = f2(r.scene.position(r.links[3][1]).unwrap());
                r.scene
                    .set_position(r.links[3][1], v2(p[0], p[1] - 0.01))
                    .unwrap();
            },
            vec![0, 3],
            five,
            true,
        ),
        (
            "set_position (moved anchor)",
            |r| r.scene.set_position(r.anchors[3], v2(3.0, 0.02)).unwrap(),
            vec![0, 3],
            five,
            true,
        ),
        (
            "add_anchor (new one-sided spring)",
            |r| {
                let (_, added) = r
                    .scene
                    .add_anchor(
                        v2(3.2, -0.5),
                        r.links[3][4],
                        sc(0.2),
                        &coefficients(0.3, 0.3, ROPE_DT),
                    )
                    .unwrap();
                assert_eq!(added.clamped, 0);
            },
            vec![0, 3],
            (2 * LINKS, 2 * LINKS + 1),
            false,
        ),
        (
            "add_spring between two sleeping ropes",
            |r| {
                let added = r
                    .scene
                    .add_spring(
                        r.links[3][4],
                        r.links[4][4],
                        S::ONE,
                        &coefficients(0.3, 0.3, ROPE_DT),
                    )
                    .unwrap();
                assert_eq!(added.clamped, 0);
            },
            vec![0, 3, 4],
            (3 * LINKS, 3 * LINKS + 1),
            false,
        ),
        (
            "set_tuning",
            |r| {
                r.scene
                    .set_tuning(r.springs[3][2], &coefficients(0.2, 0.2, ROPE_DT))
                    .unwrap();
            },
            vec![0, 3],
            five,
            true,
        ),
        (
            "set_mass",
            |r| r.scene.set_mass(r.links[3][2], Some(sc(0.1))).unwrap(),
            vec![0, 3],
            five,
            true,
        ),
        (
            "set_mass (anchor freed)",
            |r| r.scene.set_mass(r.anchors[3], Some(sc(0.05))).unwrap(),
            vec![0, 3],
            (2 * LINKS + 1, 2 * LINKS),
            false,
        ),
        (
            "remove_spring (rope cut in two)",
            |r| r.scene.remove_spring(r.springs[3][2]).unwrap(),
            vec![0, 3],
            (2 * LINKS, 2 * LINKS - 1),
            false,
        ),
        (
            "remove_particle",
            |r| r.scene.remove_particle(r.links[3][4]).unwrap(),
            vec![0, 3],
            (2 * LINKS - 1, 2 * LINKS - 1),
            true,
        ),
        (
            "impulse on the awake rope",
            |r| {
                r.scene
                    .apply_impulse(r.links[0][2], v2(0.001, 0.0))
                    .unwrap()
            },
            vec![0],
            (LINKS, LINKS),
            true,
        ),
    ]
}

fn touching_wakes_exactly_its_island<S: Scalar>() {
    let settled = settled::<S>();
    for (name, touch, expected, active, settles) in touches::<S>() {
        let mut ropes = Ropes {
            scene: settled.scene.clone(),
            anchors: settled.anchors.clone(),
            links: settled.links.clone(),
            springs: settled.springs.clone(),
        };
        touch(&mut ropes);
        assert_eq!(ropes.awake(), expected, "{} {name}", S::NAME);
        assert_eq!(ropes.scene.active(), active, "{} {name}", S::NAME);
        // A few steps later nothing else woke up.
        ropes.steps(10);
        assert_eq!(
            ropes.awake(),
            expected,
            "{} {name}, 10 steps later",
            S::NAME
        );
        // And a touched rope that comes to rest sleeps again (within 20 s).
        if settles {
            ropes.steps(2400);
            assert_eq!(ropes.awake(), vec![0], "{} {name}: asleep again", S::NAME);
        }
    }
}

#[test]
fn touching_a_sleeping_rope_wakes_exactly_that_rope() {
    touching_wakes_exactly_its_island::<f64>();
    touching_wakes_exactly_its_island::<f32>();
    touching_wakes_exactly_its_island::<I32F32>();
    touching_wakes_exactly_its_island::<I16F16>();
}

/// Two ropes from one shared anchor (left and right, at rest, no gravity) are two
/// islands (a pinned particle connects nothing): touching one leaves the other asleep,
/// moving the anchor wakes both.
#[test]
fn ropes_sharing_an_anchor_are_separate_islands() {
    let config = SceneConfig::new(ROPE_DT).unwrap();
    let mut scene = Scene::<f32, 2, 8, 8>::new(config);
    let anchor = scene.add_pinned([0.0, 0.0]).unwrap();
    let mut sides = Vec::new();
    for dir in [-1.0f32, 1.0] {
        let mut last = anchor;
        let mut ids = Vec::new();
        for i in 1..=3 {
            let p = scene
                .add_particle([0.1 * dir * i as f32, 0.0], 0.05)
                .unwrap();
            scene
                .add_spring(last, p, 0.1, &coefficients(0.3, 0.3, ROPE_DT))
                .unwrap();
            ids.push(p);
            last = p;
        }
        sides.push(ids);
    }
    let asleep = |s: &Scene<f32, 2, 8, 8>, side: &[ParticleId]| {
        side.iter()
            .map(|&p| s.is_asleep(p).unwrap())
            .collect::<Vec<_>>()
    };
    for _ in 0..120 {
        let _ = scene.step();
    }
    assert_eq!(scene.active(), (0, 0));
    let mut one = scene.clone();
    one.apply_impulse(sides[0][1], [0.001, 0.0]).unwrap();
    assert_eq!(asleep(&one, &sides[0]), [false; 3]);
    assert_eq!(asleep(&one, &sides[1]), [true; 3]);
    assert_eq!(one.active(), (3, 3));
    let mut both = scene.clone();
    both.set_position(anchor, [0.01, 0.0]).unwrap();
    assert_eq!(asleep(&both, &sides[0]), [false; 3]);
    assert_eq!(asleep(&both, &sides[1]), [false; 3]);
    assert_eq!(both.active(), (6, 6));
    // The anchor's move reaches the ropes through their springs at once: their pull
    // from the new position and their damping of its 0.01 (1.2 units per second) are in
    // the step velocity of the particle it holds. The anchor itself never moves on its
    // own.
    assert_eq!(both.velocity(anchor).unwrap(), [0.0, 0.0]);
    assert!(both.velocity(sides[0][0]).unwrap()[0] > 0.0);
    let _ = both.step();
    assert_eq!(both.velocity(anchor).unwrap(), [0.0, 0.0]);
    assert_eq!(both.position(anchor).unwrap(), [0.01, 0.0]);
    assert!(both.velocity(sides[0][0]).unwrap()[0] > 0.0);
}

// ---------------------------------------------------------------------------
// Pinned particles
// ---------------------------------------------------------------------------

#[test]
fn springs_between_two_pinned_particles_are_never_stepped() {
    let config = SceneConfig::new(0.01)
        .unwrap()
        .gravity([0.0, -9.81])
        .unwrap()
        .no_sleep();
    let mut s = Scene::<f64, 2, 4, 4>::new(config);
    let a = s.add_pinned([0.0, 0.0]).unwrap();
    let b = s.add_pinned([1.0, 0.0]).unwrap();
    let c = s.add_particle([1.0, -0.5], 1.0).unwrap();
    // Within ¾: freeing b later makes the two springs on it compete.
    let inert = s
        .add_spring(a, b, 0.5, &coefficients(0.3, 0.3, DT))
        .unwrap();
    s.add_spring(b, c, 0.5, &coefficients(0.3, 0.3, DT))
        .unwrap();
    assert_eq!(inert.clamped, 0);
    assert_eq!(s.spring_count(), 2);
    // One free particle, one stepped spring: the pinned pair's spring is dropped.
    assert_eq!(s.active(), (1, 1));
    for _ in 0..500 {
        let _ = s.step();
        assert_eq!(s.active(), (1, 1));
        assert_eq!(s.position(a).unwrap(), [0.0, 0.0]);
        assert_eq!(s.position(b).unwrap(), [1.0, 0.0]);
        assert_eq!(s.velocity(a).unwrap(), [0.0, 0.0]);
        assert_eq!(s.velocity(b).unwrap(), [0.0, 0.0]);
    }
    assert!(s.position(c).unwrap()[1] < -0.5); // it hangs, stretched
    // Freeing one end brings the spring back; pinning it again drops it again.
    s.set_mass(b, Some(1.0)).unwrap();
    assert_eq!(s.active(), (2, 2));
    s.set_mass(b, None).unwrap();
    assert_eq!(s.active(), (1, 1));
    // A scene of pinned particles only costs nothing at all.
    let mut only = Scene::<f32, 2, 3, 3>::new(SceneConfig::new(0.01).unwrap());
    let p: Vec<_> = (0..3)
        .map(|i| only.add_pinned([i as f32, 0.0]).unwrap())
        .collect();
    only.add_spring(p[0], p[1], 1.0, &rigid(DT)).unwrap();
    only.add_spring(p[1], p[2], 1.0, &rigid(DT)).unwrap();
    assert_eq!(only.active(), (0, 0));
}

/// A spring from a pinned hub to each of eight particles: the hub is not a particle
/// the step visits, and each spring moves only its free end, exactly as the single-body
/// map `u ← (1 − C_d)·u − C_k·x` along the axis.
#[test]
fn one_sided_springs_move_only_their_free_end() {
    let mut s = Scene::<f64, 2, 9, 8>::new(SceneConfig::new(0.01).unwrap().no_sleep());
    let hub = s.add_pinned([0.0, 0.0]).unwrap();
    let mut spokes = Vec::new();
    for i in 0..8 {
        let angle = i as f64 * std::f64::consts::TAU / 8.0;
        let p = s
            .add_particle([1.5 * angle.cos(), 1.5 * angle.sin()], 0.1 + i as f64)
            .unwrap();
        // Each free end carries one spring: the rigid spring is within the limit.
        let added = s.add_spring(hub, p, 1.0, &rigid(DT)).unwrap();
        assert_eq!(added.clamped, 0);
        spokes.push(p);
    }
    assert_eq!(s.active(), (8, 8));
    // Rigid: each end at the rest length in one step, at rest in two (the seed's
    // erratum), whatever its mass.
    let _ = s.step();
    for &p in &spokes {
        let x = s.position(p).unwrap();
        assert!((x[0].hypot(x[1]) - 1.0).abs() < 1e-15);
    }
    let _ = s.step();
    for &p in &spokes {
        let v = s.velocity(p).unwrap();
        assert!(v[0].hypot(v[1]) * DT < 1e-15);
    }
    assert_eq!(s.position(hub).unwrap(), [0.0, 0.0]);
    assert_eq!(s.velocity(hub).unwrap(), [0.0, 0.0]);
}

#[test]
fn a_pinned_particle_moves_only_by_set_position() {
    for stepper in [Stepper::GaussSeidel, Stepper::Jacobi] {
        let config = SceneConfig::new(0.01)
            .unwrap()
            .gravity([1.0, -9.81])
            .unwrap()
            .stepper(stepper)
            .no_sleep();
        let mut s = Scene::<f32, 2, 3, 2>::new(config);
        let anchor = s.add_pinned([0.0, 0.0]).unwrap();
        let p = s.add_particle([0.0, -1.0], 1.0).unwrap();
        let q = s.add_particle([0.0, -2.0], 3.0).unwrap();
        s.add_spring(anchor, p, 1.0, &coefficients(0.3, 0.3, DT))
            .unwrap();
        s.add_spring(p, q, 1.0, &coefficients(0.3, 0.3, DT))
            .unwrap();
        for _ in 0..300 {
            let _ = s.step();
            assert_eq!(s.position(anchor).unwrap(), [0.0, 0.0]);
            assert_eq!(s.velocity(anchor).unwrap(), [0.0, 0.0]);
            assert_eq!(s.velocity(anchor).unwrap(), [0.0, 0.0]);
        }
        s.set_position(anchor, [0.5, 0.25]).unwrap();
        assert_eq!(s.position(anchor).unwrap(), [0.5, 0.25]);
        for _ in 0..300 {
            let _ = s.step();
            assert_eq!(s.position(anchor).unwrap(), [0.5, 0.25]);
            assert_eq!(s.velocity(anchor).unwrap(), [0.0, 0.0]);
        }
        // The pinned particle takes no impulse and no velocity.
        assert_eq!(s.apply_impulse(anchor, [1.0, 0.0]), Err(Error::Pinned));
        assert_eq!(s.set_velocity(anchor, [1.0, 0.0]), Err(Error::Pinned));
        assert!(s.is_pinned(anchor).unwrap());
        assert!(!s.is_asleep(anchor).unwrap());
    }
}
