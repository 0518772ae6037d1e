//! The scene's user-facing contract: ids that cannot alias, drag handles, events, set-up
//! that fails without side effects, the time step checked, and the exact release.

use stiffspring::scene::{LimitPolicy, Scene, SceneConfig, SleepThreshold};
use stiffspring::{Error, Parameter, Scalar, Tuning};

type Rope = Scene<f32, 2, 8, 8>;

fn config(dt: f64) -> SceneConfig<f32, 2> {
    SceneConfig::new(dt).expect("a positive dt")
}

#[test]
fn a_removed_particle_id_never_names_its_successor() -> Result<(), Error> {
    let mut s = Rope::new(config(0.01));
    let a = s.add_particle([0.0, 0.0], 1.0)?;
    let b = s.add_particle([1.0, 0.0], 1.0)?;
    let spring = s.add_spring(a, b, 1.0, &Tuning::rigid(0.01)?)?.spring;
    s.remove_particle(b)?;
    let c = s.add_particle([7.0, 7.0], 2.0)?;
    assert_eq!(b.slot(), c.slot(), "the slot is reused");
    let stale = Error::Stale {
        parameter: Parameter::Particle,
    };
    assert_eq!(s.position(b), Err(stale));
    assert_eq!(s.set_position(b, [0.0, 0.0]), Err(stale));
    assert_eq!(s.remove_particle(b), Err(stale));
    assert_eq!(s.position(c)?, [7.0, 7.0]);
    // Removing b removed its spring; that id is stale too, even once the slot is reused.
    let d = s.add_particle([2.0, 0.0], 1.0)?;
    let again = s.add_spring(a, d, 1.0, &Tuning::rigid(0.01)?)?.spring;
    assert_eq!(spring.slot(), again.slot());
    assert_eq!(
        s.rest_length(spring),
        Err(Error::Stale {
            parameter: Parameter::Spring
        })
    );
    assert_eq!(s.ends(again)?, (a, d));
    Ok(())
}

#[test]
fn a_zero_length_drag_handle_pulls_a_particle_to_a_point_and_never_makes_nan() -> Result<(), Error>
{
    let dt = 1.0 / 120.0;
    let mut s = Rope::new(config(dt));
    let p = s.add_particle([1.0, 1.0], 0.1)?;
    let (handle, _) = s.add_anchor([1.0, 1.0], p, 0.0, &Tuning::from_frequency(4.0, 1.0, dt)?)?;
    // Coincident ends: the axis is undefined, the spring is satisfied, nothing moves.
    for _ in 0..10 {
        let _ = s.step();
    }
    assert_eq!(s.position(p)?, [1.0, 1.0]);
    // Drag the handle around a circle and let go: the particle follows and settles on it.
    for i in 0..240 {
        let t = i as f32 / 120.0;
        s.set_position(handle, [1.0 + t.cos(), 1.0 + t.sin()])?;
        let _ = s.step();
        let q = s.position(p)?;
        assert!(q.iter().all(|c| c.is_finite()));
    }
    for _ in 0..600 {
        let _ = s.step();
    }
    let (q, h) = (s.position(p)?, s.position(handle)?);
    assert!(
        (q[0] - h[0]).abs() < 1e-4 && (q[1] - h[1]).abs() < 1e-4,
        "{q:?} {h:?}"
    );
    Ok(())
}

#[test]
fn a_rejected_anchor_adds_nothing_and_wakes_nothing() -> Result<(), Error> {
    let dt = 0.01;
    let sleepy = config(dt).sleep(SleepThreshold::new(0.01, 0.05)?);
    let mut s = Rope::new(sleepy);
    let a = s.add_particle([0.0, 0.0], 1.0)?;
    let b = s.add_particle([1.0, 0.0], 1.0)?;
    s.add_spring(a, b, 1.0, &Tuning::from_coefficients(0.5, 0.5, dt)?)?;
    while s.step().fell_asleep == 0 {}
    let before = (s.particle_count(), s.spring_count());
    // A third spring on `a` at C = 1 exceeds the limit for two springs per particle.
    let err = s.add_anchor([0.0, 1.0], a, 1.0, &Tuning::rigid(dt)?);
    assert!(
        matches!(err, Err(Error::ExceedsNetworkLimit { .. })),
        "{err:?}"
    );
    // Tuned for another rate.
    let err = s.add_anchor(
        [0.0, 1.0],
        a,
        1.0,
        &Tuning::from_coefficients(0.1, 0.1, 0.02)?,
    );
    assert!(
        matches!(err, Err(Error::TimeStepMismatch { .. })),
        "{err:?}"
    );
    assert_eq!((s.particle_count(), s.spring_count()), before);
    assert!(s.is_asleep(a)?);
    let motion = s.step();
    assert_eq!((motion.moving, motion.woke), (0, 0));
    Ok(())
}

