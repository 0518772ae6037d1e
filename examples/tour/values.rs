//! UI values springing to their targets: every platform preset, every backend, a fling.

use lab::plot::{Grid, Plot, Series};
use lab::reference;
use lab::table::{print, sci};
use std::path::Path;
use stiffspring::{
    I16F16, I32F32, Motion, Oscillator, RestThreshold, Scalar, SpringValue, presets,
};

/// A 60 Hz display, a value 100 px from its target.
const DT: f64 = 1.0 / 60.0;
const AMPLITUDE: f64 = 100.0;
const MAX_STEPS: usize = 600;

struct Case {
    platform: &'static str,
    name: String,
    oscillator: Oscillator,
}

fn cases() -> Vec<Case> {
    use presets::android;
    let mut out = Vec::new();
    for (name, oscillator) in presets::swiftui::ALL {
        out.push(Case {
            platform: "SwiftUI",
            name: name.into(),
            oscillator,
        });
    }
    for (name, stiffness, ratio) in [
        (
            "medium/mediumBouncy",
            android::STIFFNESS_MEDIUM,
            android::DAMPING_RATIO_MEDIUM_BOUNCY,
        ),
        (
            "low/noBouncy",
            android::STIFFNESS_LOW,
            android::DAMPING_RATIO_NO_BOUNCY,
        ),
        (
            "high/highBouncy",
            android::STIFFNESS_HIGH,
            android::DAMPING_RATIO_HIGH_BOUNCY,
        ),
        (
            "veryLow/lowBouncy",
            android::STIFFNESS_VERY_LOW,
            android::DAMPING_RATIO_LOW_BOUNCY,
        ),
    ] {
        out.push(Case {
            platform: "Android",
            name: name.into(),
            oscillator: android::spring_force(stiffness, ratio).expect("constant preset"),
        });
    }
    for (name, oscillator) in presets::react_spring::ALL {
        out.push(Case {
            platform: "react-spring",
            name: name.into(),
            oscillator,
        });
    }
    out
}

/// A value of backend `S` released from rest at `AMPLITUDE` toward 0, with `threshold`.
/// Returns the positions after each step (until rest or `MAX_STEPS`) and the steps to rest.
fn release<S: Scalar>(osc: &Oscillator, threshold: RestThreshold) -> (Vec<f64>, Option<usize>) {
    let tuning = osc.tuning(DT).expect("presets are well sampled at 60 Hz");
    let mut value = SpringValue::<S, 1>::new([S::from_f64(AMPLITUDE)], &tuning)
        .expect("valid start")
        .with_rest_threshold(threshold);
    value.set_target([S::ZERO]);
    let mut xs = Vec::new();
    for n in 1..=MAX_STEPS {
        let motion = value.step();
        xs.push(value.position()[0].to_f64());
        if motion == Motion::Settled {
            return (xs, Some(n));
        }
    }
    (xs, None)
}

/// A threshold no preset reaches in `MAX_STEPS`, to measure accuracy without snapping.
fn never() -> RestThreshold {
    RestThreshold::new(1e-300, 1e-300).expect("positive")
}

/// The analytic solution released from rest at `AMPLITUDE`, sampled after each step.
fn analytic(osc: &Oscillator, steps: usize) -> Vec<f64> {
    let (w, z) = (osc.angular_frequency(), osc.damping_ratio());
    (1..=steps)
        .map(|n| reference::analytic(AMPLITUDE, 0.0, w, z, n as f64 * DT).0)
        .collect()
}

/// The reference model's discrete map with its own (pole-formula) coefficients and its
/// own analytic start: the article's spring, independent of the library.
fn reference_map(osc: &Oscillator, steps: usize) -> Vec<f64> {
    let (w, z) = (osc.angular_frequency(), osc.damping_ratio());
    let (ck, cd) = reference::exact_coefficients_from_poles(w, z, DT);
    let mut x = AMPLITUDE;
    let mut u = reference::u0_from_analytic(AMPLITUDE, 0.0, w, z, DT);
    (0..steps)
        .map(|_| {
            reference::map_step(&mut x, &mut u, ck, cd);
            x
        })
        .collect()
}

/// The naive first-order map `C_k = k·dt²/m`, `C_d = c·dt/m`, released with `u = 0`.
fn naive_map(osc: &Oscillator, steps: usize) -> Vec<f64> {
    let (w, z) = (osc.angular_frequency(), osc.damping_ratio());
    let (ck, cd) = reference::naive_coefficients(w * w, 2.0 * z * w, 1.0, DT);
    let (mut x, mut u) = (AMPLITUDE, 0.0);
    (0..steps)
        .map(|_| {
            reference::map_step(&mut x, &mut u, ck, cd);
            x
        })
        .collect()
}

fn worst(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / AMPLITUDE
}

