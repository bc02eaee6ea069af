/* actionstring port — Cortex-M4F start-up for QEMU's mps2-an386 (and any
 * ARMv7-M part with the same memory layout): vector table, reset (copy .data,
 * clear .bss, paint the stack, enable the FPU, SysTick, static constructors),
 * semihosting output and exit. No C library start-up code and no heap. */
#include <stddef.h>
#include <stdint.h>

#include "cortex_m_board.h"

extern uint32_t __data_load__, __data_start__, __data_end__, __bss_start__, __bss_end__;
extern uint32_t __stack_limit__, __stack_top__;
extern void (*__init_array_start[])(void);
extern void (*__init_array_end[])(void);

int main(void);
void Reset_Handler(void);
void SysTick_Handler(void);
void Fault_Handler(void);

#define REG32(address) (*(volatile uint32_t*)(address))
#define SCB_CPACR REG32(0xE000ED88u)
#define SYST_CSR REG32(0xE000E010u)
#define SYST_RVR REG32(0xE000E014u)
#define SYST_CVR REG32(0xE000E018u)
#define SYSTICK_RELOAD 0x00FFFFFFu
#define STACK_PAINT 0xA5A5A5A5u

static volatile uint32_t systick_wraps;

/* Stack pointer, then the 15 ARMv7-M exceptions; this image takes no device interrupts. */
__attribute__((section(".vectors"), used)) static void (*const vector_table[16])(void) = {
    (void (*)(void))(uintptr_t)&__stack_top__,
    Reset_Handler,
    Fault_Handler, /* NMI */
    Fault_Handler, /* HardFault */
    Fault_Handler, /* MemManage */
    Fault_Handler, /* BusFault */
    Fault_Handler, /* UsageFault */
    0,
    0,
    0,
    0,
    Fault_Handler, /* SVCall */
    Fault_Handler, /* DebugMonitor */
    0,
    Fault_Handler, /* PendSV */
    SysTick_Handler,
};

/* ARM semihosting: operation in r0, argument block in r1, BKPT 0xAB on M-profile. */
static int semihost(int operation, const void* argument) {
    register int r0 __asm__("r0") = operation;
    register const void* r1 __asm__("r1") = argument;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

void actionstring_board_write(const char* text) { (void)semihost(0x04 /* SYS_WRITE0 */, text); }

void actionstring_board_exit(int status) {
    /* SYS_EXIT with ADP_Stopped_ApplicationExit (QEMU exits 0) or RunTimeErrorUnknown (exits 1). */
    const uintptr_t reason = status == 0 ? 0x20026u : 0x20023u;
    (void)semihost(0x18 /* SYS_EXIT */, (const void*)reason);
    for (;;) __asm__ volatile("bkpt 0");
}

void SysTick_Handler(void) { ++systick_wraps; }

uint64_t actionstring_board_ticks(void) {
    uint32_t wraps, current;
    do { /* re-read when the wrap interrupt ran in between */
        wraps = systick_wraps;
        current = SYST_CVR;
    } while (wraps != systick_wraps);
    return (uint64_t)wraps * (SYSTICK_RELOAD + 1u) + (SYSTICK_RELOAD - current);
}

uint32_t actionstring_board_stack_size(void) {
    return (uint32_t)((uintptr_t)&__stack_top__ - (uintptr_t)&__stack_limit__);
}

uint32_t actionstring_board_stack_used(void) {
    const uint32_t* word = &__stack_limit__;
    while (word < &__stack_top__ && *word == STACK_PAINT) ++word;
    return (uint32_t)((uintptr_t)&__stack_top__ - (uintptr_t)word);
}

void Fault_Handler(void) {
    actionstring_board_write("actionstring firmware: fault exception\n");
    actionstring_board_exit(1);
}

void Reset_Handler(void) {
    for (uint32_t *from = &__data_load__, *to = &__data_start__; to < &__data_end__;) *to++ = *from++;
    for (uint32_t* to = &__bss_start__; to < &__bss_end__;) *to++ = 0u;
    /* Paint the stack below this frame so the deepest use can be measured later. */
    uintptr_t stack_pointer;
    __asm__ volatile("mov %0, sp" : "=r"(stack_pointer));
    for (uint32_t* word = &__stack_limit__; (uintptr_t)word < stack_pointer - 64u; ++word) *word = STACK_PAINT;
    SCB_CPACR |= 0xFu << 20; /* CP10 and CP11: full access to the FPU */
    __asm__ volatile("dsb\n\tisb" ::: "memory");
    SYST_RVR = SYSTICK_RELOAD;
    SYST_CVR = 0u;
    SYST_CSR = 0x7u; /* enable, interrupt on wrap, core clock */
    for (void (**constructor)(void) = __init_array_start; constructor < __init_array_end; ++constructor)
        (*constructor)();
    actionstring_board_exit(main());
}
