// The STM32F4's start-up: the vector table (linker/stm32f4-app.ld puts it at
// the start of flash, where the core reads its stack pointer and reset
// address), the reset handler that prepares RAM and calls main, and the
// handler of every vector the firmware does not use.

#include <stdint.h>

#include "stm32f4_registers.h"

#define SYSTEM_VECTORS   16u
#define EXTERNAL_VECTORS 82u // the STM32F405/407's interrupts (RM0090 §12.2)
#define VECTOR_SYSTICK   15u
#define VECTOR_USART1    (SYSTEM_VECTORS + STM32F4_IRQ_USART1)

// From the linker script.
extern uint32_t _stack_top;
extern uint32_t _data_load;
extern uint32_t _data_start;
extern uint32_t _data_end;
extern uint32_t _bss_start;
extern uint32_t _bss_end;

int main(void);

// The entry point's handlers, which forward to its board.
void stm32f4_systick_vector(void);
void stm32f4_usart1_vector(void);

// Copies the initialised data, zeroes the rest (not .noinit) and runs main.
void stm32f4_reset_handler(void);

void stm32f4_reset_handler(void)
{
    uint32_t *from = &_data_load;
    uint32_t *to;

    for (to = &_data_start; to < &_data_end;)
        *to++ = *from++;
    for (to = &_bss_start; to < &_bss_end;)
        *to++ = 0;
    main();
    for (;;)
        ;
}

// A fault or an unexpected interrupt restarts the chip: the robot comes back
// reachable, as after a REBOOT.
static void unexpected_vector(void)
{
    stm32f4_data_barrier();
    stm32f4_write(STM32F4_SCB_AIRCR, STM32F4_AIRCR_RESET);
    for (;;)
        ;
}

typedef void (*vector)(void);

// Entry 0 is the initial stack pointer, entry 1 the reset handler.
__attribute__((section(".isr_vector"),
               used)) static const vector vectors[SYSTEM_VECTORS + EXTERNAL_VECTORS] = {
    [0] = (vector)&_stack_top,
    [1] = stm32f4_reset_handler,
    [2 ... VECTOR_SYSTICK - 1] = unexpected_vector,
    [VECTOR_SYSTICK] = stm32f4_systick_vector,
    [SYSTEM_VECTORS... VECTOR_USART1 - 1] = unexpected_vector,
    [VECTOR_USART1] = stm32f4_usart1_vector,
    [VECTOR_USART1 + 1 ... SYSTEM_VECTORS + EXTERNAL_VECTORS - 1] = unexpected_vector,
};
