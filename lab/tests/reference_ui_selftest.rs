//! Self-tests of `lab::reference::ui`: each closed form against its defining equation
//! (finite differences), its published numbers, or its limits.

use lab::reference::ui::*;

/// Central difference of `f` at `t`.
fn derivative(f: impl Fn(f64) -> f64, t: f64) -> f64 {
    let h = 1e-6;
    (f(t + h) - f(t - h)) / (2.0 * h)
}

#[test]
fn a_throw_obeys_its_friction_and_rests_where_it_says() {
    let (x0, v0, c) = (10.0, 800.0, 2.5);
    for t in [0.0, 0.1, 0.7, 3.0] {
        let (x, v) = throw(x0, v0, c, t);
        assert!((derivative(|t| throw(x0, v0, c, t).0, t) - v).abs() < 1e-5 * v0);
        assert!((derivative(|t| throw(x0, v0, c, t).1, t) + c * v).abs() < 1e-5 * v0 * c);
        assert!(x >= x0 && x < throw_rest(x0, v0, c));
    }
    assert!((throw(x0, v0, c, 60.0).0 - throw_rest(x0, v0, c)).abs() < 1e-9);
}

#[test]
fn platform_frictions_keep_their_fraction_per_millisecond() {
    for d in [IOS_NORMAL, IOS_FAST] {
        let c = ios_rate(d);
        assert!(((-c * 1e-3).exp() - d).abs() < 1e-15);
    }
    assert!((ios_rate(IOS_NORMAL) - 2.002_002_670_673_3).abs() < 1e-9);
    assert_eq!(android_rate(1.0), 4.2);
}

#[test]
fn the_rubber_band_has_its_published_values_and_inverse() {
    // "Analysis of Apple's rubber band scrolling" (2013): d = 960, c = 0.55.
    for (x, b) in [
        (5.0, 2.74),
        (10.0, 5.47),
        (100.0, 52.02),
        (400.0, 178.98),
        (960.0, 340.65),
    ] {
        assert!(
            (rubber_band(x, RUBBER_BAND, 960.0) - b).abs() < 0.005,
            "{x}"
        );
    }
    for x in [-300.0, -1.0, 0.0, 0.5, 40.0, 2000.0] {
        let b = rubber_band(x, RUBBER_BAND, 160.0);
        assert!(b.abs() < 160.0 && b.abs() <= x.abs());
        assert!((rubber_band_inverse(b, RUBBER_BAND, 160.0) - x).abs() < 1e-9 * (1.0 + x.abs()));
    }
    // Slope c at the edge: a small pull moves the content 0.55 of it.
    assert!((rubber_band(1e-6, RUBBER_BAND, 160.0) / 1e-6 - RUBBER_BAND).abs() < 1e-6);
}

#[test]
fn a_throw_into_a_bound_crosses_it_with_its_velocity() {
    let (x0, v0, c, bound) = (0.0, 3000.0, 2.0, 400.0);
    let (omega, zeta) = (12.0, 1.0);
    let (_, crossing) = throw_into_bound(x0, v0, c, bound, omega, zeta, 0.0);
    let before = throw_into_bound(x0, v0, c, bound, omega, zeta, crossing - 1e-9).0;
    let after = throw_into_bound(x0, v0, c, bound, omega, zeta, crossing + 1e-9).0;
    assert!((before.0 - bound).abs() < 1e-5 && (after.0 - bound).abs() < 1e-5);
    assert!((before.1 - after.1).abs() < 1e-4);
    assert!((before.1 - (v0 - c * (bound - x0))).abs() < 1e-4); // v = v0 − c·(x − x0)
    // Then the spring brings it back to the bound.
    let late = throw_into_bound(x0, v0, c, bound, omega, zeta, crossing + 5.0).0;
    assert!((late.0 - bound).abs() < 1e-6 && late.1.abs() < 1e-5);
}

#[test]
fn the_two_pole_snap_keeps_the_velocity_and_is_the_throw_on_its_resting_point() {
    let (x0, v0, c, p) = (0.0, 1000.0, 2.0, 12.0);
    let rest = throw_rest(x0, v0, c);
    for t in [0.0, 0.2, 1.0, 4.0] {
        let (x, v) = two_pole(x0, v0, rest, c, p, t);
        let (tx, tv) = throw(x0, v0, c, t);
        assert!((x - tx).abs() < 1e-9 && (v - tv).abs() < 1e-9, "{t}");
    }
    for s in [rest - 37.0, rest + 12.0] {
        let (x, v) = two_pole(x0, v0, s, c, p, 0.0);
        assert!((x - x0).abs() < 1e-9 && (v - v0).abs() < 1e-9);
        let (x, _) = two_pole(x0, v0, s, c, p, 30.0);
        assert!((x - s).abs() < 1e-9);
        // x'' = −(c + p)·x' − c·p·(x − s).
        let t = 0.3;
        let a = derivative(|t| two_pole(x0, v0, s, c, p, t).1, t);
        let (x, v) = two_pole(x0, v0, s, c, p, t);
        assert!((a + (c + p) * v + c * p * (x - s)).abs() < 1e-3);
    }
    assert_eq!(nearest_index(119.0, 40.0, 0.0), 3);
    assert_eq!(nearest_index(-61.0, 40.0, 0.0), -2);
}

#[test]
fn a_trail_follows_its_head() {
    let start: Vec<f64> = (0..5).map(|k| k as f64 * 10.0).collect();
    let frames = trail(&start, 100.0, 10.0, 15.0, 1.0, 1.0 / 60.0, 600);
    let last = frames.last().unwrap();
    for (k, x) in last.iter().enumerate() {
        assert!((x - (100.0 + 10.0 * k as f64)).abs() < 1e-6, "{k}: {x}");
    }
    // The head moves first; the tail starts a frame later per link.
    assert!(frames[0][0] > start[0] && frames[0][4] == start[4]);
}
