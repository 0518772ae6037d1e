//! The golden values of the `knob_menu` scene (`firmware/src/scenes/knob_menu.rs`), which
//! the `knob_menu` starter checks itself against on the host and on the microcontrollers:
//! the item (the knob's detent) and the menu's offset after each frame.
//!
//! They come from the scene's rotor and hand (`f64`) closed around the library's `f64`
//! knob (which follows an independent `f64` model of its torque law to 2.2e−16 of the
//! limit, `tests/knob_golden.rs`), and from the menu computed here without the library:
//! the analytic solution of SwiftUI's `.snappy` spring (`lab::reference::analytic`),
//! restarted with its position and velocity whenever the item changes, toward
//! `item · ROW`. The library's `f64` `Scroll` must follow it within the rest threshold,
//! and the starter's `f32` run within `OFFSET_TOLERANCE`, with the same item on every
//! frame.
//!
//! This test recomputes them and fails when `firmware/src/golden/knob_menu.rs` is missing
//! or stale. To regenerate:
//!
//! ```text
//! STIFFSPRING_BLESS=1 cargo test --release --test knob_menu_golden
//! ```

use firmware::golden::knob_menu as golden;
use firmware::scenes::knob_menu::{self as scene, CONFIG, FRAME, FRAMES, ITEMS, PERIODS, ROW};
use lab::golden::{check_or_bless, f64_table};
use lab::reference;
use std::path::Path;
use stiffspring::knob::{Endstop, KnobDesign};
use stiffspring::{Bounds, Friction, Knob, Scalar, Scroll, Snap, knob, presets};

/// SwiftUI's `.snappy`: `Spring(duration: 0.5, bounce: 0.15)`, the mass-1 spring of
/// angular frequency 2π/duration and damping ratio 1 − bounce (Apple's `Spring`
/// documentation), the `Scroll`'s default step spring.
const OMEGA: f64 = std::f64::consts::TAU / 0.5;
const ZETA: f64 = 1.0 - 0.15;

/// One run of the scene on backend `S`, as the starter plays it.
#[derive(Default)]
struct Run {
    /// The item after each frame.
    items: Vec<i32>,
    /// The menu's offset after each frame, px.
    offsets: Vec<f64>,
    /// The menu's resting point after each frame, px.
    resting: Vec<f64>,
    /// The period (from the start) of every detent change.
    changes: Vec<usize>,
    /// The endstops the knob hit, in order.
    hits: Vec<Endstop>,
}

/// The starter's loop on backend `S`: the knob every period, stepping the menu on each
/// detent click, and the menu's spring once a frame.
fn play<S: Scalar>(design: &KnobDesign<S>) -> Run {
    let mut knob = Knob::from_design(design, S::ZERO).unwrap();
    let bounds = Bounds::new(S::ZERO, S::from_f64(f64::from(ITEMS - 1) * f64::from(ROW))).unwrap();
    let mut menu = Scroll::<S>::new(S::ZERO, bounds, &Friction::IOS_NORMAL, FRAME)
        .unwrap()
        .with_snap(Snap::spacing(S::from_f64(ROW.into()), S::ZERO).unwrap());
    let mut rotor = scene::Rotor::new();
    let mut run = Run::default();
    for frame in 0..FRAMES {
        for p in 0..PERIODS {
            let out = knob.update(S::from_f64(rotor.encoder()));
            assert_eq!(out.events.sensor, None, "frame {frame}");
            if out.events.detent_step != 0 {
                menu.step_by(out.events.detent_step.into());
                run.changes.push(frame * PERIODS + p);
            }
            run.hits.extend(out.events.endstop_hit);
            rotor.turn(out.torque.to_f64());
        }
        let _ = menu.step();
        run.items.push(knob.detent());
        run.offsets.push(menu.position().to_f64());
        run.resting.push(menu.resting_point().to_f64());
    }
    run
}

/// The menu's offset after each frame from the analytic spring: toward `item · ROW`,
/// restarted from its position and velocity on each frame whose item changed.
fn analytic_menu(items: &[i32]) -> Vec<f64> {
    let (mut target, mut anchor, mut x0, mut v0) = (0.0f64, 0usize, 0.0f64, 0.0f64);
    let mut last = 0;
    let mut offsets = Vec::with_capacity(items.len());
    for (frame, &item) in items.iter().enumerate() {
        // The item read on this frame retargets the spring before its step.
        if item != last {
            let (x, v) = reference::analytic(x0, v0, OMEGA, ZETA, (frame - anchor) as f64 * FRAME);
            let to = f64::from(item) * f64::from(ROW);
            (anchor, x0, v0, target) = (frame, x + target - to, v, to);
            last = item;
        }
        let (x, _) = reference::analytic(x0, v0, OMEGA, ZETA, (frame + 1 - anchor) as f64 * FRAME);
        offsets.push(target + x);
    }
    offsets
}

