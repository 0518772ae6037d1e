//! `Tuning::from_rope_stretch` against the statics of a hanging chain: a rope tuned for a
//! stretch, hung from a pin and left to come to rest in a scene, hangs with each link as
//! long as its share of the weight below it makes it (`T_i = (N − i + 1)·m·g` over the
//! link's stiffness `C_k·μ_i/dt²`, with `μ` the reduced mass of its ends: `m` at the pin,
//! `m/2` between two particles), and as long in all as asked.

use stiffspring::scene::{Scene, SceneConfig, Stepper};
use stiffspring::{Error, Parameter, Scalar, Tuning};

const DT: f64 = 1.0 / 240.0;
const G: f64 = 9.81;

/// Each link's length at rest, top first, for `n` particles of mass `mass` on links of
/// rest length `link`, tuned for `stretch` with stretch damping `damping`, stepped by
/// `stepper`.
fn hang<S: Scalar>(
    n: usize,
    link: f64,
    mass: f64,
    stretch: f64,
    damping: f64,
    stepper: Stepper,
) -> Vec<f64> {
    let tuning = Tuning::from_rope_stretch(n as u32, link, G, stretch, damping, DT).unwrap();
    // Drag to settle the swing faster; at rest it does nothing. No sleep: the rope comes
    // to its exact rest instead of stopping within a threshold of it.
    let config = SceneConfig::<S, 2>::new(DT)
        .unwrap()
        .gravity([S::ZERO, S::from_f64(-G)])
        .unwrap()
        .linear_damping(4.0)
        .unwrap()
        .no_sleep()
        .stepper(stepper);
    let mut rope = Scene::<S, 2, 32, 32>::new(config);
    let mut ids = vec![rope.add_pinned([S::ZERO, S::ZERO]).unwrap()];
    for i in 1..=n {
        let at = [S::ZERO, S::from_f64(-(i as f64) * link)];
        ids.push(rope.add_particle(at, S::from_f64(mass)).unwrap());
        rope.add_spring(ids[i - 1], ids[i], S::from_f64(link), &tuning)
            .unwrap();
    }
    for _ in 0..(30.0 / DT) as usize {
        let _ = rope.step();
    }
    let y = |i: usize| rope.position(ids[i]).unwrap()[1].to_f64();
    (1..=n).map(|i| y(i - 1) - y(i)).collect()
}

/// The statics: link `i` (from 1 at the pin) of a rope of `n` particles, from the `C_k`
/// the tuning holds (the check of the formula itself is the rope's total length against
/// the one asked for).
fn expected(n: usize, link: f64, stretch: f64, i: usize) -> f64 {
    let ck = Tuning::from_rope_stretch(n as u32, link, G, stretch, 0.0, DT)
        .unwrap()
        .stiffness();
    let weight_over_mass = (n - i + 1) as f64 * G; // T_i / m
    let reduced = if i == 1 { 1.0 } else { 0.5 }; // μ_i / m
    link + weight_over_mass * DT * DT / (ck * reduced)
}

const ROPES: [(usize, f64, f64); 4] = [
    (12, 0.1, 0.05),
    (5, 0.2, 0.02),
    (20, 0.05, 0.3),
    (8, 0.1, 0.1),
];

/// Every rope of [`ROPES`], light and heavy, hangs as the statics say, within `tolerance`
/// of a link's length.
fn hangs_as_the_statics_say<S: Scalar>(damping: f64, stepper: Stepper, tolerance: f64) {
    for (n, link, stretch) in ROPES {
        for mass in [0.02, 2.0] {
            let links = hang::<S>(n, link, mass, stretch, damping, stepper);
            for (k, &length) in links.iter().enumerate() {
                let want = expected(n, link, stretch, k + 1);
                assert!(
                    (length - want).abs() <= tolerance * link,
                    "{}, {stepper:?}, C_d {damping}: {n} particles of {mass} kg, link {}: \
                     {length} against {want}",
                    S::NAME,
                    k + 1
                );
            }
            let total: f64 = links.iter().sum();
            let asked = n as f64 * link * (1.0 + stretch);
            assert!(
                (total - asked).abs() <= n as f64 * tolerance * link,
                "{}: {n} particles: {total} m against the {asked} m asked",
                S::NAME
            );
        }
    }
}

