/*
 * board.c -- start-up and counters for QEMU's mps2-an386 board (Cortex-M4F,
 * run with semihosting): the vector table, a reset handler that turns the
 * FPU on before anything else, SysTick as an instruction counter, and the
 * stack painting of board.h.  Built for any other machine it supplies the
 * stubs board.h describes, so the same host runs on the build machine.
 */
#include "board.h"

#if defined(__arm__)

#include <stdlib.h>

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack;
extern void initialise_monitor_handles(void); /* newlib's rdimon: semihosting */
int main(void);
void board_reset(void);
void board_fault(void);
void board_systick(void);
void _init(void);
void _fini(void);

#define REG(a) (*(volatile uint32_t *)(a))
#define CPACR 0xE000ED88u
#define SYST_CSR 0xE000E010u
#define SYST_RVR 0xE000E014u
#define SYST_CVR 0xE000E018u
#define TICK_INSNS 40u /* 1 ns an instruction (-icount shift=0), 25 MHz */

/* Initial stack pointer, then the handlers; a fault ends the run with a
 * failure status (QEMU's exit status follows the program's). */
__attribute__((section(".vectors"), used)) const uintptr_t board_vectors[16] = {
    (uintptr_t)&_estack, (uintptr_t)board_reset, (uintptr_t)board_fault,
    (uintptr_t)board_fault, (uintptr_t)board_fault, (uintptr_t)board_fault,
    (uintptr_t)board_fault, 0, 0, 0, 0, (uintptr_t)board_fault, (uintptr_t)board_fault,
    0, (uintptr_t)board_fault, (uintptr_t)board_systick};

static volatile uint32_t wraps;
static uint32_t *paint_lo, *paint_hi;

/* No floating point may run before CP10 and CP11 are enabled. */
void board_reset(void)
{
    uint32_t *s = &_sidata, *d;
    REG(CPACR) |= 0xFu << 20;
    __asm volatile("dsb\n\tisb" ::: "memory");
    for (d = &_sdata; d < &_edata;)
        *d++ = *s++;
    for (d = &_sbss; d < &_ebss;)
        *d++ = 0;
    initialise_monitor_handles();
    REG(SYST_RVR) = 0xFFFFFFu;
    REG(SYST_CVR) = 0;
    REG(SYST_CSR) = 7u; /* core clock, interrupt on wrap, enabled */
    while (REG(SYST_CVR) == 0) /* the first reload, or a reading is off by a wrap */
        ;
    exit(main());
}

void board_fault(void)
{
    exit(3);
}

void board_systick(void)
{
    wraps = wraps + 1u;
}

void _init(void) {}
void _fini(void) {}

uint64_t board_instructions(void)
{
    uint32_t w, v;
    do {
        w = wraps;
        v = REG(SYST_CVR);
    } while (w != wraps);
    return ((uint64_t)w * 0x1000000u + (0xFFFFFFu - v)) * TICK_INSNS;
}

void board_stack_paint(uint32_t bytes)
{
    uint32_t *sp, *p;
    __asm volatile("mov %0, sp" : "=r"(sp));
    paint_hi = sp - 16; /* leave this frame alone */
    paint_lo = paint_hi - bytes / 4u;
    for (p = paint_lo; p < paint_hi; p++)
        *p = 0xA5A5A5A5u;
}

uint32_t board_stack_used(void)
{
    uint32_t *p = paint_lo;
    while (p < paint_hi && *p == 0xA5A5A5A5u)
        p++;
    return (uint32_t)(paint_hi - p) * 4u;
}

#else /* the build machine: no counter, no painting */

uint64_t board_instructions(void)
{
    return 0;
}

void board_stack_paint(uint32_t bytes)
{
    (void)bytes;
}

uint32_t board_stack_used(void)
{
    return 0;
}

#endif