#[test]
fn knob_menu_golden_values_are_current() {
    assert_eq!(presets::swiftui::SNAPPY.damping_ratio(), ZETA);
    assert!((presets::swiftui::SNAPPY.frequency() * std::f64::consts::TAU - OMEGA).abs() < 1e-12);
    const F64: KnobDesign<f64> = knob!(CONFIG, f64);
    const F32: KnobDesign<f32> = knob!(CONFIG, f32);
    let reference = play(&F64);
    let offsets = analytic_menu(&reference.items);
    let items: Vec<f64> = reference.items.iter().map(|&i| f64::from(i)).collect();

    // The scene does what it says: every item up, the upper stop, three down, the lower
    // stop, and at rest on the first item at the end.
    let clicks: Vec<(usize, i32)> = reference
        .changes
        .iter()
        .map(|&p| (p / PERIODS, reference.items[p / PERIODS]))
        .collect();
    println!("(frame, item) of every click: {clicks:?}");
    println!("endstop hits: {:?}", reference.hits);
    assert_eq!(reference.items.iter().max(), Some(&(ITEMS as i32 - 1)));
    assert!(reference.hits.contains(&Endstop::Max) && reference.hits.contains(&Endstop::Min));
    assert_eq!(*reference.items.last().unwrap(), 0);
    // The menu never leaves the item the knob is on (the knob's endstops are the list's
    // ends), and rests on it.
    for (k, (&item, &to)) in reference.items.iter().zip(&reference.resting).enumerate() {
        assert_eq!(to, f64::from(item) * f64::from(ROW), "frame {k}");
    }
    let end = f64::from(ITEMS - 1) * f64::from(ROW);
    let past = offsets
        .iter()
        .map(|&x| (-x).max(x - end))
        .fold(f64::MIN, f64::max);
    // `.snappy` overshoots (ζ = 0.85) the end it arrives at with the velocity of the
    // clicks before: by less than half a pixel, so that drawn (rounded) the list never
    // passes its first or last item.
    println!("the menu's farthest past an end: {past:.3} px (the spring's overshoot)");
    assert!(past < 0.5, "{past}");

    // No detent change falls on a frame's first or last period: a change one period
    // earlier or later in another backend stays in the same frame, so the items and the
    // steps of the menu must agree frame by frame.
    for &p in &reference.changes {
        assert!(
            !matches!(p % PERIODS, 0 | 19),
            "a detent change on period {p} (frame edge)"
        );
    }

    // The library's f64 menu follows the analytic spring within its rest threshold.
    let worst_f64 = worst(&reference.offsets, &offsets);
    println!("the f64 Scroll against the analytic spring: worst {worst_f64:.1e} px");
    assert!(worst_f64 <= 0.75e-3, "{worst_f64}");

    // The starter's f32 run, as on the host and the microcontrollers.
    let run = play(&F32);
    assert_eq!(run.items, reference.items, "the f32 knob's items");
    let worst_f32 = worst(&run.offsets, &offsets);
    let rounding = worst(&run.offsets, &reference.offsets);
    assert_eq!(
        run.changes.len(),
        reference.changes.len(),
        "the f32 knob's clicks"
    );
    let shift = run
        .changes
        .iter()
        .zip(&reference.changes)
        .map(|(a, b)| a.abs_diff(*b))
        .max()
        .unwrap_or(0);
    // Within the margin the frame edges leave (above).
    assert!(shift <= 1, "{shift}");
    println!(
        "the f32 run: same items on all {FRAMES} frames, detent clicks within {shift} periods \
         of the f64 run's, worst offset {worst_f32:.1e} px (tolerance {:e}; {rounding:.1e} px from the f64 Scroll)",
        scene::OFFSET_TOLERANCE
    );
    assert!(worst_f32 <= scene::OFFSET_TOLERANCE, "{worst_f32}");

    let source = format!(
        "//! Golden values of the `knob_menu` scene (`firmware/src/scenes/knob_menu.rs`):\n\
         //! the item (the knob's detent) and the menu's offset (px) after each frame.\n\
         //!\n\
         //! @generated by `STIFFSPRING_BLESS=1 cargo test --release --test knob_menu_golden`\n\
         //! from the scene's rotor on the library's f64 knob and the analytic solution of\n\
         //! the menu's spring (tests/knob_menu_golden.rs); do not edit.\n\n{}",
        f64_table(
            "RUN",
            "The item, then the menu offset; sample `k` is after frame `k`.",
            &[
                ("item".to_string(), items.as_slice()),
                ("offset".to_string(), offsets.as_slice()),
            ],
        )
    );
    check_or_bless(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("firmware/src/golden/knob_menu.rs"),
        &source,
        &[items, offsets],
        &golden::RUN,
        1e-12,
        "regenerate with `STIFFSPRING_BLESS=1 cargo test --release --test knob_menu_golden`",
    );
}

/// The largest `|a − b|`.
fn worst(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}
