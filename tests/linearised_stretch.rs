//! The `Linearised` length kernel under a standing stretch.
//!
//! A 6×6 mesh with diagonals, rim pinned, every rest length the distance / 1.5, uniform
//! `C_k`, `C_d`: a drum skin held at 50 % stretch. The linearised kernel hardens with
//! stretch `s` (axial stiffness `C_k·(3s² − 1)/2`, axial damping `C_d·s²`; see
//! `Linearised`), so at the exact kernel's network limit it is far past its own; the
//! scene applies the factors when a spring is added.
//!
//! `cargo test --release --test linearised_stretch -- --nocapture` prints the offsets.

use lab::rng::Rng;
use stiffspring::length::{Exact, LengthKernel, Linearised};
use stiffspring::scene::{LimitPolicy, Scene, SceneConfig, Stepper, network_limit};
use stiffspring::{Error, I16F16, Scalar, Tuning};

const W: usize = 6;
const P: usize = W * W;
const K: usize = 2 * W * (W - 1) + 2 * (W - 1) * (W - 1);

/// The largest distance of a particle from its lattice place over `steps` (∞ when not
/// finite), or the error the scene's set-up returned.
fn drum<S: Scalar, L: LengthKernel<S>>(
    stepper: Stepper,
    (ck, cd): (f64, f64),
    kick: f64,
    stretch: f64,
    steps: usize,
    policy: LimitPolicy,
) -> Result<f64, Error> {
    let dt = 1.0 / 60.0;
    let config = SceneConfig::new(dt)?
        .stepper(stepper)
        .limit_policy(policy)
        .no_sleep();
    let mut scene = Scene::<S, 2, P, K, L>::new(config);
    let mut ids = Vec::new();
    let mut home = Vec::new();
    for r in 0..W {
        for col in 0..W {
            let p = [col as f64, r as f64];
            let rim = r == 0 || col == 0 || r == W - 1 || col == W - 1;
            let at = [S::from_f64(p[0]), S::from_f64(p[1])];
            ids.push(if rim {
                scene.add_pinned(at)?
            } else {
                scene.add_particle(at, S::ONE)?
            });
            home.push(p);
        }
    }
    let tuning = Tuning::from_coefficients(ck, cd, dt)?;
    let mut add = |a: usize, b: usize| -> Result<(), Error> {
        let d = (home[b][0] - home[a][0]).hypot(home[b][1] - home[a][1]);
        scene.add_spring(ids[a], ids[b], S::from_f64(d / stretch), &tuning)?;
        Ok(())
    };
    for r in 0..W {
        for col in 0..W {
            let i = r * W + col;
            if col + 1 < W {
                add(i, i + 1)?;
            }
            if r + 1 < W {
                add(i, i + W)?;
            }
        }
    }
    for r in 0..W - 1 {
        for col in 0..W - 1 {
            let i = r * W + col;
            add(i, i + W + 1)?;
            add(i + 1, i + W)?;
        }
    }
    // A kick off the symmetric equilibrium.
    let mut rng = Rng::seeded(5);
    for &id in &ids {
        if !scene.is_pinned(id)? {
            let v = [rng.sym(kick), rng.sym(kick)];
            scene.set_velocity(id, [S::from_f64(v[0]), S::from_f64(v[1])])?;
        }
    }
    let mut worst = 0.0f64;
    for _ in 0..steps {
        let _ = scene.step();
        for (i, &id) in ids.iter().enumerate() {
            let p = scene.position(id)?;
            let off = (p[0].to_f64() - home[i][0]).hypot(p[1].to_f64() - home[i][1]);
            worst = worst.max(if off.is_finite() { off } else { f64::INFINITY });
        }
    }
    Ok(worst)
}

#[test]
fn a_stretched_linearised_mesh_at_the_exact_limit_is_refused_and_clamped_to_a_stable_one() {
    for stepper in [Stepper::GaussSeidel, Stepper::Jacobi] {
        let limit = network_limit(8, stepper);
        let at_limit = (limit, limit);
        let reject = LimitPolicy::Reject;
        // At the limit of the exact kernel: refused for the linearised one...
        assert!(matches!(
            drum::<f64, Linearised>(stepper, at_limit, 0.5, 1.5, 1, reject),
            Err(Error::ExceedsNetworkLimit { .. })
        ));
        // ...accepted for the exact one, and for the linearised one without stretch.
        assert!(drum::<f64, Exact>(stepper, at_limit, 0.5, 1.5, 1, reject).is_ok());
        assert!(drum::<f64, Linearised>(stepper, at_limit, 0.5, 1.0, 1, reject).is_ok());
        // Within the stiffened limit (C_k·2.875 and C_d·2.25 at s = 1.5): accepted.
        let stiffened = (limit / 2.875, limit / 2.25);
        assert!(drum::<f64, Linearised>(stepper, stiffened, 0.5, 1.5, 1, reject).is_ok());
    }
    // Clamped, every combination stays near the lattice.
    for stepper in [Stepper::GaussSeidel, Stepper::Jacobi] {
        let limit = network_limit(8, stepper);
        for cd_fraction in [0.0, 0.1, 0.5, 1.0] {
            for kick in [0.5, 5.0] {
                let c = (limit, limit * cd_fraction);
                let clamp = LimitPolicy::Clamp;
                for (name, worst) in [
                    (
                        "f64",
                        drum::<f64, Linearised>(stepper, c, kick, 1.5, 6000, clamp),
                    ),
                    (
                        "f32",
                        drum::<f32, Linearised>(stepper, c, kick, 1.5, 6000, clamp),
                    ),
                    (
                        "I16F16",
                        drum::<I16F16, Linearised>(stepper, c, kick, 1.5, 6000, clamp),
                    ),
                ] {
                    let worst = worst.unwrap_or(f64::INFINITY);
                    println!("{stepper:?} C_d/C_k {cd_fraction} kick {kick} {name}: {worst:.3e}");
                    assert!(
                        worst < 1.0,
                        "{stepper:?} {cd_fraction} {kick} {name}: {worst:e}"
                    );
                }
            }
        }
    }
}
