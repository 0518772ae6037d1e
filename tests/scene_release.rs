//! [`Scene::release`] against the analytic damped oscillator: a body on a spring to a
//! pinned particle, stretched and released, follows the continuous spring at every
//! sample, as a [`SpringValue`] released from the same offset does.
//!
//! Three geometries, each along a direction that is not an axis (`(0.6, 0.8)` in 2-D):
//! 1-D; 2-D with a point spring (rest length 0, a drag handle); 2-D with a rest length
//! (twice the amplitude), where the body moves along the line through the pin. Springs of
//! 1–50 Hz at 60 Hz–10 kHz with `f·dt ≤ 0.2`, ζ from 0 to 10, amplitudes 1 and 100,
//! 10 000 steps. The measure is the largest distance of the body from the analytic
//! trajectory over the run, relative to the amplitude; the same case run by a
//! `SpringValue` is printed beside it.
//!
//! The bound is the value's: `1e−9` in `f64`, `1e−5` in `f32` (for ζ = 0 the drift of an
//! undamped `f32` spring, whose `C_k` carries 24 bits: `tests/exact_map.rs`), `1e−4` in
//! `I16F16`. With a rest length the oscillator is the spring's extension, the body's
//! distance from the pin, and that is what the bound holds. Its direction is a neutral
//! mode: the spring pulls along its axis only and nothing damps a turn about the pin
//! (angular momentum is conserved), so the rounding of each step's velocity (`f32`: an ulp
//! of a velocity as large as the amplitude per step at 60 Hz) sets the body turning
//! slowly, and the drift off the line grows with the run as the angular momentum it
//! gathered times the time: up to 6.4e−2 of the amplitude in `f32` and 7.5e−3 in
//! `I16F16` (their axes' last bits) after 10 000 steps of an undamped 12 Hz spring at
//! 60 Hz (166 s), 1e−10 in `f64`. A value has no such mode; a point spring damps both
//! axes. The test bounds it at 3× those. `cargo test --release --test scene_release -- --nocapture` prints the worst
//! case of each; `STIFFSPRING_FULL_GRID=1` runs every frequency and rate of
//! `tests/exact_map.rs`'s full grid.

use core::f64::consts::PI;
use lab::reference::analytic;
use stiffspring::scene::{Scene, SceneConfig};
use stiffspring::{I16F16, Scalar, SpringValue, Tuning};

const STEPS: usize = 10_000;
const ZETAS: [f64; 8] = [0.0, 0.1, 0.3, 0.7, 1.0, 2.0, 3.0, 10.0];

#[derive(Clone, Copy, Debug, PartialEq)]
enum Geometry {
    Line,
    Point,
    RestLength,
}

#[derive(Clone, Copy, Debug)]
struct Case {
    geometry: Geometry,
    frequency: f64,
    zeta: f64,
    rate: f64,
    amplitude: f64,
}

fn grid() -> Vec<Case> {
    let full = std::env::var_os("STIFFSPRING_FULL_GRID").is_some();
    let (frequencies, rates): (&[f64], &[f64]) = if full {
        (
            &[1.0, 1.37, 2.0, 3.3, 5.0, 7.7, 12.0, 20.0, 37.1, 50.0],
            &[60.0, 120.0, 240.0, 500.0, 1000.0, 2000.0, 4000.0, 10_000.0],
        )
    } else {
        (&[1.0, 3.3, 12.0, 50.0], &[60.0, 1000.0, 10_000.0])
    };
    let mut cases = Vec::new();
    for geometry in [Geometry::Line, Geometry::Point, Geometry::RestLength] {
        for &rate in rates {
            for &frequency in frequencies {
                if frequency / rate > 0.2 {
                    continue;
                }
                for zeta in ZETAS {
                    for amplitude in [1.0, 100.0] {
                        cases.push(Case {
                            geometry,
                            frequency,
                            zeta,
                            rate,
                            amplitude,
                        });
                    }
                }
            }
        }
    }
    cases
}

/// The direction the body is stretched along (2-D).
const DIRECTION: [f64; 2] = [0.6, 0.8];

