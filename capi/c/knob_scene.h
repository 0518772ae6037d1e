/* The encoder sweep of the Rust firmware check `examples/check_knob.rs`, played through
 * the C API's f32 knob: the torques must equal the Rust Knob<f32>'s bit for bit
 * (knob_rust_f32_torque_bits, computed on the host by the generator of goldens.h), and lie
 * within check_knob's tolerance (1e-4 of the limit) of the golden f64 torques, with the
 * same detents except in the period next to a change of the golden index.
 * Shared by the host test (host_test.c) and the Cortex-M4F example (knob_m4f.c). */
#ifndef STIFFSPRING_KNOB_SCENE_H
#define STIFFSPRING_KNOB_SCENE_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "goldens.h"
#include "stiffspring.h"

#define KNOB_TOLERANCE 1e-4

/* The scene's configuration (firmware/src/scenes/knob.rs), through the C builder. */
static StiffspringError knob_scene_config(StiffspringKnobConfig *config) {
    StiffspringError e = stiffspring_knob_config_init(config, sizeof *config, KNOB_RATE, KNOB_INERTIA,
                                                      KNOB_TORQUE_LIMIT, KNOB_COUNTS_PER_TURN);
    if (e == STIFFSPRING_ERROR_OK) e = stiffspring_knob_config_latency(config, STIFFSPRING_LATENCY_ONE_STEP);
    if (e == STIFFSPRING_ERROR_OK) e = stiffspring_knob_config_endstops(config, 0.0, KNOB_MAX);
    if (e == STIFFSPRING_ERROR_OK) e = stiffspring_knob_config_endstop_stiffness(config, KNOB_ENDSTOP_STIFFNESS);
    if (e == STIFFSPRING_ERROR_OK) e = stiffspring_knob_config_detent_count(config, KNOB_DETENTS);
    if (e == STIFFSPRING_ERROR_OK) e = stiffspring_knob_config_detent_stiffness(config, KNOB_DETENT_STIFFNESS);
    if (e == STIFFSPRING_ERROR_OK) e = stiffspring_knob_config_hysteresis(config, KNOB_HYSTERESIS);
    return e;
}

/* The knob's sweep; returns the failures. */
__attribute__((unused)) static int knob_sweep_f32(void) {
    StiffspringKnobConfig config;
    StiffspringKnobF32 knob;
    StiffspringError e = knob_scene_config(&config);
    if (e == STIFFSPRING_ERROR_OK) e = stiffspring_knob_f32_init(&knob, sizeof knob, &config, (float)knob_angles[0]);
    if (e != STIFFSPRING_ERROR_OK) {
        printf("knob: set-up refused: %s\n", stiffspring_error_name(e));
        return 1;
    }
    int bit_differences = 0, out_of_tolerance = 0, detent_mismatches = 0, detent_changes = 0, compared = 0;
    double worst = 0.0;
    for (int n = 0; n < KNOB_SWEEP_STEPS; n++) {
        StiffspringKnobOutputF32 out;
        if (stiffspring_knob_f32_update(&knob, (float)knob_angles[n], &out) != STIFFSPRING_ERROR_OK) return 1;
        uint32_t bits;
        memcpy(&bits, &out.torque, sizeof bits);
        if (bits != knob_rust_f32_torque_bits[n]) {
            if (bit_differences < 3) printf("knob: period %d: torque %.9g differs from the Rust knob's\n", n, out.torque);
            bit_differences++;
        }
        detent_changes += out.events.detent_step != 0;
        int near_change = 0;
        for (int k = n > 0 ? n - 1 : 0; k <= n + 1 && k < KNOB_SWEEP_STEPS; k++) {
            if (k > 0 && knob_golden_detents[k] != knob_golden_detents[k - 1]) near_change = 1;
        }
        if (out.detent != knob_golden_detents[n]) {
            detent_mismatches += !near_change;
            continue;
        }
        if (near_change) continue;
        double error = fabs((double)out.torque - knob_golden_torques[n]);
        compared++;
        if (error > worst) worst = error;
        if (!(error <= KNOB_TOLERANCE)) out_of_tolerance++;
    }
    printf("knob sweep (f32): %d periods, %d torques differ from the Rust knob's bits; %d compared with the "
           "golden f64 torques, worst %.3g of the limit (tolerance %.0e), %d out; %d detent mismatches, %d detent changes\n",
           KNOB_SWEEP_STEPS, bit_differences, compared, worst, KNOB_TOLERANCE, out_of_tolerance, detent_mismatches,
           detent_changes);
    stiffspring_knob_f32_drop(&knob);
    return bit_differences + out_of_tolerance + detent_mismatches + (detent_changes == 0);
}

#endif
