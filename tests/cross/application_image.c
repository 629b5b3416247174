// The e-puck application image's interrupt handlers, which only the vector
// table reaches on the chip, kept for the size measure through a volatile
// table (scripts/cross-check.sh; registers: simulated_registers.c).

void _T1Interrupt(void);
void _U1RXInterrupt(void);
void _U1TXInterrupt(void);
void _T2Interrupt(void);
void _T3Interrupt(void);
void _T4Interrupt(void);
void _T5Interrupt(void);
void _ADCInterrupt(void);
void _INT0Interrupt(void);
void (*volatile const application_handlers[])(void) = {
    _T1Interrupt, _U1RXInterrupt, _U1TXInterrupt, _T2Interrupt,   _T3Interrupt,
    _T4Interrupt, _T5Interrupt,   _ADCInterrupt,  _INT0Interrupt,
};

// The camera's timed row read is dsPIC assembly (dspic30_camera_row.c); on
// the proxies' chips a loop of about its size stands for it.
#include <stdbool.h>
#include <stdint.h>

bool dspic30_camera_read_row(uint8_t *bytes, uint16_t pixels, uint16_t polls);
bool dspic30_camera_read_row(uint8_t *bytes, uint16_t pixels, uint16_t polls)
{
    volatile uint16_t *const port = (volatile uint16_t *)bytes;
    while (polls-- > 0 && (*port & 8u) == 0)
        ;
    for (; pixels > 0; pixels--) {
        *bytes++ = (uint8_t)(*port >> 8);
        *bytes++ = (uint8_t)(*port >> 8);
    }
    return polls != 0;
}