/// The worst distance from the analytic trajectory of the scene `D` released from the
/// case's stretch (with a rest length, of its distance from the pin from `L + x(t)`), and
/// with a rest length its worst distance from the line it started on; both relative to
/// the amplitude.
fn scene_error<S: Scalar, const D: usize>(case: &Case) -> (f64, f64) {
    let dt = 1.0 / case.rate;
    let tuning = Tuning::from_frequency(case.frequency, case.zeta, dt).expect("valid");
    let mut scene = Scene::<S, D, 2, 1>::new(SceneConfig::new(dt).expect("dt").no_sleep());
    let rest = if case.geometry == Geometry::RestLength {
        2.0 * case.amplitude
    } else {
        0.0
    };
    let direction: [f64; D] = core::array::from_fn(|k| if D == 1 { 1.0 } else { DIRECTION[k] });
    let at = |x: f64| direction.map(|c| c * (rest + x));
    let pin = scene.add_pinned([S::ZERO; D]).expect("room");
    let body = scene
        .add_particle(at(case.amplitude).map(S::from_f64), S::ONE)
        .expect("room");
    scene
        .add_spring(pin, body, S::from_f64(rest), &tuning)
        .expect("one spring to a pinned particle is accepted as a value accepts it");
    scene.release().expect("a representable release");
    let omega = 2.0 * PI * case.frequency;
    let (mut worst, mut sideways): (f64, f64) = (0.0, 0.0);
    for n in 1..=STEPS {
        let _ = scene.step();
        let (x, _) = analytic(case.amplitude, 0.0, omega, case.zeta, n as f64 * dt);
        let p = scene.position(body).expect("live").map(S::to_f64);
        if case.geometry == Geometry::RestLength {
            // The spring's oscillator is its extension: the distance from the pin.
            let r = p.iter().map(|c| c * c).sum::<f64>().sqrt();
            worst = worst.max((r - (rest + x).abs()).abs());
            sideways = sideways.max((p[0] * DIRECTION[1] - p[1] * DIRECTION[0]).abs());
        } else {
            let expected = at(x);
            let distance = (0..D)
                .map(|k| (p[k] - expected[k]).powi(2))
                .sum::<f64>()
                .sqrt();
            worst = worst.max(distance);
        }
    }
    (worst / case.amplitude, sideways / case.amplitude)
}

/// The same case run by a `SpringValue` (1-D: the oscillator of the extension).
fn value_error<S: Scalar>(case: &Case) -> f64 {
    let dt = 1.0 / case.rate;
    let tuning = Tuning::from_frequency(case.frequency, case.zeta, dt).expect("valid");
    let mut v = SpringValue::<S>::new([S::from_f64(case.amplitude)], &tuning).expect("ok");
    v.set_target([S::ZERO]);
    let omega = 2.0 * PI * case.frequency;
    let mut worst: f64 = 0.0;
    for n in 1..=STEPS {
        v.advance();
        let (x, _) = analytic(case.amplitude, 0.0, omega, case.zeta, n as f64 * dt);
        worst = worst.max((v.position()[0].to_f64() - x).abs());
    }
    worst / case.amplitude
}

fn error<S: Scalar>(case: &Case) -> (f64, f64) {
    match case.geometry {
        Geometry::Line => scene_error::<S, 1>(case),
        _ => scene_error::<S, 2>(case),
    }
}

/// The value's bound for the case (see the module docs).
fn bound<S: Scalar>(case: &Case) -> f64 {
    match S::NAME {
        "f64" => 1e-9,
        "I16F16" => 1e-4,
        _ if case.zeta == 0.0 => {
            // exact_map's drift bound: half an ulp of C_k over the run, plus 1e−5.
            let theta = 2.0 * PI * case.frequency / case.rate;
            1e-5 + STEPS as f64 * (theta / 2.0).tan() * 2f64.powi(-24)
        }
        _ => 1e-5,
    }
}

/// How far a body on a spring with a rest length may wander off its line (relative to
/// the amplitude): about 3× the measured worst (see the module docs).
fn sideways_bound<S: Scalar>() -> f64 {
    match S::NAME {
        "f64" => 1e-9,
        "I16F16" => 2e-2,
        _ => 2e-1,
    }
}

