//! Fixed point beyond the single spring of the unit square: the whole stability region,
//! and networks. Extends `tests/fixed_rounding.rs` (which shows why the step rounds its
//! spring term toward zero and its damping term away from it, and that the library is the
//! study's integer model of that step bit for bit) with:
//!
//! 1. **The whole region.** The study's integer model of one spring (`lab::precision::Kept`:
//!    Q24.40 or Q64.64 state, 31- or 63-bit gains), run from several starts until its state
//!    repeats, on a grid over the square `(0, 1]²` and over the extended region (`C_k > 1`
//!    or `C_d > 1`, which the exact map produces for undersampled oscillators,
//!    `f·dt > 1/6`, or raw coefficients): in the square every start ends on a fixed point;
//!    beyond it a few end in cycles of the state, all far below a position's last bit.
//! 2. **Rest detection.** A value with such a tuning comes to rest even with a tiny
//!    threshold (its band holds motion of about a last bit).
//! 3. **Networks.** Braced meshes in `I16F16` and `I32F32`, both steppers, at the scene's
//!    limits and soft: do they come to a standstill or cycle, and does the scene's island
//!    sleep (every step velocity within `max(threshold·dt, 1 LSB)` for the sleep time)?
//!
//! `cargo test --release --test fixed_point_limits -- --nocapture` prints the tables.

use lab::linear::Topology;
use lab::precision::{Coefs, Fixed, KRound, Kept, kept_settle};
use stiffspring::scene::{LimitPolicy, Scene, SceneConfig, Stepper};
use stiffspring::{I16F16, I32F32, Motion, RestThreshold, Scalar, SpringValue, Tuning};

/// Starts in position LSB: (offset, step velocity).
const STARTS: [(i128, i128); 6] = [
    (1 << 16, 0),
    (-(1 << 20), 0),
    (12_345, -678),
    (0, 4_000),
    (100 << 16, 0),
    (-7, 3),
];

/// Grid points of the stable region with damping (an undamped spring never rests: its
/// integer map is a bijection, `tests/long_runs.rs`).
fn grid(square: bool) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for i in 1..=40 {
        let ck = 0.1 * i as f64;
        for cd in [
            0.001, 0.01, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 1.0, 1.2, 1.5, 1.8, 1.95,
        ] {
            let inside = cd < 2.0 && ck + 2.0 * cd < 4.0;
            let in_square = ck <= 1.0 && cd <= 1.0;
            if (inside || in_square) && in_square == square {
                out.push((ck, cd));
            }
        }
    }
    out
}

#[derive(Default, Debug)]
struct Summary {
    runs: usize,
    rests: usize,
    cycles: usize,
    unresolved: usize,
    /// Largest `|x|·C_k` at rest (below 1: inside the dead band).
    worst_rest_ck_x: f64,
    /// Largest `|x|` and `|ũ|` on a cycle, state LSB.
    worst_cycle: (i128, i128),
    worst_at: (f64, f64),
}

fn summarise(t: Fixed, points: &[(f64, f64)]) -> Summary {
    let mut s = Summary::default();
    let g = Kept::guard(t);
    for &(ck, cd) in points {
        for (x, u) in STARTS {
            // The step velocity u becomes the kept one, (1 − C_d)·u.
            let kept = ((1.0 - cd) * (u << g) as f64).round() as i128;
            let k = Kept::from_state(t, KRound::Lead, Coefs { ck, cd }, x << g, kept);
            let end = kept_settle(k, 4_000_000);
            s.runs += 1;
            match end.period {
                1 => {
                    s.rests += 1;
                    s.worst_rest_ck_x = s.worst_rest_ck_x.max(end.band);
                }
                0 => s.unresolved += 1,
                _ => {
                    s.cycles += 1;
                    // A state on the cycle, and its peak-to-peak in x.
                    let size = (end.pp, end.state.1.abs());
                    if size.0.max(size.1) > s.worst_cycle.0.max(s.worst_cycle.1) {
                        s.worst_at = (ck, cd);
                    }
                    s.worst_cycle = (s.worst_cycle.0.max(size.0), s.worst_cycle.1.max(size.1));
                }
            }
        }
    }
    s
}

/// docs/stability.md's row of a [`Summary`]: runs, at rest, in a cycle, and the largest
/// cycle with the tuning it came from.
fn doc_row(t: Fixed, region: &str, s: &Summary) -> Vec<String> {
    let largest = if s.cycles == 0 {
        "—".to_string()
    } else {
        format!(
            "{}, {} at `C_k = {:.1}`, `C_d = {}`",
            lab::table::grouped(s.worst_cycle.0),
            lab::table::grouped(s.worst_cycle.1),
            s.worst_at.0,
            s.worst_at.1
        )
    };
    vec![
        format!("`{t:?}`"),
        region.to_string(),
        lab::table::grouped(s.runs),
        lab::table::grouped(s.rests),
        lab::table::grouped(s.cycles),
        largest,
    ]
}

