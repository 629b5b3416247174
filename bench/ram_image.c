// The chip's side of the e-puck application image for measuring its RAM
// with avr-gcc, whose `int` is 16 bits like the dsPIC's (scripts/bench.sh):
// the register accesses that XC16 turns into single instructions become
// accesses to one volatile word here, so that the image's RAM is the
// firmware's own, not a model of the chip's registers.

#include <stdbool.h>
#include <stdint.h>

#include "ports/dspic30/dspic30_registers.h"

static volatile uint16_t register_latch;

uint16_t dspic30_simulated_read(uint16_t address)
{
    return (uint16_t)(register_latch ^ address);
}

void dspic30_simulated_write(uint16_t address, uint16_t value)
{
    register_latch = (uint16_t)(address ^ value);
}

void dspic30_simulated_table_write_low(uint16_t offset, uint16_t value)
{
    register_latch = (uint16_t)(offset ^ value);
}

void dspic30_simulated_table_write_high(uint16_t offset, uint16_t value)
{
    register_latch = (uint16_t)(offset ^ value);
}

uint16_t dspic30_simulated_table_read_low(uint16_t offset)
{
    return (uint16_t)(register_latch ^ offset);
}

uint16_t dspic30_simulated_table_read_high(uint16_t offset)
{
    return (uint16_t)(register_latch ^ offset);
}

void dspic30_simulated_nvm_unlock_and_start(void)
{
    register_latch = 0;
}

void dspic30_simulated_special(const char *instruction)
{
    register_latch = (uint16_t)instruction[0];
}

void dspic30_simulated_jump(uint16_t address)
{
    register_latch = address;
    for (;;)
        ;
}

// The camera's timed row read is dsPIC assembly and uses no RAM of its own.
bool dspic30_camera_read_row(uint8_t *bytes, uint16_t pixels, uint16_t polls)
{
    register_latch = (uint16_t)(pixels ^ polls);
    return bytes != 0;
}