#[test]
fn a_full_scene_rejects_an_anchor_before_adding_its_pin() -> Result<(), Error> {
    let mut s = Scene::<f32, 1, 2, 1>::new(SceneConfig::new(0.01)?);
    let a = s.add_particle([0.0], 1.0)?;
    let b = s.add_particle([1.0], 1.0)?;
    assert_eq!(
        s.add_anchor([2.0], a, 1.0, &Tuning::rigid(0.01)?),
        Err(Error::CapacityFull { capacity: 2 })
    );
    s.add_spring(a, b, 1.0, &Tuning::rigid(0.01)?)?;
    s.remove_particle(b)?;
    // Room for the pin now, none for its spring: still nothing added.
    let c = s.add_particle([3.0], 1.0)?;
    s.add_spring(a, c, 1.0, &Tuning::rigid(0.01)?)?;
    s.remove_particle(c)?;
    let d = s.add_particle([3.0], 1.0)?;
    s.add_spring(a, d, 1.0, &Tuning::rigid(0.01)?)?;
    assert_eq!(s.particle_count(), 2);
    Ok(())
}

#[test]
fn the_clamp_policy_reports_what_it_lowered() -> Result<(), Error> {
    let dt = 0.01;
    let mut s = Rope::new(config(dt).limit_policy(LimitPolicy::Clamp));
    let p: Vec<_> = (0..3)
        .map(|i| s.add_particle([i as f32, 0.0], 1.0))
        .collect::<Result<_, _>>()?;
    let rigid = Tuning::rigid(dt)?;
    assert_eq!(s.add_spring(p[0], p[1], 1.0, &rigid)?.clamped, 0);
    let added = s.add_spring(p[1], p[2], 1.0, &rigid)?;
    assert_eq!(added.clamped, 2);
    assert_eq!(s.tuning(added.spring)?.stiffness(), 0.75);
    Ok(())
}

#[test]
fn steps_report_motion_sleep_and_waking() -> Result<(), Error> {
    let dt = 0.01;
    let mut s = Rope::new(config(dt).sleep(SleepThreshold::new(0.01, 0.1)?));
    let pin = s.add_pinned([0.0, 0.0])?;
    let p = s.add_particle([1.5, 0.0], 1.0)?;
    s.add_spring(pin, p, 1.0, &Tuning::from_frequency(2.0, 1.0, dt)?)?;
    let first = s.step();
    assert_eq!((first.moving, first.woke), (1, 0));
    assert_eq!(s.moving().map(|(id, _)| id).collect::<Vec<_>>(), [p]);
    let mut steps = 1;
    loop {
        steps += 1;
        let m = s.step();
        if m.fell_asleep > 0 {
            assert_eq!(m.fell_asleep, 1);
            assert_eq!(s.just_fell_asleep().collect::<Vec<_>>(), [p]);
            break;
        }
        assert!(steps < 1000, "never fell asleep");
    }
    assert!(s.is_asleep(p)?);
    s.set_velocity(p, [0.0, 1.0])?;
    let woke = s.step();
    assert_eq!((woke.woke, woke.moving), (1, 1));
    Ok(())
}

#[test]
fn a_released_spring_follows_its_oscillator_and_a_stepped_one_lags() -> Result<(), Error> {
    // One body on a zero-length spring to a pin, stretched by 1 and released from rest:
    // x(t) = e^{−ζωt}·(cos ω_d t + ζω/ω_d·sin ω_d t).
    let (f, zeta, dt): (f64, f64, f64) = (2.0, 0.2, 1.0 / 60.0);
    let w = 2.0 * core::f64::consts::PI * f;
    let wd = w * (1.0 - zeta * zeta).sqrt();
    let exact = |t: f64| (-zeta * w * t).exp() * ((wd * t).cos() + zeta * w / wd * (wd * t).sin());
    let run = |release: bool| -> Result<f64, Error> {
        let mut s = Scene::<f64, 1, 2, 1>::new(SceneConfig::new(dt)?.no_sleep());
        let pin = s.add_pinned([0.0])?;
        let body = s.add_particle([1.0], 1.0)?;
        s.add_spring(pin, body, 0.0, &Tuning::from_frequency(f, zeta, dt)?)?;
        if release {
            s.release()?;
        }
        let mut worst: f64 = 0.0;
        for n in 1..=120 {
            let _ = s.step();
            worst = worst.max((s.position(body)?[0] - exact(n as f64 * dt)).abs());
        }
        Ok(worst)
    };
    let (released, stepped) = (run(true)?, run(false)?);
    assert!(released < 1e-12, "released: {released}");
    // Half a step behind: about π·f·dt of the amplitude.
    assert!(stepped > 0.05, "stepped from rest: {stepped}");
    Ok(())
}

#[test]
fn code_generic_over_the_backend_needs_no_kernel_bound() {
    fn hang<S: Scalar>() -> Scene<S, 2, 2, 1> {
        Scene::new(SceneConfig::new(0.01).expect("a positive dt"))
    }
    assert_eq!(hang::<f32>().particle_count(), 0);
    assert_eq!(hang::<f64>().spring_count(), 0);
}
