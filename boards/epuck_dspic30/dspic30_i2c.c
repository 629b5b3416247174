// The I2C master (§2.4) for the camera and extensions: each bus step is
// started by one I2CCON bit and polled until the module clears it, as the
// library's protocol layer does (it waits for the MI2C flag instead).

#include "epuck_dspic30_board.h"
#include "ports/dspic30/dspic30_registers.h"

#define I2C_READ_BIT 0x01u // 8-bit address + 1 = the read address

void dspic30_i2c_init(hal_board *board)
{
    (void)board;
    dspic30_write(DSPIC30_I2CCON, 0);
    dspic30_write(DSPIC30_I2CBRG, DSPIC30_I2C_BRG);
    dspic30_write(DSPIC30_I2CSTAT, 0);
    dspic30_write(DSPIC30_I2CCON, DSPIC30_I2CCON_I2CEN);
}

// Starts the bus step of `step` (an I2CCON bit) and waits until the module
// has done it; false on a timeout or a bus collision.
static bool do_step(uint16_t step)
{
    uint16_t attempts;

    dspic30_set_bits(DSPIC30_I2CCON, step);
    for (attempts = 0; attempts < DSPIC30_I2C_STEP_ATTEMPTS; attempts++) {
        if ((dspic30_read(DSPIC30_I2CCON) & step) == 0)
            return (dspic30_read(DSPIC30_I2CSTAT) & DSPIC30_I2CSTAT_BCL) == 0;
    }
    return false;
}

// Sends one byte and waits for the slave's acknowledge; false on a NACK.
static bool send_byte(uint8_t byte)
{
    uint16_t attempts;

    dspic30_write(DSPIC30_I2CTRN, byte);
    for (attempts = 0; attempts < DSPIC30_I2C_STEP_ATTEMPTS; attempts++) {
        uint16_t status = dspic30_read(DSPIC30_I2CSTAT);
        if ((status & (DSPIC30_I2CSTAT_TRSTAT | DSPIC30_I2CSTAT_TBF)) == 0)
            return (status &
                    (DSPIC30_I2CSTAT_ACKSTAT | DSPIC30_I2CSTAT_BCL | DSPIC30_I2CSTAT_IWCOL)) == 0;
    }
    return false;
}

// Ends a transaction with a stop condition; returns `ok`.
static bool finish(bool ok)
{
    if (!do_step(DSPIC30_I2CCON_PEN))
        ok = false;
    // Clear error flags so that the next transaction starts clean.
    dspic30_clear_bits(DSPIC30_I2CSTAT, DSPIC30_I2CSTAT_BCL | DSPIC30_I2CSTAT_IWCOL);
    return ok;
}

bool epuck_board_i2c_write(hal_board *board,
                           uint8_t device,
                           uint8_t reg,
                           const uint8_t *bytes,
                           uint16_t count)
{
    uint16_t i;

    (void)board;
    if (!do_step(DSPIC30_I2CCON_SEN))
        return finish(false);
    if (!send_byte(device) || !send_byte(reg))
        return finish(false);
    for (i = 0; i < count; i++) {
        if (!send_byte(bytes[i]))
            return finish(false);
    }
    return finish(true);
}

bool epuck_board_i2c_read(hal_board *board,
                          uint8_t device,
                          uint8_t reg,
                          uint8_t *bytes,
                          uint16_t count)
{
    uint16_t i;

    (void)board;
    if (!do_step(DSPIC30_I2CCON_SEN))
        return finish(false);
    if (!send_byte(device) || !send_byte(reg))
        return finish(false);
    if (!do_step(DSPIC30_I2CCON_RSEN) || !send_byte((uint8_t)(device | I2C_READ_BIT)))
        return finish(false);
    for (i = 0; i < count; i++) {
        if (!do_step(DSPIC30_I2CCON_RCEN))
            return finish(false);
        bytes[i] = (uint8_t)dspic30_read(DSPIC30_I2CRCV);
        // Acknowledge every byte but the last, which gets a NACK.
        if (i + 1u < count)
            dspic30_clear_bits(DSPIC30_I2CCON, DSPIC30_I2CCON_ACKDT);
        else
            dspic30_set_bits(DSPIC30_I2CCON, DSPIC30_I2CCON_ACKDT);
        if (!do_step(DSPIC30_I2CCON_ACKEN))
            return finish(false);
    }
    return finish(true);
}
