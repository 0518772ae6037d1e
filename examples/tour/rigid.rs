//! The article's stiffest spring, C_k = C_d = 1: at rest in one step, stopped in two.

use lab::table::print;
use stiffspring::{I16F16, I32F32, Scalar, SpringValue, Tuning};

fn trace<S: Scalar>() -> Vec<String> {
    // Offset 3, thrown away from the target at 40 units/s, dt = 0.01: the rigid spring
    // ignores both and cancels the offset in one step.
    let mut v = SpringValue::<S, 1>::new([S::from_f64(3.0)], Tuning::rigid(), 0.01).expect("valid");
    v.set_target([S::ZERO]).expect("in range");
    v.fling([S::from_f64(40.0)]).expect("in range");
    let mut cells = vec![S::NAME.to_string()];
    for _ in 0..3 {
        cells.push(format!(
            "{:+.3} / {:+.3}",
            v.position()[0].to_f64(),
            v.step_velocity()[0].to_f64()
        ));
        v.step();
    }
    cells.push(if v.is_at_rest() {
        "yes".into()
    } else {
        "no".into()
    });
    cells
}

pub fn rest_in_two_steps() {
    println!("The rigid spring (C_k = C_d = 1) from x = 3 moving away at u = 0.4 per step");
    print(
        &[
            "backend",
            "step 0: x / u",
            "step 1: x / u",
            "step 2: x / u",
            "at rest",
        ],
        &[
            trace::<f64>(),
            trace::<f32>(),
            trace::<I32F32>(),
            trace::<I16F16>(),
        ],
    );
    println!(
        "(the position is on target after one step, for any offset, velocity, mass and dt, \
         but still moving at −x₀ per step: full rest takes two — the erratum in the article)\n"
    );
}
