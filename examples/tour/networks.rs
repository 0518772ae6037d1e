//! Networks: a rope swinging from a pinned end, and a jelly wobbling on a plate.

use firmware::scenes::rope as rope_scene;
use lab::plot::render_frames;
use lab::reference::network::Network;
use lab::table::{print, sci};
use std::path::Path;
use stiffspring::length::{Exact, LengthKernel, Linearised};
use stiffspring::scene::{ParticleId, Scene, SceneConfig, Stepper};
use stiffspring::{I16F16, I32F32, Scalar, Tuning};

/// The reference rope with the scene's geometry (the reference's masses are 1: the motion
/// does not depend on them).
fn reference_rope() -> Network<2> {
    let c = rope_scene::COEFFICIENT;
    let mut net =
        lab::reference::network::rope_2d(rope_scene::PARTICLES, rope_scene::SEGMENT, true, c, c);
    net.gravity = rope_scene::GRAVITY;
    net
}

/// Worst distance from the reference over the run, relative to the rope's length.
fn rope_error<S: Scalar, L: LengthKernel<S>>(stepper: Stepper) -> f64 {
    let (mut rope, ids) = rope_scene::build::<S, L>().expect("valid scene");
    let mut net = reference_rope();
    if stepper == Stepper::Jacobi {
        // Same scene, the other stepper: rebuild with it.
        let config = SceneConfig::new(rope_scene::DT)
            .and_then(|c| c.gravity(rope_scene::GRAVITY.map(S::from_f64)))
            .expect("valid")
            .stepper(Stepper::Jacobi);
        let mut jacobi = Scene::new(config);
        let c = rope_scene::COEFFICIENT;
        let tuning = Tuning::from_coefficients(c, c, rope_scene::DT).expect("valid");
        let mut prev = jacobi.add_pinned([S::ZERO, S::ZERO]).expect("room");
        for i in 1..rope_scene::PARTICLES {
            let x = S::from_f64(i as f64 * rope_scene::SEGMENT);
            let next = jacobi
                .add_particle([x, S::ZERO], S::from_f64(rope_scene::MASS))
                .expect("room");
            jacobi
                .add_spring(prev, next, S::from_f64(rope_scene::SEGMENT), &tuning)
                .expect("valid");
            prev = next;
        }
        rope = jacobi;
    }
    let length = rope_scene::SEGMENT * (rope_scene::PARTICLES - 1) as f64;
    let mut worst = 0.0f64;
    for _ in 0..rope_scene::STEPS {
        let _ = rope.step();
        match stepper {
            Stepper::GaussSeidel => net.step_gauss_seidel_kept(rope_scene::DT),
            Stepper::Jacobi => net.step_jacobi_kept(rope_scene::DT),
        }
        for (i, id) in ids.iter().enumerate() {
            let p = rope.position(*id).expect("live");
            let q = net.particles[i].pos;
            let d = ((p[0].to_f64() - q[0]).powi(2) + (p[1].to_f64() - q[1]).powi(2)).sqrt();
            worst = worst.max(d / length);
        }
    }
    worst
}

