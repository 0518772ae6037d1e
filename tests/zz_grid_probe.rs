//! scratch: issue-10 grid through the public API
use stiffspring::{I16F16, I32F32, Scalar, SpringValue, Tuning};
fn analytic(w: f64, z: f64, x0: f64, v0: f64, t: f64) -> f64 {
    if z < 1.0 {
        let wd = w * (1.0 - z * z).sqrt();
        (-z * w * t).exp() * (x0 * (wd * t).cos() + (v0 + z * w * x0) / wd * (wd * t).sin())
    } else if z == 1.0 {
        (-w * t).exp() * (x0 + (v0 + w * x0) * t)
    } else {
        let g = w * (z * z - 1.0).sqrt();
        let (s1, s2) = (-z * w + g, -z * w - g);
        let b = (v0 - s1 * x0) / (s2 - s1);
        let a = x0 - b;
        a * (s1 * t).exp() + b * (s2 * t).exp()
    }
}
fn run<S: Scalar>(f: f64, z: f64, rate: f64, amp: f64, fling: bool, steps: usize) -> Option<f64> {
    let dt = 1.0 / rate;
    let t = Tuning::from_frequency(f, z, dt).ok()?;
    let w = 2.0 * std::f64::consts::PI * f;
    let mut v = SpringValue::<S>::new([S::from_f64(0.0)], &t).ok()?;
    let (x0, v0) = if fling { (0.0, amp * w) } else { (-amp, 0.0) };
    // target 0 offset x0: start at x0 with target 0
    v.try_set_position([S::from_f64(x0)]).ok()?;
    if fling {
        v.try_fling([S::from_f64(v0)]).ok()?;
    }
    let mut worst: f64 = 0.0;
    for n in 1..=steps {
        v.advance();
        let x = v.position()[0].to_f64();
        let e = (x - analytic(w, z, x0, v0, n as f64 * dt)).abs();
        worst = worst.max(e);
    }
    Some(worst / amp)
}
#[test]
fn grid() {
    for (name, f_run) in [
        (
            "I16F16",
            run::<I16F16> as fn(f64, f64, f64, f64, bool, usize) -> Option<f64>,
        ),
        ("I32F32", run::<I32F32>),
        ("f32", run::<f32>),
        ("f64", run::<f64>),
    ] {
        for rate in [60.0, 240.0, 1000.0, 4000.0, 10000.0] {
            let mut worst: f64 = 0.0;
            let mut worst0: f64 = 0.0;
            let mut refused = 0;
            for f in [1.0, 2.0, 5.0, 12.0, 20.0, 50.0] {
                if f / rate > 0.2 {
                    continue;
                }
                for amp in [1.0, 100.0] {
                    for fling in [false, true] {
                        for z in [0.0, 0.1, 0.3, 0.7, 1.0, 2.0, 10.0] {
                            match f_run(f, z, rate, amp, fling, 10_000) {
                                Some(e) => {
                                    if z == 0.0 {
                                        worst0 = worst0.max(e)
                                    } else {
                                        worst = worst.max(e)
                                    }
                                }
                                None => refused += 1,
                            }
                        }
                    }
                }
            }
            println!(
                "{name} {rate} Hz: damped {worst:.2e} undamped {worst0:.2e} refused {refused}"
            );
        }
    }
}
#[test]
fn worst60() {
    for f in [1.0, 2.0, 5.0, 12.0] {
        for amp in [1.0, 100.0] {
            for fling in [false, true] {
                for z in [0.1, 0.3, 0.7, 1.0, 2.0, 10.0] {
                    let a = run::<f32>(f, z, 60.0, amp, fling, 10_000);
                    let b = run::<f64>(f, z, 60.0, amp, fling, 10_000);
                    let c = run::<I16F16>(f, z, 60.0, amp, fling, 10_000);
                    if a.unwrap_or(1.0) > 1e-5 || b.unwrap_or(1.0) > 1e-9 || c.unwrap_or(1.0) > 1e-4
                    {
                        println!(
                            "f {f} amp {amp} fling {fling} z {z}: f32 {a:?} f64 {b:?} I16F16 {c:?}"
                        );
                    }
                }
            }
        }
    }
}