/// The force form (Jacobi) takes every spring's impulse from one state: at rest each
/// link's impulse is its statics', whatever its damping.
#[test]
fn a_rope_hangs_as_long_as_it_was_tuned_to_with_the_force_form() {
    hangs_as_the_statics_say::<f64>(0.3, Stepper::Jacobi, 1e-9);
    hangs_as_the_statics_say::<f32>(0.3, Stepper::Jacobi, 1e-4);
}

/// Gauss–Seidel (the default) without stretch damping: the statics too. (The swing is
/// damped by the scene's drag.)
#[test]
fn a_rope_hangs_as_long_as_it_was_tuned_to_without_stretch_damping() {
    hangs_as_the_statics_say::<f64>(0.0, Stepper::GaussSeidel, 1e-9);
    hangs_as_the_statics_say::<f32>(0.0, Stepper::GaussSeidel, 1e-4);
}

/// Gauss–Seidel with stretch damping damps, in place, the step velocity the links above
/// left: at rest the link to the pin is the statics' and every link below it is shorter,
/// the more so the more damping (documented with `Tuning::from_rope_stretch`; printed
/// here with `--nocapture`).
#[test]
fn stretch_damping_shortens_the_links_below_the_pin_in_place() {
    let (n, link, stretch) = (12, 0.1, 0.05);
    let mut last = vec![f64::INFINITY; n];
    for damping in [0.1, 0.3, 0.5] {
        let links = hang::<f64>(n, link, 0.02, stretch, damping, Stepper::GaussSeidel);
        let total: f64 = links.iter().sum::<f64>() - n as f64 * link;
        println!(
            "C_d {damping}: stretch {:.4} of the {stretch} asked",
            total / (n as f64 * link)
        );
        assert!((links[0] - expected(n, link, stretch, 1)).abs() <= 1e-9 * link);
        for k in 1..n {
            let statics = expected(n, link, stretch, k + 1);
            assert!(
                links[k] < statics && links[k] > link,
                "C_d {damping}, link {}",
                k + 1
            );
            assert!(links[k] < last[k], "C_d {damping}, link {}", k + 1);
        }
        last = links;
    }
}

#[test]
fn a_stretch_the_rate_cannot_hold_names_the_least_one() {
    // 12 links of 0.1 m at 240 Hz: at C_k = 1 the rope stretches 12·g·dt²/0.1.
    let least = 12.0 * G * DT * DT / 0.1;
    assert_eq!(
        Tuning::from_rope_stretch(12, 0.1, G, 0.5 * least, 0.3, DT),
        Err(Error::OutOfRange {
            parameter: Parameter::Stretch,
            value: 0.5 * least,
            bound: stiffspring::Bound::AtLeast { min: least },
        })
    );
    assert!(Tuning::from_rope_stretch(12, 0.1, G, least, 0.3, DT).is_ok());
    for (bad, parameter) in [
        (
            Tuning::from_rope_stretch(0, 0.1, G, 0.1, 0.3, DT),
            Parameter::ParticleCount,
        ),
        (
            Tuning::from_rope_stretch(12, -0.1, G, 0.1, 0.3, DT),
            Parameter::RestLength,
        ),
        (
            Tuning::from_rope_stretch(12, 0.1, f64::NAN, 0.1, 0.3, DT),
            Parameter::Acceleration,
        ),
        (
            Tuning::from_rope_stretch(12, 0.1, G, 0.0, 0.3, DT),
            Parameter::Stretch,
        ),
        (
            Tuning::from_rope_stretch(12, 0.1, G, 0.1, 1.5, DT),
            Parameter::Damping,
        ),
    ] {
        assert_eq!(bad.unwrap_err().parameter(), Some(parameter));
    }
}
