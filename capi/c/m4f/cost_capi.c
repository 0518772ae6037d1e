/* Instructions per call of the C API on the Cortex-M4F (QEMU mps2-an386 under -icount,
 * where the CMSDK TIMER0 counts instructions exactly; firmware/src/timer.rs has why),
 * against the Rust API's figures of examples/cost.rs (docs/firmware.md):
 *
 * - stiffspring_value_f32_step on a moving value (2 Hz at 1 kHz, damping ratio 0.02, as
 *   cost.rs's value, which never settles while measured), against `step`'s 15.0;
 * - stiffspring_knob_f32_update on cost.rs's knob (1 kHz, 16 detents between endstops at
 *   0 and 3 rad) and its scripted encoder (up and down 3.4 rad in 256 updates, one add and
 *   one compare a step), over whole sweeps after one of warm-up, against `Knob::update`'s
 *   207.0.
 *
 * Each kernel runs 32 and then 288 times between two timer reads; the difference, minus
 * the same loop with no call, is divided by 256. scripts/qemu-run runs an ELF named cost*
 * with -icount shift=10. Built and run by scripts/check-capi. */
#include <stdio.h>

#include <stdint.h>

#include "stiffspring.h"

#define TIMER0_CTRL (*(volatile uint32_t *)0x40000000u)
#define TIMER0_VALUE (*(volatile uint32_t *)0x40000004u)
#define TIMER0_RELOAD (*(volatile uint32_t *)0x40000008u)

/* Instructions in `ticks` of 40 ns at 1,024 ns an instruction (-icount shift=10). */
static double instructions(uint32_t ticks) { return (double)ticks * 40.0 / 1024.0; }

static StiffspringValueF32 value;
static StiffspringKnobF32 knob;
static volatile int sink;

__attribute__((noinline)) static void run_empty(int n) {
    for (int i = 0; i < n; i++) __asm__ volatile("" ::: "memory");
}

__attribute__((noinline)) static void run_value(int n) {
    for (int i = 0; i < n; i++) {
        stiffspring_value_f32_step(&value, NULL);
        __asm__ volatile("" ::: "memory");
    }
}

/* cost.rs's encoder script. */
#define SWEEP 256
static float angle = -0.2f, increment = (float)(3.4 / (SWEEP - 0.5));
static const float low = -0.2f, high = 3.2f;

__attribute__((noinline)) static void run_knob(int n) {
    for (int i = 0; i < n; i++) {
        StiffspringKnobOutputF32 out;
        stiffspring_knob_f32_update(&knob, angle, &out);
        sink = (int)out.detent;
        float next = angle + increment;
        if (next > high || next < low) increment = -increment;
        angle = angle + increment;
    }
}

/* The ticks of `more` runs minus those of `fewer`. */
static uint32_t ticks_of(void (*run)(int), int fewer, int more) {
    uint32_t a = TIMER0_VALUE;
    run(fewer);
    uint32_t b = TIMER0_VALUE;
    run(more);
    uint32_t c = TIMER0_VALUE;
    return (b - c) - (a - b);
}

int main(void) {
    TIMER0_RELOAD = 0xffffffffu;
    TIMER0_VALUE = 0xffffffffu;
    TIMER0_CTRL = 1;

    StiffspringTuning tuning;
    StiffspringKnobConfig config;
    if (stiffspring_tuning_from_frequency(&tuning, sizeof tuning, 2.0, 0.02, 1e-3) != STIFFSPRING_ERROR_OK ||
        stiffspring_value_f32_init(&value, sizeof value, &tuning, 0.0f) != STIFFSPRING_ERROR_OK ||
        stiffspring_knob_config_init(&config, sizeof config, 1000.0, 1e-5, 0.05, 16384) != STIFFSPRING_ERROR_OK ||
        stiffspring_knob_config_endstops(&config, 0.0, 3.0) != STIFFSPRING_ERROR_OK ||
        stiffspring_knob_config_detent_count(&config, 16) != STIFFSPRING_ERROR_OK ||
        stiffspring_knob_config_detent_stiffness(&config, 0.05) != STIFFSPRING_ERROR_OK ||
        stiffspring_knob_f32_init(&knob, sizeof knob, &config, -0.2f) != STIFFSPRING_ERROR_OK) {
        printf("set-up refused\n");
        return 1;
    }
    stiffspring_value_f32_set_target(&value, 100.0f);
    run_knob(SWEEP); /* warm-up */

    double empty = instructions(ticks_of(run_empty, 32, 288)) / 256.0;
    double step = instructions(ticks_of(run_value, 32, 288)) / 256.0 - empty;
    /* Whole sweeps, up and down: 2 and 4 of cost.rs's SWEEP. */
    double update = instructions(ticks_of(run_knob, 2 * SWEEP, 4 * SWEEP)) / (2.0 * SWEEP) - empty;

    printf("C API on the Cortex-M4F, instructions per call (QEMU -icount):\n");
    printf("stiffspring_value_f32_step (moving value): %.1f\n", step);
    printf("stiffspring_knob_f32_update (cost.rs's knob and sweep, with the script): %.1f\n", update);
    printf("empty loop: %.1f per iteration\n", empty);
    return 0;
}