pub fn rope(dir: &Path) {
    println!(
        "A 2D rope: {} particles pinned at one end, released level under gravity, {} s at {} Hz, C = {}",
        rope_scene::PARTICLES,
        rope_scene::STEPS as f64 * rope_scene::DT,
        1.0 / rope_scene::DT,
        rope_scene::COEFFICIENT
    );
    let mut rows = Vec::new();
    for stepper in [Stepper::GaussSeidel, Stepper::Jacobi] {
        rows.push(vec![
            format!("{stepper:?}"),
            sci(rope_error::<f64, Exact>(stepper)),
            sci(rope_error::<f32, Exact>(stepper)),
            sci(rope_error::<I32F32, Exact>(stepper)),
            sci(rope_error::<I16F16, Exact>(stepper)),
            {
                let e = rope_error::<f32, Linearised>(stepper);
                if e > 1.0 { "unstable".into() } else { sci(e) }
            },
        ]);
    }
    print(
        &[
            "stepper",
            "f64",
            "f32",
            "I32F32",
            "I16F16",
            "f32 linearised",
        ],
        &rows,
    );
    println!(
        "(worst distance from the reference model over the run, relative to the rope's 1.1 m; \
         the whip stretches segments far beyond the linearised kernel's range)\n"
    );

    let (mut rope, ids) = rope_scene::build::<f32, Exact>().expect("valid scene");
    let edges: Vec<(usize, usize)> = (0..rope_scene::SPRINGS).map(|i| (i, i + 1)).collect();
    let snapshot = |r: &rope_scene::Rope<f32, Exact>| -> Vec<(f64, f64)> {
        ids.iter()
            .map(|id| {
                let p = r.position(*id).expect("live");
                (p[0] as f64, p[1] as f64)
            })
            .collect()
    };
    let marks = [0, 60, 120, 180, 240, 360, 480];
    let mut frames = Vec::new();
    let mut times = Vec::new();
    for n in 0..=rope_scene::STEPS {
        if marks.contains(&n) {
            frames.push(snapshot(&rope));
            times.push(n as f64 * rope_scene::DT);
        }
        let _ = rope.step();
    }
    let path = dir.join("rope.svg");
    std::fs::write(
        &path,
        render_frames(
            "A rope swinging down (f32, Gauss-Seidel)",
            &frames,
            &edges,
            &times,
        ),
    )
    .expect("write rope.svg");
    println!("  wrote {}\n", path.display());
}

/// The jelly: a W×H mesh with diagonals, bottom row pinned to a plate.
const W: usize = 8;
const H: usize = 8;
const CELL: f64 = 0.05;
const DT: f64 = 1.0 / 120.0;
/// Up to eight springs per particle with diagonals: the article's limit is 1/9.
const JELLY_C: f64 = 0.1;
/// The top row is pushed sideways at this speed (m/s).
const PUSH: f64 = 0.8;
const JELLY_STEPS: usize = 360;

/// The springs in the scene's execution order: those with a pinned end first, then the
/// rest, each in the order added (what `Scene` does), as (a, b, rest).
fn jelly_springs() -> Vec<(usize, usize, f64)> {
    let mut all = Vec::new();
    for r in 0..H {
        for c in 0..W {
            let i = r * W + c;
            if c + 1 < W {
                all.push((i, i + 1, CELL));
            }
            if r + 1 < H {
                all.push((i, i + W, CELL));
            }
        }
    }
    for r in 0..H - 1 {
        for c in 0..W - 1 {
            let i = r * W + c;
            all.push((i, i + W + 1, CELL * std::f64::consts::SQRT_2));
            all.push((i + 1, i + W, CELL * std::f64::consts::SQRT_2));
        }
    }
    let pinned = |i: usize| i < W;
    let mut order: Vec<_> = all
        .iter()
        .copied()
        .filter(|&(a, b, _)| pinned(a) != pinned(b))
        .collect();
    order.extend(
        all.iter()
            .copied()
            .filter(|&(a, b, _)| !pinned(a) && !pinned(b)),
    );
    order
}

type Jelly<S> = Scene<S, 2, { W * H }, { 2 * W * H + 2 * (W - 1) * (H - 1) }>;

fn build_jelly<S: Scalar>(stepper: Stepper) -> (Jelly<S>, Vec<ParticleId>) {
    let config = SceneConfig::new(DT).expect("valid").stepper(stepper);
    let mut jelly = Scene::new(config);
    let mut ids = Vec::new();
    for r in 0..H {
        for c in 0..W {
            let p = [S::from_f64(c as f64 * CELL), S::from_f64(r as f64 * CELL)];
            ids.push(if r == 0 {
                jelly.add_pinned(p).expect("room")
            } else {
                jelly.add_particle(p, S::from_f64(0.01)).expect("room")
            });
        }
    }
    let tuning = Tuning::from_coefficients(JELLY_C, JELLY_C, DT).expect("valid");
    for (a, b, rest) in jelly_springs() {
        jelly
            .add_spring(ids[a], ids[b], S::from_f64(rest), &tuning)
            .expect("within the limit");
    }
    for id in &ids[(H - 1) * W..] {
        jelly
            .set_velocity(*id, [S::from_f64(PUSH), S::ZERO])
            .expect("free");
    }
    (jelly, ids)
}

