/* The C API on the host (gcc): its error cases, the value scene of examples/check_value.rs
 * and the knob sweep of examples/check_knob.rs against the same golden values. Built and run by
 * scripts/check-capi; prints "N passed, N failed" and exits non-zero on a failure. */
#include <math.h>
#include <stdalign.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "stiffspring.h"
#include "knob_scene.h"
#include "value_scene.h"

static int passed, failed;

#define CHECK(cond)                                                        \
    do {                                                                   \
        if (cond) {                                                        \
            passed++;                                                      \
        } else {                                                           \
            failed++;                                                      \
            printf("%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
        }                                                                  \
    } while (0)

/* A call that returns the code `expected`. */
#define EXPECT(call, expected) CHECK((call) == (expected))

static void error_names(void) {
    CHECK(strcmp(stiffspring_error_name(STIFFSPRING_ERROR_OK), "STIFFSPRING_ERROR_OK") == 0);
    CHECK(strcmp(stiffspring_error_name(STIFFSPRING_ERROR_DROPPED), "STIFFSPRING_ERROR_DROPPED") == 0);
    CHECK(strcmp(stiffspring_error_name(-1), "STIFFSPRING_ERROR_UNKNOWN") == 0);
    CHECK(strcmp(stiffspring_error_name(1000), "STIFFSPRING_ERROR_UNKNOWN") == 0);
}

static void storage_sizes(void) {
    CHECK(sizeof(StiffspringBatchF32) == STIFFSPRING_BATCH_F32_SIZE);
    CHECK(sizeof(StiffspringKnobF32) == STIFFSPRING_KNOB_F32_SIZE);
    CHECK(sizeof(StiffspringKnobConfig) == STIFFSPRING_KNOB_CONFIG_SIZE);
    CHECK(sizeof(StiffspringValueF32) == STIFFSPRING_VALUE_F32_SIZE);
    CHECK(sizeof(StiffspringValueQ16) == STIFFSPRING_VALUE_Q16_SIZE);
    CHECK(sizeof(StiffspringTuning) == STIFFSPRING_TUNING_SIZE);
    CHECK(alignof(StiffspringValueF32) == STIFFSPRING_STORAGE_ALIGN);
}

static void tuning_errors(void) {
    StiffspringTuning t;
    memset(&t, 0, sizeof t);
    EXPECT(stiffspring_tuning_from_frequency(NULL, sizeof t, 2.0, 0.3, 0.01), STIFFSPRING_ERROR_NULL_POINTER);
    EXPECT(stiffspring_tuning_from_frequency(&t, sizeof t - 1, 2.0, 0.3, 0.01), STIFFSPRING_ERROR_BUFFER_TOO_SMALL);
    EXPECT(stiffspring_tuning_from_frequency(&t, sizeof t, NAN, 0.3, 0.01), STIFFSPRING_ERROR_NOT_FINITE);
    EXPECT(stiffspring_tuning_from_frequency(&t, sizeof t, 2.0, -1.0, 0.01), STIFFSPRING_ERROR_OUT_OF_RANGE);
    EXPECT(stiffspring_tuning_from_coefficients(&t, sizeof t, 0.5, 1.5, 0.01), STIFFSPRING_ERROR_OUT_OF_RANGE);
    EXPECT(stiffspring_tuning_coefficients(&t, NULL, NULL, NULL), STIFFSPRING_ERROR_NOT_INITIALISED);
    EXPECT(stiffspring_tuning_from_coefficients(&t, sizeof t, 0.25, 0.5, 0.01), STIFFSPRING_ERROR_OK);
    double k = 0, dt = 0;
    EXPECT(stiffspring_tuning_coefficients(&t, &k, NULL, &dt), STIFFSPRING_ERROR_OK);
    CHECK(k == 0.25 && dt == 0.01);
}

static void value_errors(void) {
    StiffspringTuning t;
    EXPECT(stiffspring_tuning_from_frequency(&t, sizeof t, 2.0, 0.3, 1.0 / 60.0), STIFFSPRING_ERROR_OK);
    static StiffspringValueF32 v; /* zeroed */
    float x = -1.0f;
    bool resting = false;

    /* Storage that holds nothing yet. */
    EXPECT(stiffspring_value_f32_step(&v, NULL), STIFFSPRING_ERROR_NOT_INITIALISED);
    EXPECT(stiffspring_value_f32_position(&v, &x), STIFFSPRING_ERROR_NOT_INITIALISED);
    /* Bad storage, bad tuning, bad position: nothing is written. */
    EXPECT(stiffspring_value_f32_init(NULL, sizeof v, &t, 0.0f), STIFFSPRING_ERROR_NULL_POINTER);
    EXPECT(stiffspring_value_f32_init(&v, sizeof v - 1, &t, 0.0f), STIFFSPRING_ERROR_BUFFER_TOO_SMALL);
    alignas(8) unsigned char raw[STIFFSPRING_VALUE_F32_SIZE + 8];
    EXPECT(stiffspring_value_f32_init((StiffspringValueF32 *)(raw + 4), STIFFSPRING_VALUE_F32_SIZE, &t, 0.0f),
           STIFFSPRING_ERROR_MISALIGNED);
    EXPECT(stiffspring_value_f32_init((StiffspringValueF32 *)raw, sizeof raw, &t, 0.0f), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_value_f32_init(&v, sizeof v, NULL, 0.0f), STIFFSPRING_ERROR_NULL_POINTER);
    StiffspringTuning untuned = {0};
    EXPECT(stiffspring_value_f32_init(&v, sizeof v, &untuned, 0.0f), STIFFSPRING_ERROR_NOT_INITIALISED);
    EXPECT(stiffspring_value_f32_init(&v, sizeof v, &t, NAN), STIFFSPRING_ERROR_NOT_FINITE);
    EXPECT(stiffspring_value_f32_init(&v, sizeof v, &t, INFINITY), STIFFSPRING_ERROR_NOT_FINITE);
    static const StiffspringValueF32 zero;
    CHECK(memcmp(&v, &zero, sizeof v) == 0);

    EXPECT(stiffspring_value_f32_init(&v, sizeof v, &t, 1.0f), STIFFSPRING_ERROR_OK);
    /* The UI path's setters cannot fail on a value: NaN is ignored. */
    EXPECT(stiffspring_value_f32_set_target(&v, NAN), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_value_f32_set_position(&v, NAN), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_value_f32_fling(&v, NAN), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_value_f32_position(&v, &x), STIFFSPRING_ERROR_OK);
    CHECK(x == 1.0f);
    EXPECT(stiffspring_value_f32_is_at_rest(&v, &resting), STIFFSPRING_ERROR_OK);
    CHECK(resting);
    /* Their try_ twins report it and change nothing. */
    EXPECT(stiffspring_value_f32_try_set_target(&v, NAN), STIFFSPRING_ERROR_NOT_FINITE);
    EXPECT(stiffspring_value_f32_try_set_position(&v, INFINITY), STIFFSPRING_ERROR_NOT_FINITE);
    EXPECT(stiffspring_value_f32_try_fling(&v, NAN), STIFFSPRING_ERROR_NOT_FINITE);
    EXPECT(stiffspring_value_f32_set_rest_threshold(&v, -1.0, 1.0), STIFFSPRING_ERROR_OUT_OF_RANGE);
    EXPECT(stiffspring_value_f32_set_rest_threshold(&v, 0.5, 10.0), STIFFSPRING_ERROR_OK);
    /* Out-pointers. */
    EXPECT(stiffspring_value_f32_position(&v, NULL), STIFFSPRING_ERROR_NULL_POINTER);
    EXPECT(stiffspring_value_f32_position(&v, (float *)(raw + 1)), STIFFSPRING_ERROR_MISALIGNED);
    /* A handle of another type. */
    EXPECT(stiffspring_value_q16_step((StiffspringValueQ16 *)&v, NULL), STIFFSPRING_ERROR_NOT_INITIALISED);
    /* A copy is an object of its own. */
    StiffspringValueF32 copy;
    memcpy(&copy, &v, sizeof v);
    EXPECT(stiffspring_value_f32_set_target(&copy, 5.0f), STIFFSPRING_ERROR_OK);
    /* Use after drop. */
    EXPECT(stiffspring_value_f32_drop(&v), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_value_f32_drop(&v), STIFFSPRING_ERROR_DROPPED);
    EXPECT(stiffspring_value_f32_set_target(&v, 2.0f), STIFFSPRING_ERROR_DROPPED);
    EXPECT(stiffspring_value_f32_step(&v, NULL), STIFFSPRING_ERROR_DROPPED);
    EXPECT(stiffspring_value_f32_target(&copy, &x), STIFFSPRING_ERROR_OK);
    CHECK(x == 5.0f);
    /* Null handles. */
    EXPECT(stiffspring_value_f32_step(NULL, NULL), STIFFSPRING_ERROR_NULL_POINTER);
    EXPECT(stiffspring_value_f32_velocity(NULL, &x), STIFFSPRING_ERROR_NULL_POINTER);
}

static void value_q16(void) {
    StiffspringTuning t;
    StiffspringValueQ16 v;
    EXPECT(stiffspring_tuning_from_frequency(&t, sizeof t, 3.0, 1.0, 1.0 / 60.0), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_value_q16_init(&v, sizeof v, &t, 10 * STIFFSPRING_Q16_ONE), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_value_q16_set_target(&v, -STIFFSPRING_Q16_ONE / 2), STIFFSPRING_ERROR_OK);
    StiffspringMotion m = STIFFSPRING_MOTION_MOVING;
    int frames = 0;
    while (m != STIFFSPRING_MOTION_SETTLED && frames < 1000) {
        EXPECT(stiffspring_value_q16_step(&v, &m), STIFFSPRING_ERROR_OK);
        frames++;
    }
    int32_t x = 0;
    EXPECT(stiffspring_value_q16_position(&v, &x), STIFFSPRING_ERROR_OK);
    CHECK(x == -STIFFSPRING_Q16_ONE / 2 && frames < 120);
    /* A 0.1 Hz spring at 10 kHz is below Q16.16's resolution. */
    EXPECT(stiffspring_tuning_from_frequency(&t, sizeof t, 0.1, 0.5, 1e-4), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_value_q16_init(&v, sizeof v, &t, 0), STIFFSPRING_ERROR_UNREPRESENTABLE);
    EXPECT(stiffspring_value_q16_position(&v, &x), STIFFSPRING_ERROR_OK); /* the old value lives on */
}

static void batch(void) {
    StiffspringTuning t;
    static StiffspringBatchF32 rows;
    uint32_t a = 0, b = 0, stale;
    float y = 0.0f;
    EXPECT(stiffspring_tuning_from_frequency(&t, sizeof t, 3.0, 1.0, 1.0 / 60.0), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_batch_f32_push(&rows, 0.0f, &a), STIFFSPRING_ERROR_NOT_INITIALISED);
    EXPECT(stiffspring_batch_f32_init(&rows, sizeof rows - 8, &t), STIFFSPRING_ERROR_BUFFER_TOO_SMALL);
    EXPECT(stiffspring_batch_f32_init(&rows, sizeof rows, &t), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_batch_f32_push(&rows, NAN, &a), STIFFSPRING_ERROR_NOT_FINITE);
    EXPECT(stiffspring_batch_f32_push(&rows, 0.0f, NULL), STIFFSPRING_ERROR_NULL_POINTER);
    EXPECT(stiffspring_batch_f32_push(&rows, 0.0f, &a), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_batch_f32_push(&rows, 24.0f, &b), STIFFSPRING_ERROR_OK);
    stale = b;
    EXPECT(stiffspring_batch_f32_remove(&rows, b, &y), STIFFSPRING_ERROR_OK);
    CHECK(y == 24.0f);
    EXPECT(stiffspring_batch_f32_push(&rows, 48.0f, &b), STIFFSPRING_ERROR_OK);
    CHECK(b != stale && (b & 0xffff) == (stale & 0xffff));
    EXPECT(stiffspring_batch_f32_set_target(&rows, stale, 1.0f), STIFFSPRING_ERROR_STALE_INDEX);
    EXPECT(stiffspring_batch_f32_position(&rows, stale, &y), STIFFSPRING_ERROR_STALE_INDEX);
    EXPECT(stiffspring_batch_f32_set_target(&rows, a, NAN), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_batch_f32_try_set_target(&rows, a, NAN), STIFFSPRING_ERROR_NOT_FINITE);
    EXPECT(stiffspring_batch_f32_set_target(&rows, a, 100.0f), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_batch_f32_fling(&rows, b, -50.0f), STIFFSPRING_ERROR_OK);
    /* The batch equals a separate value of the same tuning, to the bit. */
    StiffspringValueF32 alone;
    EXPECT(stiffspring_value_f32_init(&alone, sizeof alone, &t, 0.0f), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_value_f32_set_target(&alone, 100.0f), STIFFSPRING_ERROR_OK);
    int differ = 0, settled_a = 0;
    for (int frame = 0; frame < 300; frame++) {
        StiffspringBatchMotion m;
        EXPECT(stiffspring_batch_f32_step(&rows, &m), STIFFSPRING_ERROR_OK);
        stiffspring_value_f32_step(&alone, NULL);
        float x, z;
        stiffspring_batch_f32_position(&rows, a, &x);
        stiffspring_value_f32_position(&alone, &z);
        differ += memcmp(&x, &z, sizeof x) != 0;
        uint32_t done[STIFFSPRING_BATCH_CAPACITY];
        size_t n = 0;
        EXPECT(stiffspring_batch_f32_just_settled(&rows, done, STIFFSPRING_BATCH_CAPACITY, &n), STIFFSPRING_ERROR_OK);
        for (size_t i = 0; i < n; i++) settled_a += done[i] == a;
    }
    CHECK(differ == 0);
    CHECK(settled_a == 1);
    uint32_t len = 0, awake = 9;
    EXPECT(stiffspring_batch_f32_counts(&rows, &len, &awake), STIFFSPRING_ERROR_OK);
    CHECK(len == 2 && awake == 0);
    /* Full. */
    for (int i = 2; i < STIFFSPRING_BATCH_CAPACITY; i++) EXPECT(stiffspring_batch_f32_push(&rows, 0.0f, &b), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_batch_f32_push(&rows, 0.0f, &b), STIFFSPRING_ERROR_CAPACITY_FULL);
    EXPECT(stiffspring_batch_f32_drop(&rows), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_batch_f32_step(&rows, NULL), STIFFSPRING_ERROR_DROPPED);
}

static void knob_errors(void) {
    StiffspringKnobConfig config = {0};
    static StiffspringKnobF32 knob;
    StiffspringKnobOutputF32 out;
    EXPECT(stiffspring_knob_f32_init(&knob, sizeof knob, &config, 0.0f), STIFFSPRING_ERROR_NOT_INITIALISED);
    EXPECT(knob_scene_config(&config), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_knob_config_latency(&config, 2), STIFFSPRING_ERROR_OUT_OF_RANGE);
    static const double nine[9];
    EXPECT(stiffspring_knob_config_magnets(&config, nine, 9), STIFFSPRING_ERROR_CAPACITY_FULL);
    EXPECT(stiffspring_knob_f32_init(&knob, sizeof knob, &config, NAN), STIFFSPRING_ERROR_NOT_FINITE);
    EXPECT(stiffspring_knob_f32_update(&knob, 0.0f, &out), STIFFSPRING_ERROR_NOT_INITIALISED);
    StiffspringKnobConfig strong = config;
    EXPECT(stiffspring_knob_config_detent_stiffness(&strong, 10.0), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_knob_f32_init(&knob, sizeof knob, &strong, 0.0f), STIFFSPRING_ERROR_OUT_OF_RANGE);
    StiffspringKnobConfig no_stops;
    EXPECT(stiffspring_knob_config_init(&no_stops, sizeof no_stops, 1000.0, 1e-5, 0.05, 16384), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_knob_config_detent_count(&no_stops, 8), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_knob_f32_init(&knob, sizeof knob, &no_stops, 0.0f), STIFFSPRING_ERROR_NEEDS_ENDSTOPS);
    EXPECT(stiffspring_knob_f32_init(&knob, sizeof knob, &config, 1.0f), STIFFSPRING_ERROR_OK);
    /* Bad readings are sensor faults, never errors. */
    EXPECT(stiffspring_knob_f32_update(&knob, NAN, &out), STIFFSPRING_ERROR_OK);
    CHECK(out.events.sensor == STIFFSPRING_SENSOR_FAULT_NOT_A_NUMBER);
    EXPECT(stiffspring_knob_f32_update(&knob, INFINITY, &out), STIFFSPRING_ERROR_OK);
    CHECK(out.events.sensor == STIFFSPRING_SENSOR_FAULT_OUT_OF_RANGE);
    EXPECT(stiffspring_knob_f32_update(&knob, 1.0f, NULL), STIFFSPRING_ERROR_NULL_POINTER);
    EXPECT(stiffspring_knob_f32_reset(&knob, 2.0f), STIFFSPRING_ERROR_OK);
    int32_t detent = -1;
    EXPECT(stiffspring_knob_f32_detent(&knob, &detent), STIFFSPRING_ERROR_OK);
    CHECK(detent > 0);
    EXPECT(stiffspring_knob_f32_drop(&knob), STIFFSPRING_ERROR_OK);
    EXPECT(stiffspring_knob_f32_update(&knob, 1.0f, &out), STIFFSPRING_ERROR_DROPPED);
    /* Q16.16. */
    static StiffspringKnobQ16 q;
    StiffspringKnobOutputQ16 outq;
    EXPECT(stiffspring_knob_q16_init(&q, sizeof q, &config, STIFFSPRING_Q16_ONE), STIFFSPRING_ERROR_OK);
    /* 1 rad, then 0.0046 rad past it, held: the detent pulls back (a negative torque). */
    for (int n = 0; n < 5; n++) {
        EXPECT(stiffspring_knob_q16_update(&q, STIFFSPRING_Q16_ONE + 300, &outq), STIFFSPRING_ERROR_OK);
    }
    CHECK(outq.torque < 0 && outq.torque >= -STIFFSPRING_Q16_ONE);
    CHECK(outq.events.sensor == STIFFSPRING_SENSOR_FAULT_NONE);
}

int main(void) {
    error_names();
    storage_sizes();
    tuning_errors();
    value_errors();
    value_q16();
    batch();
    knob_errors();
    int scene = value_scene_f32();
    CHECK(scene == 0);
    int sweep = knob_sweep_f32();
    CHECK(sweep == 0);
    printf("%d passed, %d failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}
