// The dsPIC's registers for measuring the e-puck images' sizes with
// avr-gcc and arm-none-eabi-gcc (scripts/cross-check.sh): the register
// accesses that XC16 turns into single instructions become accesses to a
// volatile array here; each image's file keeps its interrupt handlers, which
// only the vector table reaches on the chip.

#include <stdint.h>

#include "ports/dspic30/dspic30_registers.h"

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