/// In the square every start ends at rest inside the dead band `|x| < 1/C_k` state LSB;
/// beyond it, some end in cycles of a few thousand state LSB at most (below `2¹²`, each
/// `2⁻²⁴` or `2⁻³²` of a position's last bit): invisible, and inside a value's rest band.
/// Writes docs/stability.md's table (`target/figures/stability/fixed-point-limits.md`).
#[test]
fn the_step_rests_in_the_square_and_cycles_far_below_a_last_bit_beyond_it() {
    println!(
        "backend region     runs  rest  cycle  unresolved  worst |C_k·x| at rest  worst cycle p-p x, |ũ| (state LSB) at (C_k, C_d)"
    );
    let mut rows = Vec::new();
    for t in [Fixed::I16F16, Fixed::I32F32] {
        let square = summarise(t, &grid(true));
        let beyond = summarise(t, &grid(false));
        for (name, s) in [("[0, 1]²", &square), ("beyond", &beyond)] {
            println!(
                "{t:?} {name:<10} {:>5} {:>5} {:>6} {:>11} {:>22.3} {:>10}, {:<6} {:?}",
                s.runs,
                s.rests,
                s.cycles,
                s.unresolved,
                s.worst_rest_ck_x,
                s.worst_cycle.0,
                s.worst_cycle.1,
                s.worst_at
            );
        }
        rows.push(doc_row(t, "square", &square));
        rows.push(doc_row(t, "beyond", &beyond));
        assert_eq!(
            (square.rests, square.runs),
            (square.runs, 6 * grid(true).len())
        );
        assert!(square.worst_rest_ck_x < 1.0, "{square:?}");
        assert_eq!(beyond.unresolved, 0, "{beyond:?}");
        assert!(beyond.cycles > 0, "{beyond:?}");
        assert!(
            beyond.worst_cycle.0.max(beyond.worst_cycle.1) < 1 << 12,
            "{beyond:?}"
        );
    }
    let header = [
        "backend",
        "region",
        "runs",
        "at rest",
        "in a cycle",
        "largest cycle (state last bits): `x` peak to peak, largest `\\|ũ\\|` on a cycle",
    ];
    let path = lab::table::write_figures(
        "stability/fixed-point-limits.md",
        &lab::table::markdown(&header, &rows),
    );
    println!("wrote {}", path.display());
}

/// Beyond the square a value still comes to rest, even with a threshold far below its last
/// bit: its rest band holds a swing of about one last bit (`RestThreshold`), which covers
/// the state's cycles. Including an undersampled, very lightly damped oscillator from the
/// exact map (`f·dt = 0.3`, `ζ = 3·10⁻⁴`, so `C_k ≈ 2.6`), and `C_d > 1` near Jury's edge.
fn beyond_the_square_comes_to_rest<S: Scalar>() {
    let tiny = RestThreshold::new(1e-12, 1e-12).expect("positive");
    let dt = 1e-3;
    let cases = [
        Tuning::from_coefficients_extended(2.0, 0.1, dt),
        Tuning::from_coefficients_extended(3.0, 0.119, dt),
        Tuning::from_coefficients_extended(0.357, 1.82, dt),
        Tuning::from_coefficients_extended(0.1, 1.949, dt),
        Tuning::from_frequency(0.3 / dt, 3e-4, dt),
    ];
    for tuning in cases.map(|t| t.expect("stable")) {
        assert!(tuning.stiffness() > 1.0 || tuning.damping() > 1.0);
        let mut v = SpringValue::<S>::new([S::from_f64(100.0)], &tuning)
            .expect("representable")
            .with_rest_threshold(tiny);
        v.set_target([S::ZERO]);
        let settled = (0..2_000_000).any(|_| v.step() == Motion::Settled);
        assert!(settled, "{} {tuning:?}: still moving", S::NAME);
        assert_eq!(v.position(), [S::ZERO]);
    }
}

#[test]
fn a_fixed_point_value_beyond_the_square_comes_to_rest() {
    beyond_the_square_comes_to_rest::<I16F16>();
    beyond_the_square_comes_to_rest::<I32F32>();
}

// ---------------------------------------------------------------------------
// Networks
// ---------------------------------------------------------------------------

const P: usize = 32;
const K: usize = 64;
const DT: f64 = 1.0 / 120.0;

/// How a network ended: asleep (after how many steps), or still awake with the largest
/// step velocity over its last 1 000 steps (in LSB; in units for floats).
#[derive(Debug)]
enum Outcome {
    Asleep(usize),
    Awake { u_lsb: f64, standstill: bool },
}

