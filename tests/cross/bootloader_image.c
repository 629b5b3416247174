// The Aseba bootloader image's interrupt handlers, which only the vector
// table reaches on the chip, kept for the size measure through a volatile
// table (scripts/cross-check.sh; registers: simulated_registers.c).

void _T1Interrupt(void);
void _U1RXInterrupt(void);
void _U1TXInterrupt(void);
void (*volatile const bootloader_handlers[])(void) = { _T1Interrupt,
                                                       _U1RXInterrupt,
                                                       _U1TXInterrupt };
