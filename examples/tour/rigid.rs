//! The article's stiffest spring, C_k = C_d = 1: on target in one step.

use lab::table::print;
use stiffspring::{I16F16, I32F32, Scalar, SpringValue, Tuning};

/// Position, velocity and what `step` reported, before and after each of three steps.
fn trace<S: Scalar>() -> Vec<String> {
    // Offset 3, thrown away from the target at 40 units/s, dt = 0.01: the rigid spring
    // ignores both and cancels the offset in one step.
    let rigid = Tuning::rigid(0.01).expect("valid");
    let mut v = SpringValue::<S, 1>::new([S::from_f64(3.0)], &rigid).expect("valid");
    v.set_target([S::ZERO]);
    v.try_fling([S::from_f64(40.0)]).expect("in range");
    let mut cells = vec![S::NAME.to_string()];
    let state = |v: &SpringValue<S, 1>| {
        format!(
            "{:+.3} / {:+.1}",
            v.position()[0].to_f64(),
            v.velocity()[0].to_f64()
        )
    };
    cells.push(state(&v));
    for _ in 0..2 {
        let motion = v.step();
        cells.push(format!("{} ({motion:?})", state(&v)));
    }
    cells
}

pub fn rest_in_two_steps() {
    println!(
        "The rigid spring (C_k = C_d = 1) from x = 3, flung away from its target at 40 units/s"
    );
    print(
        &[
            "backend",
            "start: x / v",
            "step 1: x / v (step)",
            "step 2: x / v (step)",
        ],
        &[
            trace::<f64>(),
            trace::<f32>(),
            trace::<I32F32>(),
            trace::<I16F16>(),
        ],
    );
    println!(
        "(on target after one step, for any offset, velocity, mass and dt; in the article's \
         recurrence the body still moves at −x₀ per step after it and stops in the second \
         (its erratum), but a value inside its rest band snaps, so it settles at once)\n"
    );
}
