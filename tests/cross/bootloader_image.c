// The chip's side of the Aseba bootloader image, for measuring its size
// with avr-gcc and arm-none-eabi-gcc (scripts/cross-check.sh): the register
// accesses that XC16 turns into single instructions become accesses to a
// volatile array here, and the interrupt handlers, which only the vector
// table reaches on the chip, are kept through a volatile table.

#include <stdint.h>

#include "hal/dspic30/dspic30_registers.h"

#define REGISTER_WORDS 0x400u // SFR space: 2 KB
#define REGISTER_MASK  (REGISTER_WORDS - 1u)

static volatile uint16_t registers[REGISTER_WORDS];
static volatile uint16_t table_latch;

uint16_t dspic30_simulated_read(uint16_t address)
{
    return registers[(address / 2u) & REGISTER_MASK];
}

void dspic30_simulated_write(uint16_t address, uint16_t value)
{
    registers[(address / 2u) & REGISTER_MASK] = value;
}

void dspic30_simulated_table_write_low(uint16_t offset, uint16_t value)
{
    table_latch = (uint16_t)(offset ^ value);
}

void dspic30_simulated_table_write_high(uint16_t offset, uint16_t value)
{
    table_latch = (uint16_t)(offset ^ value);
}

uint16_t dspic30_simulated_table_read_low(uint16_t offset)
{
    return (uint16_t)(table_latch ^ offset);
}

uint16_t dspic30_simulated_table_read_high(uint16_t offset)
{
    return (uint16_t)(table_latch ^ offset);
}

void dspic30_simulated_nvm_unlock_and_start(void)
{
    table_latch = 0;
}

void dspic30_simulated_special(const char *instruction)
{
    table_latch = (uint16_t)instruction[0];
}

void dspic30_simulated_jump(uint16_t address)
{
    table_latch = address;
    for (;;)
        ;
}

void _T1Interrupt(void);
void _U1RXInterrupt(void);
void _U1TXInterrupt(void);
void (*volatile const bootloader_handlers[])(void) = { _T1Interrupt,
                                                       _U1RXInterrupt,
                                                       _U1TXInterrupt };