fn run_network<S: Scalar>(
    top: &Topology,
    stepper: Stepper,
    tuning: &Tuning,
    gravity: f64,
    sleep: bool,
    steps: usize,
) -> Outcome {
    let mut config = SceneConfig::new(DT)
        .expect("dt > 0")
        .stepper(stepper)
        .limit_policy(LimitPolicy::Clamp)
        .gravity([S::ZERO, S::from_f64(-gravity)])
        .expect("finite");
    if !sleep {
        config = config.no_sleep();
    }
    let mut scene = Scene::<S, 2, P, K>::new(config);
    let scale = 0.1; // 10 cm between particles
    let at = |p: [f64; 2]| [S::from_f64(p[0] * scale), S::from_f64(p[1] * scale)];
    let ids: Vec<_> = top
        .positions
        .iter()
        .enumerate()
        .map(|(i, &p)| {
            if top.is_free(i) {
                let mass = S::from_f64(1.0 / top.inverse_masses[i]);
                scene.add_particle(at(p), mass).expect("room")
            } else {
                scene.add_pinned(at(p)).expect("room")
            }
        })
        .collect();
    for &(a, b) in &top.springs {
        scene
            .add_spring_at_rest(ids[a], ids[b], tuning)
            .expect("clamped");
    }
    for (i, p) in top.deformed(0.1, 5).into_iter().enumerate() {
        if top.is_free(i) {
            scene.set_position(ids[i], at(p)).expect("live");
        }
    }
    let lsb = if S::RESOLUTION > 0.0 {
        S::RESOLUTION
    } else {
        1.0
    };
    let mut u_max = 0.0f64;
    let mut last: Vec<[S; 2]> = Vec::new();
    let mut standstill = true;
    for n in 0..steps {
        let _ = scene.step();
        if sleep
            && ids
                .iter()
                .all(|&p| scene.is_pinned(p) == Ok(true) || scene.is_asleep(p) == Ok(true))
        {
            return Outcome::Asleep(n + 1);
        }
        if n + 1000 >= steps {
            let now: Vec<[S; 2]> = ids
                .iter()
                .map(|&p| scene.position(p).expect("live"))
                .collect();
            standstill &= last.is_empty() || now == last;
            last = now;
            for &p in &ids {
                for c in scene.velocity(p).expect("live") {
                    u_max = u_max.max(c.to_f64().abs() * DT / lsb);
                }
            }
        }
    }
    Outcome::Awake {
        u_lsb: u_max,
        standstill,
    }
}

/// Braced networks (no floppy mode: a rope or an unbraced mesh keeps swinging on its
/// undamped transverse modes in any backend, which is physics, not rounding).
fn network_topologies() -> Vec<(Topology, f64)> {
    vec![
        (Topology::mesh(3, 3, true, false), 0.0),
        (Topology::mesh(4, 4, true, false), 0.0),
        (Topology::mesh(4, 4, true, true), 9.81),
    ]
}

type Row = (String, Outcome, Outcome);

/// Every network at the scene's limits (every spring rigid, clamped) and at a soft
/// `(0.05, 0.05)`, in both steppers: without sleep, does it stop dead or keep moving;
/// with sleep, does its island fall asleep within 20 000 steps?
fn network_table<S: Scalar>() -> Vec<Row> {
    let mut rows = Vec::new();
    let rigid = Tuning::rigid(DT).expect("dt > 0");
    let soft = Tuning::from_coefficients(0.05, 0.05, DT).expect("in the square");
    for (top, g) in network_topologies() {
        for stepper in [Stepper::GaussSeidel, Stepper::Jacobi] {
            for (c, tuning) in [("limit", &rigid), ("0.05", &soft)] {
                let free = run_network::<S>(&top, stepper, tuning, g, false, 20_000);
                let sleep = run_network::<S>(&top, stepper, tuning, g, true, 20_000);
                let name = format!("{} {} {stepper:?} C = {c}", S::NAME, top.name);
                rows.push((name, free, sleep));
            }
        }
    }
    rows
}

fn print_rows(rows: &[Row]) {
    for (name, free, sleep) in rows {
        println!("{name:<45} no sleep: {free:?}   sleep: {sleep:?}");
    }
}

/// Every braced network falls asleep, in `f64` and in both fixed-point backends; without
/// sleep, what is left moving is below a tenth of a last bit per step (rounding of the
/// lengths and of the weights in the wide state; the old narrow state cycled by 2 to 4
/// last bits in `I16F16`), far inside the sleep threshold, and the rigid `I32F32` networks
/// stop dead.
#[test]
fn braced_networks_fall_asleep_and_move_less_than_a_last_bit() {
    let mut rows = network_table::<f64>();
    rows.extend(network_table::<I32F32>());
    rows.extend(network_table::<I16F16>());
    print_rows(&rows);
    for (name, free, sleep) in &rows {
        assert!(
            matches!(sleep, Outcome::Asleep(n) if *n < 20_000),
            "{name}: {sleep:?}"
        );
        if let Outcome::Awake { u_lsb, standstill } = free {
            let bound = if name.starts_with("f64") { 1e-9 } else { 0.1 };
            assert!(*u_lsb < bound, "{name}: {free:?}");
            if name.starts_with("I32F32") && name.ends_with("limit") {
                assert!(standstill, "{name}: {free:?}");
            }
        }
    }
}
