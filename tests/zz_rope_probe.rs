use stiffspring::scene::{Scene, SceneConfig};
use stiffspring::{I16F16, I32F32, Scalar, Tuning};
fn energy<S: Scalar>(
    s: &Scene<S, 2, 10, 9>,
    ids: &[stiffspring::scene::ParticleId],
    ck: f64,
    dt: f64,
    rest: f64,
) -> f64 {
    let m = 1.0;
    let mut e = 0.0;
    for &p in ids {
        let v = s.velocity(p).unwrap();
        e += 0.5 * m * (v[0].to_f64().powi(2) + v[1].to_f64().powi(2));
    }
    let k = ck * 0.5 * m / (dt * dt);
    for w in ids.windows(2) {
        let a = s.position(w[0]).unwrap();
        let b = s.position(w[1]).unwrap();
        let d = ((b[0].to_f64() - a[0].to_f64()).powi(2) + (b[1].to_f64() - a[1].to_f64()).powi(2))
            .sqrt();
        e += 0.5 * k * (d - rest).powi(2);
    }
    e
}
fn run<S: Scalar>(steps: usize) -> (f64, f64, f64) {
    let dt = 1e-3;
    let ck = 0.05;
    let t = Tuning::from_coefficients(ck, 0.0, dt).unwrap();
    let mut s = Scene::<S, 2, 10, 9>::new(SceneConfig::new(dt).unwrap().no_sleep());
    let mut ids = vec![];
    for i in 0..10 {
        // zigzag stretched rope
        let y = if i % 2 == 0 { 0.0 } else { 0.3 };
        ids.push(
            s.add_particle(
                [S::from_f64(i as f64 * 0.9), S::from_f64(y)],
                S::from_f64(1.0),
            )
            .unwrap(),
        );
    }
    for w in ids.windows(2) {
        s.add_spring(w[0], w[1], S::from_f64(1.0), &t).unwrap();
    }
    let e0 = energy(&s, &ids, ck, dt, 1.0);
    let (mut lo, mut hi) = (f64::MAX, 0.0f64);
    for n in 0..steps {
        let _ = s.step();
        if n % 1000 == 999 {
            let e = energy(&s, &ids, ck, dt, 1.0) / e0;
            lo = lo.min(e);
            hi = hi.max(e);
        }
    }
    (lo, hi, energy(&s, &ids, ck, dt, 1.0) / e0)
}
#[test]
fn rope_energy() {
    println!("f64 {:?}", run::<f64>(1_000_000));
    println!("f32 {:?}", run::<f32>(1_000_000));
    println!("I32F32 {:?}", run::<I32F32>(1_000_000));
    println!("I16F16 {:?}", run::<I16F16>(1_000_000));
}
