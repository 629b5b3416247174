// USART1, the link to the hosts: 8N1 at STM32F4_LINK_BAUD on PA9/PA10.
// Received bytes go by interrupt into the board's receive ring; bytes to
// send wait in the transmit ring (hal/hal_link_rings.h), moved into the data
// register as it empties, from the transmit-empty interrupt on a real chip or by polling on
// QEMU (STM32F4_TRANSMIT_BY_INTERRUPT), so that sending never waits.

#include "stm32f4_chip.h"
#include "stm32f4_registers.h"

#define APB2_HZ                (STM32F4_HSE_HZ != 0 ? STM32F4_CPU_HZ / 2u : STM32F4_RESET_CLOCK_HZ)
#define PA9_PA10_MODE          (STM32F4_MODER_ALTERNATE << 18 | STM32F4_MODER_ALTERNATE << 20)
#define PA9_PA10_MODE_MASK     (0x3ul << 18 | 0x3ul << 20)
#define PA9_PA10_AF            (STM32F4_AF_USART1 << 4 | STM32F4_AF_USART1 << 8)
#define PA9_PA10_AF_MASK       (0xFul << 4 | 0xFul << 8)
#define STM32F4_RESET_CLOCK_HZ 16000000ul // the internal oscillator (RM0090 §6.2.2)

void stm32f4_usart_init(hal_board *board)
{
    hal_link_rings_init(&board->link);

    stm32f4_set_bits(STM32F4_RCC_AHB1ENR, STM32F4_AHB1ENR_GPIOAEN);
    stm32f4_set_bits(STM32F4_RCC_APB2ENR, STM32F4_APB2ENR_USART1EN);
    stm32f4_write(STM32F4_GPIOA_MODER,
                  (stm32f4_read(STM32F4_GPIOA_MODER) & ~PA9_PA10_MODE_MASK) | PA9_PA10_MODE);
    stm32f4_write(STM32F4_GPIOA_AFRH,
                  (stm32f4_read(STM32F4_GPIOA_AFRH) & ~PA9_PA10_AF_MASK) | PA9_PA10_AF);
    // Oversampling by 16: BRR holds the clock divided by the baud rate,
    // rounded (RM0090 §30.3.4).
    stm32f4_write(STM32F4_USART1_BRR, (APB2_HZ + STM32F4_LINK_BAUD / 2u) / STM32F4_LINK_BAUD);
    stm32f4_write(STM32F4_USART1_CR1,
                  STM32F4_USART_CR1_UE | STM32F4_USART_CR1_TE | STM32F4_USART_CR1_RE |
                    STM32F4_USART_CR1_RXNEIE);
    stm32f4_write_byte(STM32F4_NVIC_IPR0 + STM32F4_IRQ_USART1,
                       (uint8_t)(STM32F4_PRIORITY_USART1 << STM32F4_PRIORITY_SHIFT));
    stm32f4_write(STM32F4_NVIC_ISER0 + 4u * (STM32F4_IRQ_USART1 / 32u),
                  1ul << (STM32F4_IRQ_USART1 % 32u));
}

// Moves waiting bytes into the data register while it is empty; with
// interrupts, keeps the transmit-empty interrupt on exactly while bytes wait.
// Runs with the USART's interrupt held off.
static void fill_data_register(hal_board *board)
{
    uint8_t byte;

    while ((stm32f4_read(STM32F4_USART1_SR) & STM32F4_USART_SR_TXE) != 0 &&
           hal_link_rings_next_to_send(&board->link, &byte))
        stm32f4_write(STM32F4_USART1_DR, byte);
    if (STM32F4_TRANSMIT_BY_INTERRUPT) {
        if (hal_link_rings_sending(&board->link))
            stm32f4_set_bits(STM32F4_USART1_CR1, STM32F4_USART_CR1_TXEIE);
        else
            stm32f4_clear_bits(STM32F4_USART1_CR1, STM32F4_USART_CR1_TXEIE);
    }
}

void stm32f4_usart_drain(hal_board *board)
{
    hal_critical_state state = hal_critical_enter(board);
    fill_data_register(board);
    hal_critical_leave(board, state);
}

void stm32f4_on_usart1(hal_board *board)
{
    uint32_t status = stm32f4_read(STM32F4_USART1_SR);

    // Reading SR then DR clears RXNE and an overrun (RM0090 §30.6.1).
    while (status & (STM32F4_USART_SR_RXNE | STM32F4_USART_SR_ORE)) {
        uint8_t byte = (uint8_t)stm32f4_read(STM32F4_USART1_DR);
        if (status & STM32F4_USART_SR_ORE)
            board->link.receive_overruns++;
        hal_link_rings_received(&board->link, byte);
        status = stm32f4_read(STM32F4_USART1_SR);
    }
    if (STM32F4_TRANSMIT_BY_INTERRUPT)
        fill_data_register(board);
}

uint16_t hal_link_receive(hal_board *board, uint8_t *bytes, uint16_t capacity)
{
    return hal_link_rings_take(&board->link, bytes, capacity);
}

uint16_t hal_link_send_room(hal_board *board)
{
    return hal_link_rings_room(&board->link);
}

uint16_t hal_link_send(hal_board *board, const uint8_t *bytes, uint16_t count)
{
    count = hal_link_rings_queue(&board->link, bytes, count);
    stm32f4_usart_drain(board);
    return count;
}
