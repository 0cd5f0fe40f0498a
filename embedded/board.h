/*
 * board.h -- what the embedded host needs from its board (board.c, QEMU's
 * mps2-an386 Cortex-M4F): an instruction counter and a stack high-water
 * mark.  Built for the host machine instead (make embedded-host), the
 * counter reads 0 and the stack is not measured.
 */
#ifndef BOARD_H
#define BOARD_H

#include <stdint.h>

/* Instructions executed since reset, from SysTick: QEMU run with
 * `-icount shift=0` makes one instruction one nanosecond of emulated time,
 * and SysTick counts the 25 MHz core clock, so a tick is 40 instructions
 * (docs/PORTING.md, "Embedded"). */
uint64_t board_instructions(void);

/* Fills the stack below the caller's frame (up to `bytes`) with a
 * pattern; board_stack_used then says how deep the calls made since went,
 * in bytes below the painting call's frame. */
void board_stack_paint(uint32_t bytes);
uint32_t board_stack_used(void);

#endif
