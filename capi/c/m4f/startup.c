/* Start-up of the C examples on QEMU's mps2-an386 (Cortex-M4F), the machine the Rust
 * firmware runs on (scripts/qemu-run): the vector table, the FPU turned on, .data and .bss
 * laid out, newlib's semihosting console (librdimon) opened, main(), and an exit through
 * semihosting with main's status (QEMU exits with 0 for success, 1 for anything else). */
#include <stdint.h>

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, __stack_top;
extern int main(void);
extern void initialise_monitor_handles(void);

/* Semihosting SYS_EXIT: "application exit" (0x20026) for status 0, "run-time error"
 * (0x20023) otherwise, the reasons QEMU maps to its own exit status 0 and 1. newlib's
 * _exit drops the status on this semihosting version, so the examples use this. */
__attribute__((noreturn)) void semihosting_exit(int status) {
    register uint32_t op __asm__("r0") = 0x18;
    register uint32_t reason __asm__("r1") = status == 0 ? 0x20026u : 0x20023u;
    for (;;) {
        __asm__ volatile("bkpt 0xab" : : "r"(op), "r"(reason) : "memory");
    }
}

/* The copy loops stay loops (GCC would call memcpy and memset, which an empty firmware
 * does not otherwise link, and the size report would count them as the start-up's). */
__attribute__((noreturn, optimize("no-tree-loop-distribute-patterns"))) void Reset_Handler(void) {
    /* CPACR: full access to CP10 and CP11 (the FPU), before the first float instruction. */
    *(volatile uint32_t *)0xE000ED88 |= 0xFu << 20;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
    for (uint32_t *src = &_sidata, *dst = &_sdata; dst < &_edata;) *dst++ = *src++;
    for (uint32_t *dst = &_sbss; dst < &_ebss;) *dst++ = 0;
#ifndef NO_CONSOLE
    initialise_monitor_handles();
#endif
    semihosting_exit(main());
}

/* Any fault ends the run with a failure instead of hanging QEMU. */
__attribute__((noreturn)) void Fault_Handler(void) { semihosting_exit(1); }

__attribute__((section(".vectors"), used)) static void (*const vectors[16])(void) = {
    (void (*)(void))&__stack_top, Reset_Handler, Fault_Handler, Fault_Handler,
    Fault_Handler, Fault_Handler, Fault_Handler, 0, 0, 0, 0, Fault_Handler, Fault_Handler, 0,
    Fault_Handler, Fault_Handler,
};
