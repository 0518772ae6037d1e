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
 *   SIZE_Q16                 with any of the above: the same in Q16.16 (the _q16_
 *                            functions, int32_t numbers)
 *
 * Inputs go through volatile variables (the C counterpart of black_box). The Rust twins
 * are the c_twin_* configurations of examples/size.rs (c_twin_*_q16 for SIZE_Q16). */
#include <stdint.h>

#include "stiffspring.h"

/* The backend: its functions' infix, its number type, a number from an integer (as the
 * Rust twin's `Input::input`), and the knob's encoder angle of period n. */
#ifdef SIZE_Q16
#define API(object, name) stiffspring_##object##_q16_##name
#define STORAGE(object) Stiffspring##object##Q16
typedef int32_t number;
#define NUMBER(x) ((int32_t)(x) * 65536)
#define ANGLE(n) ((int32_t)(n) * 66)
#else
#define API(object, name) stiffspring_##object##_f32_##name
#define STORAGE(object) Stiffspring##object##F32
typedef float number;
#define NUMBER(x) ((float)(x))
#define ANGLE(n) ((float)(n) * 1e-3f)
#endif

static volatile number sink_x;
static volatile int sink_i;
static volatile double in_frequency = 2.0, in_zeta = 0.7, in_dt = 1.0 / 60.0;
static volatile number in_zero = NUMBER(0), in_target = NUMBER(100);
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
    static STORAGE(Value) v;
    if (!make_tuning()) return;
    if (API(value, init)(&v, sizeof v, &tuning, in_zero) != STIFFSPRING_ERROR_OK) return;
    API(value, set_target)(&v, in_target);
    for (int i = 0; i < in_frames; i++) {
        StiffspringMotion m;
        API(value, step)(&v, &m);
        sink_i = m;
    }
    number x;
    API(value, position)(&v, &x);
    sink_x = x;
}
#endif

#ifdef SIZE_BATCH
static void batch(void) {
    static STORAGE(Batch) b;
    uint32_t last = 0;
    if (!make_tuning() || API(batch, init)(&b, sizeof b, &tuning) != STIFFSPRING_ERROR_OK) return;
    for (int i = 0; i < 16; i++) {
        if (API(batch, push)(&b, in_zero, &last) == STIFFSPRING_ERROR_OK)
            API(batch, set_target)(&b, last, NUMBER(10 * i));
    }
    for (int i = 0; i < in_frames; i++) {
        StiffspringBatchMotion m;
        API(batch, step)(&b, &m);
        sink_i = (int)m.moving;
    }
    number x;
    API(batch, position)(&b, last, &x);
    sink_x = x;
}
#endif

#ifdef SIZE_KNOB
static volatile double in_rate = 1000.0, in_inertia = 1e-5, in_limit = 0.05, in_max = 3.0, in_k = 0.05;
static volatile uint32_t in_counts = 16384, in_detents = 16;
static volatile int in_periods = 1000;

static void knob(void) {
    static StiffspringKnobConfig c;
    static STORAGE(Knob) k;
    stiffspring_knob_config_init(&c, sizeof c, in_rate, in_inertia, in_limit, in_counts);
    stiffspring_knob_config_endstops(&c, 0.0, in_max);
    stiffspring_knob_config_detent_count(&c, in_detents);
    stiffspring_knob_config_detent_stiffness(&c, in_k);
    if (API(knob, init)(&k, sizeof k, &c, in_zero) != STIFFSPRING_ERROR_OK) return;
    for (int n = 0; n < in_periods; n++) {
#ifdef SIZE_Q16
        StiffspringKnobOutputQ16 out;
#else
        StiffspringKnobOutputF32 out;
#endif
        API(knob, update)(&k, ANGLE(n), &out);
        sink_x = out.torque;
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
