/* The `value` scene of the Rust firmware check `examples/check_value.rs`, played through the
 * C API in f32 and checked against the same golden values (target/capi/goldens.h, written
 * by `cargo run -p stiffspring-c --example c_goldens` from firmware/src/golden/value.rs)
 * with the same tolerances: 4e-5 while moving, plus the rest band's snap bound at rest.
 * Shared by the host test (host_test.c) and the Cortex-M4F example (value_m4f.c). */
#ifndef STIFFSPRING_VALUE_SCENE_H
#define STIFFSPRING_VALUE_SCENE_H

#include <math.h>
#include <stdio.h>

#include "goldens.h"
#include "stiffspring.h"

/* check_value's MOVING tolerance for f32. */
#define VALUE_MOVING_TOLERANCE 4e-5

/* check_value's rest_snap_bound: how far a value that snapped to its target may be from
 * the continuous trajectory, from the default rest threshold (0.75e-3 units, 0.047
 * units/s) and the track's spring. */
static double value_rest_snap_bound(const ValueTrack *track, double stiffness) {
    const double position = 0.75e-3, velocity = 0.047;
    double box_x = position * 0.70710678118654752440;
    double box_u = fmin(box_x * sqrt(stiffness), velocity * VALUE_DT);
    double omega = 2.0 * 3.14159265358979323846 * track->frequency;
    double zeta = track->damping_ratio;
    double omega_d = zeta < 1.0 ? omega * sqrt(1.0 - zeta * zeta) : omega;
    return 2.0 * box_x + 2.0 * box_u / (omega_d * VALUE_DT);
}

/* Plays one track; returns the samples out of tolerance (or 1 for a refused call) and
 * stores the worst deviations while moving and at rest. */
static int value_play_track(const ValueTrack *track, double *worst_moving, double *worst_resting) {
    StiffspringTuning tuning;
    StiffspringValueF32 value;
    double stiffness;
    int failures = 0;
    if (stiffspring_tuning_from_frequency(&tuning, sizeof tuning, track->frequency,
                                          track->damping_ratio, VALUE_DT) != STIFFSPRING_ERROR_OK ||
        stiffspring_tuning_coefficients(&tuning, &stiffness, NULL, NULL) != STIFFSPRING_ERROR_OK ||
        stiffspring_value_f32_init(&value, sizeof value, &tuning, (float)track->start) !=
            STIFFSPRING_ERROR_OK) {
        printf("%s: set-up refused\n", track->name);
        return 1;
    }
    double at_rest = VALUE_MOVING_TOLERANCE + value_rest_snap_bound(track, stiffness);
    for (int frame = 0; frame <= VALUE_FRAMES; frame++) {
        float x;
        bool resting;
        stiffspring_value_f32_position(&value, &x);
        stiffspring_value_f32_is_at_rest(&value, &resting);
        double error = fabs((double)x - track->golden[frame]);
        double tolerance = resting ? at_rest : VALUE_MOVING_TOLERANCE;
        double *worst = resting ? worst_resting : worst_moving;
        if (error > *worst) *worst = error;
        if (!(error <= tolerance)) {
            if (failures < 3) printf("%s: frame %d at %.9g, golden %.9g\n", track->name, frame, x, track->golden[frame]);
            failures++;
        }
        /* The events go through the try_ setters, as in check_value: a saturated retarget
         * or fling fails the check instead of passing silently. */
        for (int e = 0; e < track->events; e++) {
            const ValueEvent *event = &track->event[e];
            if (event->frame != frame) continue;
            StiffspringError r = event->fling
                ? stiffspring_value_f32_try_fling(&value, (float)event->amount)
                : stiffspring_value_f32_try_set_target(&value, (float)event->amount);
            if (r != STIFFSPRING_ERROR_OK) {
                printf("%s: event at frame %d refused: %s\n", track->name, frame, stiffspring_error_name(r));
                failures++;
            }
        }
        if (stiffspring_value_f32_step(&value, NULL) != STIFFSPRING_ERROR_OK) failures++;
    }
    stiffspring_value_f32_drop(&value);
    return failures;
}

/* Plays every track and prints the worst deviations; returns the failures. */
__attribute__((unused)) static int value_scene_f32(void) {
    int failures = 0;
    for (int i = 0; i < VALUE_TRACKS; i++) {
        double moving = 0.0, resting = 0.0;
        int f = value_play_track(&value_tracks[i], &moving, &resting);
        printf("value %s (f32): worst %.3g moving (tolerance %.0e), %.3g at rest; %d out of tolerance\n",
               value_tracks[i].name, moving, VALUE_MOVING_TOLERANCE, resting, f);
        failures += f;
    }
    return failures;
}

#endif