/// Every preset in every backend: steps to rest at Android's pixel threshold, and the
/// worst error over 600 steps (10 s) against the reference and the analytic solution.
pub fn presets(dir: &Path) {
    println!("UI values at 60 Hz, released 100 px from the target (errors relative to 100 px)");
    let mut rows = Vec::new();
    let mut panels: Vec<(&str, Plot)> = Vec::new();
    for case in cases() {
        let osc = &case.oscillator;
        let steps = |n: Option<usize>| n.map_or("—".into(), |n| n.to_string());
        let (_, rest32) = release::<f32>(osc, RestThreshold::PIXELS);
        let (_, rest16) = release::<I16F16>(osc, RestThreshold::PIXELS);
        let exact = analytic(osc, MAX_STEPS);
        let reference = reference_map(osc, MAX_STEPS);
        let x64 = release::<f64>(osc, never()).0;
        let x32 = release::<f32>(osc, never()).0;
        let x3232 = release::<I32F32>(osc, never()).0;
        let x16 = release::<I16F16>(osc, never()).0;
        let naive = naive_map(osc, MAX_STEPS);
        let naive_error = worst(&naive, &exact);
        rows.push(vec![
            format!("{} {}", case.platform, case.name),
            format!("{:.2}", osc.frequency()),
            format!("{:.2}", osc.damping_ratio()),
            format!("{} / {}", steps(rest32), steps(rest16)),
            sci(worst(&x32, &reference)),
            sci(worst(&x16, &reference)),
            sci(worst(&x64, &exact)),
            sci(worst(&x3232, &exact)),
            sci(worst(&x32, &exact)),
            sci(worst(&x16, &exact)),
            if naive_error > 1.0 {
                "unstable".into()
            } else {
                sci(naive_error)
            },
        ]);
        let (shown, _) = release::<f32>(osc, RestThreshold::PIXELS);
        let points = (0..=shown.len()).map(|n| {
            let x = if n == 0 { AMPLITUDE } else { shown[n - 1] };
            (n as f64 * DT, x)
        });
        let series = Series::line(case.name.clone(), points);
        match panels.iter_mut().find(|(p, _)| *p == case.platform) {
            Some((_, plot)) => *plot = plot.clone().series(series),
            None => panels.push((
                case.platform,
                Plot::new(format!("{} presets (f32, 60 Hz)", case.platform))
                    .x_label("time [s]")
                    .y_label("offset [px]")
                    .hline(0.0, "target")
                    .series(series),
            )),
        }
    }
    print(
        &[
            "preset",
            "f [Hz]",
            "ζ",
            "rest f32/I16F16",
            "ref: f32",
            "I16F16",
            "analytic: f64",
            "I32F32",
            "f32",
            "I16F16",
            "naive map",
        ],
        &rows,
    );
    println!(
        "(rest: steps until the value snaps to its target at 0.75 px and 46.9 px/s; ref: worst \
         error over 600 steps against the reference model's own map; analytic: against the \
         continuous spring; naive map: C_k = k·dt², C_d = c·dt released with u = 0, in f64)\n"
    );
    let mut grid = Grid::new("UI presets released 100 px from their target").columns(3);
    for (_, plot) in panels {
        grid = grid.plot(plot.size(460, 320));
    }
    let path = dir.join("presets.svg");
    grid.write(&path).expect("write presets.svg");
    println!("  wrote {}", path.display());
    error_plot(dir);
}

/// How far each backend's value is from the continuous spring, in pixels, for SwiftUI's
/// `.bouncy` released 100 px from its target: what a UI user can see (a pixel) and where
/// each backend stands below it. The axis stops at 1e−8 px: below that nothing is visible
/// and only the format's resolution is left.
fn error_plot(dir: &Path) {
    const SHOWN: usize = 240; // 4 s at 60 Hz: every backend is far below a pixel by then
    let osc = presets::swiftui::BOUNCY;
    let exact = analytic(&osc, SHOWN);
    let naive = naive_map(&osc, SHOWN);
    // A fixed-point value lands exactly on its target (state 0) once the offset left is
    // below its resolution, and stays there: from then on its error is the continuous
    // spring's own remaining offset, drawn as such instead of ending the line.
    let landed = |xs: Vec<f64>| -> (Vec<f64>, Option<usize>) {
        let n = xs.len();
        let mut xs = xs;
        xs.truncate(SHOWN);
        xs.resize(SHOWN, 0.0);
        (xs, (n < SHOWN).then_some(n))
    };
    let series = |name: &str, xs: &[f64]| {
        Series::line(
            name.to_string(),
            xs.iter()
                .zip(&exact)
                .enumerate()
                .map(|(n, (x, e))| ((n + 1) as f64 * DT, (x - e).abs())),
        )
    };
    let (x16, landed16) = landed(release::<I16F16>(&osc, never()).0);
    let (x3232, landed3232) = landed(release::<I32F32>(&osc, never()).0);
    let plot =
        Plot::new("distance from the continuous spring, SwiftUI .bouncy from 100 px at 60 Hz")
            .x_label("time [s]")
            .y_label("error [px]")
            .log_y()
            .y_range(1e-8, 100.0)
            .hline(1.0, "1 px")
            .series(series("f64", &release::<f64>(&osc, never()).0))
            .series(series("f32", &release::<f32>(&osc, never()).0))
            .series(series("I32F32", &x3232))
            .series(series("I16F16", &x16))
            .series(series("naive map (f64)", &naive).dashed());
    let path = dir.join("errors.svg");
    plot.write(&path).expect("write errors.svg");
    let when = |n: Option<usize>| {
        n.map_or("not within 4 s".into(), |n| {
            format!("at {:.2} s", n as f64 * DT)
        })
    };
    println!(
        "  wrote {} (error in px of a 100 px release, 0–4 s; I16F16 lands exactly on its target \
         {}, I32F32 {}: from then on the line is the continuous spring's own remaining offset)",
        path.display(),
        when(landed16),
        when(landed3232)
    );
}