/// The worst error of each geometry over the grid (and over its damped cases alone), each
/// with a value's error on the same case: a row of docs/networks.md's table.
fn worst<S: Scalar>() -> Vec<String> {
    let mut row = vec![format!("`{}`", S::NAME)];
    for geometry in [Geometry::Line, Geometry::Point, Geometry::RestLength] {
        let mut all: (f64, Option<Case>) = (0.0, None);
        let mut damped: (f64, Option<Case>) = (0.0, None);
        for case in grid().into_iter().filter(|c| c.geometry == geometry) {
            let (e, _) = error::<S>(&case);
            if e > all.0 {
                all = (e, Some(case));
            }
            if case.zeta > 0.0 && e > damped.0 {
                damped = (e, Some(case));
            }
        }
        let cell = |(e, case): (f64, Option<Case>)| match case {
            Some(c) => format!(
                "{e:.1e} at ζ = {}, {} Hz at {} Hz (a value: {:.1e})",
                c.zeta,
                c.frequency,
                c.rate,
                value_error::<S>(&c)
            ),
            None => "–".into(),
        };
        row.push(cell(all));
        row.push(cell(damped));
    }
    row
}

/// docs/networks.md's table of the worst releases in every backend, written for
/// `scripts/check-figures` (`target/figures/scene-release.md`).
#[test]
fn release_table() {
    let rows = vec![worst::<f64>(), worst::<f32>(), worst::<I16F16>()];
    let header = [
        "backend",
        "1-D",
        "1-D, ζ > 0",
        "2-D point spring",
        "2-D point spring, ζ > 0",
        "2-D with rest length (its extension)",
        "2-D with rest length, ζ > 0",
    ];
    // The full grid's worst cases go to their own file: the docs' table is the short grid's.
    let name = if std::env::var_os("STIFFSPRING_FULL_GRID").is_some() {
        "scene-release-full.md"
    } else {
        "scene-release.md"
    };
    let path = lab::table::write_figures(name, &lab::table::markdown(&header, &rows));
    println!("wrote {}", path.display());
}

fn check<S: Scalar>() {
    for geometry in [Geometry::Line, Geometry::Point, Geometry::RestLength] {
        let mut worst = (0.0, None);
        let mut worst_sideways: (f64, Option<Case>) = (0.0, None);
        let mut failures = Vec::new();
        for case in grid().into_iter().filter(|c| c.geometry == geometry) {
            let (e, sideways) = error::<S>(&case);
            if e > bound::<S>(&case) || sideways > sideways_bound::<S>() {
                failures.push((e, sideways, case, value_error::<S>(&case)));
            }
            if sideways > worst_sideways.0 {
                worst_sideways = (sideways, Some(case));
            }
            if e / bound::<S>(&case) > worst.0 {
                worst = (e / bound::<S>(&case), Some((e, case)));
            }
        }
        if let (_, Some((e, case))) = worst {
            println!(
                "{} {geometry:?}: worst {e:.2e} ({:.2} of its bound) at {} Hz, ζ = {}, {} Hz, A = {}; a value there: {:.2e}",
                S::NAME,
                worst.0,
                case.frequency,
                case.zeta,
                case.rate,
                case.amplitude,
                value_error::<S>(&case)
            );
        }
        if let (w, Some(case)) = worst_sideways {
            println!(
                "{} {geometry:?}: off its line by up to {w:.2e} at {} Hz, ζ = {}, {} Hz, A = {}",
                S::NAME,
                case.frequency,
                case.zeta,
                case.rate,
                case.amplitude
            );
        }
        assert!(
            failures.is_empty(),
            "{} {geometry:?}: {failures:?}",
            S::NAME
        );
    }
}

#[test]
fn f64_releases_exactly() {
    check::<f64>();
}

#[test]
fn f32_releases_within_a_values_error() {
    check::<f32>();
}

#[test]
fn i16f16_releases_within_a_values_error() {
    check::<I16F16>();
}