fn reference_jelly(stepper: Stepper) -> Network<2> {
    let mut net = Network::new();
    for r in 0..H {
        for c in 0..W {
            let p = [c as f64 * CELL, r as f64 * CELL];
            if r == 0 {
                net.add_pinned(p);
            } else {
                let v = if r == H - 1 { [PUSH, 0.0] } else { [0.0; 2] };
                net.add_particle(p, v, 1.0);
            }
        }
    }
    for (a, b, rest) in jelly_springs() {
        net.add_spring(a, b, rest, JELLY_C, JELLY_C);
    }
    let _ = stepper;
    net
}

fn jelly_error<S: Scalar>(stepper: Stepper) -> f64 {
    let (mut jelly, ids) = build_jelly::<S>(stepper);
    let mut net = reference_jelly(stepper);
    let size = CELL * (W - 1) as f64;
    let mut worst = 0.0f64;
    for _ in 0..JELLY_STEPS {
        let _ = jelly.step();
        match stepper {
            Stepper::GaussSeidel => net.step_gauss_seidel_kept(DT),
            Stepper::Jacobi => net.step_jacobi_kept(DT),
        }
        for (i, id) in ids.iter().enumerate() {
            let p = jelly.position(*id).expect("live");
            let q = net.particles[i].pos;
            let d = ((p[0].to_f64() - q[0]).powi(2) + (p[1].to_f64() - q[1]).powi(2)).sqrt();
            worst = worst.max(d / size);
        }
    }
    worst
}

pub fn jelly(dir: &Path) {
    println!(
        "A jelly: {W}×{H} mesh with diagonals on a pinned plate, top row pushed at {PUSH} m/s, \
         {} s at {} Hz, C = {JELLY_C}",
        JELLY_STEPS as f64 * DT,
        1.0 / DT
    );
    let mut rows = Vec::new();
    for stepper in [Stepper::GaussSeidel, Stepper::Jacobi] {
        rows.push(vec![
            format!("{stepper:?}"),
            sci(jelly_error::<f64>(stepper)),
            sci(jelly_error::<f32>(stepper)),
            sci(jelly_error::<I32F32>(stepper)),
            sci(jelly_error::<I16F16>(stepper)),
        ]);
    }
    print(&["stepper", "f64", "f32", "I32F32", "I16F16"], &rows);
    println!("(worst distance from the reference model, relative to the jelly's 0.35 m width)");

    // Wobble, then sleep: how much work the step does before and after.
    let (mut jelly, ids) = build_jelly::<f32>(Stepper::GaussSeidel);
    let edges: Vec<(usize, usize)> = jelly
        .springs()
        .map(|(_, a, b)| (a.slot(), b.slot()))
        .collect();
    let (particles, springs) = jelly.active();
    let mut frames = Vec::new();
    let mut times = Vec::new();
    let mut asleep_at = None;
    for n in 0..=24_000 {
        if [0, 10, 20, 40, 80].contains(&n) {
            frames.push(
                ids.iter()
                    .map(|id| {
                        let p = jelly.position(*id).expect("live");
                        (p[0] as f64, p[1] as f64)
                    })
                    .collect(),
            );
            times.push(n as f64 * DT);
        }
        if jelly.active().0 == 0 {
            asleep_at = Some(n);
            break;
        }
        let _ = jelly.step();
    }
    match asleep_at {
        Some(n) => println!(
            "  stepping {particles} particles and {springs} springs per step while it wobbles; \
             asleep after {:.2} s, then {:?} (particles, springs) per step",
            n as f64 * DT,
            jelly.active()
        ),
        None => println!("  still awake after 200 s"),
    }
    let path = dir.join("jelly.svg");
    std::fs::write(
        &path,
        render_frames(
            "A jelly wobbling on a plate (f32, Gauss-Seidel)",
            &frames,
            &edges,
            &times,
        ),
    )
    .expect("write jelly.svg");
    println!("  wrote {}\n", path.display());
}
