/* The C knob loop on the Cortex-M4F (QEMU mps2-an386): the encoder sweep of
 * examples/check_knob.rs through the C API's f32 knob, one update per period, against the
 * Rust knob's torques (bit for bit) and the golden f64 torques. Built and run by
 * scripts/check-capi; exits with failure on any difference. */
#include <stdio.h>

#include "knob_scene.h"

int main(void) {
    printf("C knob loop on the Cortex-M4F\n");
    int failures = knob_sweep_f32();
    printf("knob sweep: %s\n", failures == 0 ? "the Rust knob's torques, bit for bit" : "FAILED");
    return failures != 0;
}
