// The STM32F4's clock: the crystal and the PLL to STM32F4_CPU_HZ when the
// board has a crystal (RM0090 §6.3), SysTick's millisecond interrupt,
// interrupt masking, reset and sleep.

#include "stm32f4_chip.h"
#include "stm32f4_registers.h"

#define MILLISECONDS_PER_SECOND 1000ul
#define MICROSECONDS_PER_SECOND 1000000ul
// Polls of a ready bit before the start-up goes on without it.
#define CLOCK_READY_ATTEMPTS 100000ul
// The PLL from the crystal: VCO input 2 MHz (M = crystal in MHz / 2), VCO
// 336 MHz (N = 168), system clock = VCO / 2, 48 MHz for USB = VCO / 7
// (RM0090 §6.3.2). Flash wait states at 168 MHz and 3.3 V (§3.5.1): 5.
#define PLL_INPUT_HZ          2000000ul
#define PLL_N                 168ul
#define PLL_P_CODE            0ul // P = 2
#define PLL_Q                 7ul
#define FLASH_WAIT_STATES     5ul
#define CYCLES_PER_DELAY_LOOP 4ul // a loop iteration, about

typedef char clock_is_what_the_pll_makes
  [STM32F4_HSE_HZ == 0 || PLL_INPUT_HZ * PLL_N / 2ul == STM32F4_CPU_HZ ? 1 : -1];

static bool wait_for(uint32_t address, uint32_t mask, uint32_t value)
{
    uint32_t attempts;

    for (attempts = 0; attempts < CLOCK_READY_ATTEMPTS; attempts++) {
        if ((stm32f4_read(address) & mask) == value)
            return true;
    }
    return false;
}

// Crystal, PLL, flash wait states, bus dividers; stays on the internal
// oscillator when anything does not get ready.
static void start_pll(void)
{
    stm32f4_set_bits(STM32F4_RCC_CR, STM32F4_RCC_CR_HSEON);
    if (!wait_for(STM32F4_RCC_CR, STM32F4_RCC_CR_HSERDY, STM32F4_RCC_CR_HSERDY))
        return;
    stm32f4_write(STM32F4_RCC_PLLCFGR,
                  STM32F4_HSE_HZ / PLL_INPUT_HZ | PLL_N << STM32F4_PLLCFGR_N_SHIFT |
                    PLL_P_CODE << STM32F4_PLLCFGR_P_SHIFT | STM32F4_PLLCFGR_PLLSRC_HSE |
                    PLL_Q << STM32F4_PLLCFGR_Q_SHIFT);
    stm32f4_set_bits(STM32F4_RCC_CR, STM32F4_RCC_CR_PLLON);
    if (!wait_for(STM32F4_RCC_CR, STM32F4_RCC_CR_PLLRDY, STM32F4_RCC_CR_PLLRDY))
        return;
    stm32f4_write(STM32F4_FLASH_ACR,
                  FLASH_WAIT_STATES | STM32F4_ACR_PRFTEN | STM32F4_ACR_ICEN | STM32F4_ACR_DCEN);
    stm32f4_write(STM32F4_RCC_CFGR,
                  STM32F4_CFGR_PPRE1_DIV4 | STM32F4_CFGR_PPRE2_DIV2 | STM32F4_CFGR_SW_PLL);
    wait_for(STM32F4_RCC_CFGR, STM32F4_CFGR_SWS_MASK, STM32F4_CFGR_SWS_PLL);
}

void stm32f4_board_init(hal_board *board)
{
    stm32f4_clock_init(board);
    stm32f4_usart_init(board);
}

void stm32f4_clock_init(hal_board *board)
{
    board->milliseconds = 0;
    if (STM32F4_HSE_HZ != 0)
        start_pll();
    stm32f4_write_byte(STM32F4_SCB_SHPR3 + 3u,
                       (uint8_t)(STM32F4_PRIORITY_SYSTICK << STM32F4_PRIORITY_SHIFT));
    stm32f4_write(STM32F4_SYST_RVR, STM32F4_CPU_HZ / MILLISECONDS_PER_SECOND - 1ul);
    stm32f4_write(STM32F4_SYST_CVR, 0);
    stm32f4_write(STM32F4_SYST_CSR,
                  STM32F4_SYST_CSR_ENABLE | STM32F4_SYST_CSR_TICKINT | STM32F4_SYST_CSR_CLKSOURCE);
}

void stm32f4_on_systick(hal_board *board)
{
    board->milliseconds++;
}

uint32_t hal_milliseconds(hal_board *board)
{
    // A 32-bit read is one instruction on the Cortex-M4.
    return board->milliseconds;
}

void hal_delay_microseconds(hal_board *board, uint16_t microseconds)
{
    volatile uint32_t iterations =
      (uint32_t)microseconds * (STM32F4_CPU_HZ / MICROSECONDS_PER_SECOND) / CYCLES_PER_DELAY_LOOP;
    (void)board;
    while (iterations > 0)
        iterations--;
}

hal_critical_state hal_critical_enter(hal_board *board)
{
    (void)board;
    return (hal_critical_state)stm32f4_interrupts_off();
}

void hal_critical_leave(hal_board *board, hal_critical_state state)
{
    (void)board;
    stm32f4_interrupts_restore(state);
}

void hal_reset(hal_board *board)
{
    // A REBOOT's last answers leave first.
    while (hal_link_rings_sending(&board->link))
        stm32f4_usart_drain(board);
    stm32f4_data_barrier();
    stm32f4_write(STM32F4_SCB_AIRCR, STM32F4_AIRCR_RESET);
    for (;;)
        ;
}

void hal_idle(hal_board *board)
{
    // Polled transmission has no interrupt to wake the core: only sleep
    // when nothing waits to be sent.
    stm32f4_usart_drain(board);
    if (STM32F4_TRANSMIT_BY_INTERRUPT || !hal_link_rings_sending(&board->link))
        stm32f4_wait_for_interrupt();
}
