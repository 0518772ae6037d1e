/* The C value animation on the Cortex-M4F (QEMU mps2-an386): the value scene of
 * examples/check_value.rs through the C API in f32, against the same golden values.
 * Built and run by scripts/check-capi; exits with failure when a sample is out of
 * tolerance. */
#include <stdio.h>

#include "value_scene.h"

int main(void) {
    printf("C value animation on the Cortex-M4F\n");
    int failures = value_scene_f32();
    printf("value scene: %s\n", failures == 0 ? "every sample within tolerance" : "FAILED");
    return failures != 0;
}
