/* Minimal C firmwares for the flash the C API adds (scripts/capi-size): each does what the
 * configuration of the same name in examples/size.rs does, through the C API, so that the
 * difference of the two over their own empty firmwares is the C layer's cost.
 *
 *   (none)                   boots and exits (startup.c, semihosting exit)
 *   SIZE_VALUE               value_f32_exact_runtime: an f32 value tuned by the exact map
 *                            at run time, retargeted, stepped 60 times, read
 *   SIZE_BATCH               batch16_f32 with SIZE_VALUE's run-time tuning: 16 values in
 *                            a batch, retargeted, stepped 60 times, one read
 *   SIZE_KNOB                knob_f32: an f32 knob with 16 detents between endstops, set
 *                            up at run time, updated 1000 times
 *
 * Inputs go through volatile variables (the C counterpart of black_box). The Rust twins
 * are the c_twin_* configurations of examples/size.rs. */
#include <stdint.h>

#include "stiffspring.h"

static volatile float sink_f;
static volatile int sink_i;
static volatile double in_frequency = 2.0, in_zeta = 0.7, in_dt = 1.0 / 60.0;
static volatile float in_zero = 0.0f, in_target = 100.0f;
static volatile int in_frames = 60;

#if defined(SIZE_VALUE) || defined(SIZE_BATCH)
static StiffspringTuning tuning;

static int make_tuning(void) {
    return stiffspring_tuning_from_frequency(&tuning, sizeof tuning, in_frequency, in_zeta, in_dt) ==
           STIFFSPRING_ERROR_OK;
}
#endif

#ifdef SIZE_VALUE
static void value(void) {
    static StiffspringValueF32 v;
    if (!make_tuning()) return;
    if (stiffspring_value_f32_init(&v, sizeof v, &tuning, in_zero) != STIFFSPRING_ERROR_OK) return;
    stiffspring_value_f32_set_target(&v, in_target);
    for (int i = 0; i < in_frames; i++) {
        StiffspringMotion m;
        stiffspring_value_f32_step(&v, &m);
        sink_i = m;
    }
    float x;
    stiffspring_value_f32_position(&v, &x);
    sink_f = x;
}
#endif

#ifdef SIZE_BATCH
static void batch(void) {
    static StiffspringBatchF32 b;
    uint32_t last = 0;
    if (!make_tuning() || stiffspring_batch_f32_init(&b, sizeof b, &tuning) != STIFFSPRING_ERROR_OK) return;
    for (int i = 0; i < 16; i++) {
        if (stiffspring_batch_f32_push(&b, in_zero, &last) == STIFFSPRING_ERROR_OK)
            stiffspring_batch_f32_set_target(&b, last, 10.0f * (float)i);
    }
    for (int i = 0; i < in_frames; i++) {
        StiffspringBatchMotion m;
        stiffspring_batch_f32_step(&b, &m);
        sink_i = (int)m.moving;
    }
    float x;
    stiffspring_batch_f32_position(&b, last, &x);
    sink_f = x;
}
#endif

#ifdef SIZE_KNOB
static volatile double in_rate = 1000.0, in_inertia = 1e-5, in_limit = 0.05, in_max = 3.0, in_k = 0.05;
static volatile uint32_t in_counts = 16384, in_detents = 16;
static volatile int in_periods = 1000;

static void knob(void) {
    static StiffspringKnobConfig c;
    static StiffspringKnobF32 k;
    stiffspring_knob_config_init(&c, sizeof c, in_rate, in_inertia, in_limit, in_counts);
    stiffspring_knob_config_endstops(&c, 0.0, in_max);
    stiffspring_knob_config_detent_count(&c, in_detents);
    stiffspring_knob_config_detent_stiffness(&c, in_k);
    if (stiffspring_knob_f32_init(&k, sizeof k, &c, in_zero) != STIFFSPRING_ERROR_OK) return;
    for (int n = 0; n < in_periods; n++) {
        StiffspringKnobOutputF32 out;
        stiffspring_knob_f32_update(&k, (float)n * 1e-3f, &out);
        sink_f = out.torque;
    }
}
#endif

int main(void) {
#ifdef SIZE_VALUE
    value();
#endif
#ifdef SIZE_BATCH
    batch();
#endif
#ifdef SIZE_KNOB
    knob();
#endif
    return 0;
}