/// A fling: a value resting on its target is thrown at 800 px/s. The library starts it
/// on the continuous trajectory (`u₀ = x(0) − x(−dt)`); the obvious `u₀ = v₀·dt` misses.
pub fn fling(dir: &Path) {
    const V0: f64 = 800.0;
    const STEPS: usize = 120;
    let osc = presets::swiftui::BOUNCY;
    let tuning = osc.tuning(DT).expect("well sampled");
    let (w, z) = (osc.angular_frequency(), osc.damping_ratio());
    let exact: Vec<f64> = (1..=STEPS)
        .map(|n| reference::analytic(0.0, V0, w, z, n as f64 * DT).0)
        .collect();
    let amplitude = exact.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    fn flung<S: Scalar>(tuning: stiffspring::Tuning, steps: usize) -> Vec<f64> {
        let mut v = SpringValue::<S, 1>::new([S::ZERO], &tuning)
            .expect("valid")
            .with_rest_threshold(RestThreshold::new(1e-300, 1e-300).expect("positive"));
        v.try_fling([S::from_f64(V0)]).expect("in range");
        (0..steps)
            .map(|_| {
                v.advance();
                v.position()[0].to_f64()
            })
            .collect()
    }
    // The same map started the obvious way, in the reference model.
    let (ck, cd) = (tuning.stiffness(), tuning.damping());
    let (mut x, mut u) = (0.0, V0 * DT);
    let obvious: Vec<f64> = (0..STEPS)
        .map(|_| {
            reference::map_step(&mut x, &mut u, ck, cd);
            x
        })
        .collect();
    let err = |xs: &[f64]| {
        xs.iter()
            .zip(&exact)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / amplitude
    };
    let x32 = flung::<f32>(tuning, STEPS);
    println!("A fling: SwiftUI .bouncy at 60 Hz thrown at 800 px/s from its target (2 s)");
    print(
        &["start", "f64", "f32", "I32F32", "I16F16"],
        &[
            vec![
                "u₀ = x(0) − x(−dt) (library)".into(),
                sci(err(&flung::<f64>(tuning, STEPS))),
                sci(err(&x32)),
                sci(err(&flung::<I32F32>(tuning, STEPS))),
                sci(err(&flung::<I16F16>(tuning, STEPS))),
            ],
            vec![
                "u₀ = v₀·dt (obvious)".into(),
                sci(err(&obvious)),
                "".into(),
                "".into(),
                "".into(),
            ],
        ],
    );
    println!("(worst |x − x_analytic| relative to the peak of {amplitude:.1} px)\n");
    let t = |n: usize| (n + 1) as f64 * DT;
    let fine: Vec<(f64, f64)> = (0..=STEPS * 8)
        .map(|i| {
            let time = i as f64 * DT / 8.0;
            (time, reference::analytic(0.0, V0, w, z, time).0)
        })
        .collect();
    let plot = Plot::new("A fling at 800 px/s, SwiftUI .bouncy at 60 Hz")
        .x_label("time [s]")
        .y_label("position [px]")
        .hline(0.0, "target")
        .series(Series::line("continuous spring", fine))
        .series(Series::markers(
            "stiffspring f32",
            std::iter::once((0.0, 0.0)).chain(x32.iter().enumerate().map(|(n, x)| (t(n), *x))),
        ))
        .series(
            Series::line(
                "u₀ = v₀·dt",
                std::iter::once((0.0, 0.0))
                    .chain(obvious.iter().enumerate().map(|(n, x)| (t(n), *x))),
            )
            .dashed(),
        );
    let path = dir.join("fling.svg");
    plot.write(&path).expect("write fling.svg");
    println!("  wrote {}\n", path.display());
}
