/* actionstring port — the few board services the Cortex-M hooks need,
 * implemented in startup.c. Usable from C and C++. */
#ifndef ACTIONSTRING_CORTEX_M_BOARD_H
#define ACTIONSTRING_CORTEX_M_BOARD_H

#include <stdint.h>

/* QEMU's mps2-an386 (and the real AN386 FPGA image) clock the core at 25 MHz. */
#ifndef ACTIONSTRING_CORE_CLOCK_HZ
#define ACTIONSTRING_CORE_CLOCK_HZ 25000000u
#endif

#ifdef __cplusplus
extern "C" {
#endif

/** Core clock cycles since reset (SysTick extended to 64 bits). */
uint64_t actionstring_board_ticks(void);
/** Writes a NUL-terminated string through semihosting (SYS_WRITE0). */
void actionstring_board_write(const char* text);
/** Ends the program through semihosting: status 0 is success. */
__attribute__((noreturn)) void actionstring_board_exit(int status);
/** Deepest stack use since reset in bytes (the stack is painted at reset). */
uint32_t actionstring_board_stack_used(void);
/** Bytes reserved for the stack by the linker script. */
uint32_t actionstring_board_stack_size(void);

#ifdef __cplusplus
}
#endif

#endif
