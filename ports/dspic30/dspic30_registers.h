// The one door to the dsPIC30F6014A's special function registers.
//
// The HAL names each SFR by its data-space address (hardware §1.8, §2) and
// reaches it only through the small functions at the end of this file. The
// chip build maps them onto the real addresses and XC16's builtins; a test
// build that defines DSPIC30_SIMULATED_REGISTERS maps them onto a simulated
// register file that the test provides (functions dspic30_simulated_*), so
// every ports/dspic30 file also runs on a PC. This is the only #ifdef of the
// port.

#ifndef DSPIC30_REGISTERS_H
#define DSPIC30_REGISTERS_H

#include <stdint.h>

// --- core and system (§1.8) -------------------------------------------------
#define DSPIC30_TBLPAG  0x0032u
#define DSPIC30_SR      0x0042u
#define DSPIC30_CORCON  0x0044u
#define DSPIC30_INTCON1 0x0080u
#define DSPIC30_INTCON2 0x0082u
#define DSPIC30_RCON    0x0740u
#define DSPIC30_OSCCON  0x0742u
#define DSPIC30_NVMCON  0x0760u
#define DSPIC30_NVMADR  0x0762u
#define DSPIC30_NVMADRU 0x0764u
#define DSPIC30_NVMKEY  0x0766u

#define DSPIC30_SR_IPL_MASK       0x00E0u // bits 7:5
#define DSPIC30_SR_IPL_SHIFT      5u
#define DSPIC30_INTCON1_NSTDIS    0x8000u
#define DSPIC30_INTCON2_INT0EP    0x0001u // 1 = falling edge
#define DSPIC30_INTCON2_ALTIVT    0x8000u
#define DSPIC30_RCON_POR          0x0001u
#define DSPIC30_OSCCON_LOCK       0x0020u
#define DSPIC30_OSCCON_COSC_MASK  0x7000u
#define DSPIC30_OSCCON_COSC_SHIFT 12u
#define DSPIC30_NVMCON_WR         0x8000u
#define DSPIC30_NVMCON_WRERR      0x2000u

// --- interrupt controller (§1.7, §2.6) --------------------------------------------
#define DSPIC30_IFS0 0x0084u
#define DSPIC30_IFS1 0x0086u
#define DSPIC30_IFS2 0x0088u
#define DSPIC30_IEC0 0x008Cu
#define DSPIC30_IEC1 0x008Eu
#define DSPIC30_IEC2 0x0090u
#define DSPIC30_IPC0 0x0094u
#define DSPIC30_IPC1 0x0096u
#define DSPIC30_IPC2 0x0098u
#define DSPIC30_IPC3 0x009Au
#define DSPIC30_IPC5 0x009Eu

// Flag and enable bits: IFS0/IEC0.
#define DSPIC30_IRQ0_INT0 0x0001u
#define DSPIC30_IRQ0_T1   0x0008u
#define DSPIC30_IRQ0_T2   0x0040u
#define DSPIC30_IRQ0_T3   0x0080u
#define DSPIC30_IRQ0_U1RX 0x0200u
#define DSPIC30_IRQ0_U1TX 0x0400u
#define DSPIC30_IRQ0_ADC  0x0800u
#define DSPIC30_IRQ0_MI2C 0x4000u
// IFS1/IEC1.
#define DSPIC30_IRQ1_T4 0x0020u
#define DSPIC30_IRQ1_T5 0x0040u

// Priority fields: register and shift of each source's 3-bit field.
#define DSPIC30_PRIORITY_FIELD_MASK 0x7u
#define DSPIC30_IPC_INT0            DSPIC30_IPC0
#define DSPIC30_SHIFT_INT0          0u
#define DSPIC30_IPC_T1              DSPIC30_IPC0
#define DSPIC30_SHIFT_T1            12u
#define DSPIC30_IPC_T2              DSPIC30_IPC1
#define DSPIC30_SHIFT_T2            8u
#define DSPIC30_IPC_T3              DSPIC30_IPC1
#define DSPIC30_SHIFT_T3            12u
#define DSPIC30_IPC_U1RX            DSPIC30_IPC2
#define DSPIC30_SHIFT_U1RX          4u
#define DSPIC30_IPC_U1TX            DSPIC30_IPC2
#define DSPIC30_SHIFT_U1TX          8u
#define DSPIC30_IPC_ADC             DSPIC30_IPC2
#define DSPIC30_SHIFT_ADC           12u
#define DSPIC30_IPC_T4              DSPIC30_IPC5
#define DSPIC30_SHIFT_T4            4u
#define DSPIC30_IPC_T5              DSPIC30_IPC5
#define DSPIC30_SHIFT_T5            8u

// --- timers (§2.2) ---------------------------------------------------------------------
#define DSPIC30_TMR1  0x0100u
#define DSPIC30_PR1   0x0102u
#define DSPIC30_T1CON 0x0104u
#define DSPIC30_TMR2  0x0106u
#define DSPIC30_TMR3  0x010Au
#define DSPIC30_PR2   0x010Cu
#define DSPIC30_PR3   0x010Eu
#define DSPIC30_T2CON 0x0110u
#define DSPIC30_T3CON 0x0112u
#define DSPIC30_TMR4  0x0114u
#define DSPIC30_TMR5  0x0118u
#define DSPIC30_PR4   0x011Au
#define DSPIC30_PR5   0x011Cu
#define DSPIC30_T4CON 0x011Eu
#define DSPIC30_T5CON 0x0120u

#define DSPIC30_TCON_TON         0x8000u
#define DSPIC30_TCON_TCKPS_SHIFT 4u // 00 = 1:1, 01 = 1:8, 10 = 1:64, 11 = 1:256
#define DSPIC30_TCON_T32         0x0008u
#define DSPIC30_TCON_TCS         0x0002u

// --- UART1 (§2.1) ------------------------------------------------------------------------
#define DSPIC30_U1MODE  0x020Cu
#define DSPIC30_U1STA   0x020Eu
#define DSPIC30_U1TXREG 0x0210u
#define DSPIC30_U1RXREG 0x0212u
#define DSPIC30_U1BRG   0x0214u

#define DSPIC30_UMODE_UARTEN      0x8000u
#define DSPIC30_UMODE_ALTIO       0x0400u
#define DSPIC30_USTA_UTXISEL      0x8000u
#define DSPIC30_USTA_UTXEN        0x0400u
#define DSPIC30_USTA_UTXBF        0x0200u
#define DSPIC30_USTA_TRMT         0x0100u
#define DSPIC30_USTA_URXISEL_MASK 0x00C0u
#define DSPIC30_USTA_PERR         0x0008u
#define DSPIC30_USTA_FERR         0x0004u
#define DSPIC30_USTA_OERR         0x0002u
#define DSPIC30_USTA_URXDA        0x0001u

// --- I2C (§2.4) ----------------------------------------------------------------------------
#define DSPIC30_I2CRCV  0x0200u
#define DSPIC30_I2CTRN  0x0202u
#define DSPIC30_I2CBRG  0x0204u
#define DSPIC30_I2CCON  0x0206u
#define DSPIC30_I2CSTAT 0x0208u

#define DSPIC30_I2CCON_I2CEN 0x8000u
#define DSPIC30_I2CCON_ACKDT 0x0020u // 1 = send NACK
#define DSPIC30_I2CCON_ACKEN 0x0010u
#define DSPIC30_I2CCON_RCEN  0x0008u
#define DSPIC30_I2CCON_PEN   0x0004u
#define DSPIC30_I2CCON_RSEN  0x0002u
#define DSPIC30_I2CCON_SEN   0x0001u
#define DSPIC30_I2CCON_STEPS                                                                       \
    (DSPIC30_I2CCON_ACKEN | DSPIC30_I2CCON_RCEN | DSPIC30_I2CCON_PEN | DSPIC30_I2CCON_RSEN |       \
     DSPIC30_I2CCON_SEN)
#define DSPIC30_I2CSTAT_ACKSTAT 0x8000u // 1 = NACK received
#define DSPIC30_I2CSTAT_TRSTAT  0x4000u
#define DSPIC30_I2CSTAT_BCL     0x0400u
#define DSPIC30_I2CSTAT_IWCOL   0x0080u
#define DSPIC30_I2CSTAT_RBF     0x0002u
#define DSPIC30_I2CSTAT_TBF     0x0001u

// --- ADC (§2.3) -----------------------------------------------------------------------------
#define DSPIC30_ADCBUF0 0x0280u
#define DSPIC30_ADCON1  0x02A0u
#define DSPIC30_ADCON2  0x02A2u
#define DSPIC30_ADCON3  0x02A4u
#define DSPIC30_ADCHS   0x02A6u
#define DSPIC30_ADPCFG  0x02A8u
#define DSPIC30_ADCSSL  0x02AAu

#define DSPIC30_ADCON1_ADON       0x8000u
#define DSPIC30_ADCON1_SSRC_AUTO  0x00E0u // SSRC = 111: internal counter ends sampling
#define DSPIC30_ADCON1_ASAM       0x0004u
#define DSPIC30_ADCON1_SAMP       0x0002u
#define DSPIC30_ADCON1_DONE       0x0001u
#define DSPIC30_ADCON2_CSCNA      0x0400u
#define DSPIC30_ADCON2_SMPI_SHIFT 2u
#define DSPIC30_ADCON3_SAMC_SHIFT 8u
#define DSPIC30_ADCON3_ADCS_MASK  0x003Fu

// --- I/O ports (§2.5): TRIS, PORT and LAT of each port are consecutive ------
#define DSPIC30_TRISA       0x02C0u
#define DSPIC30_TRISB       0x02C6u
#define DSPIC30_TRISC       0x02CCu
#define DSPIC30_TRISD       0x02D2u
#define DSPIC30_TRISF       0x02DEu
#define DSPIC30_TRISG       0x02E4u
#define DSPIC30_PORT_OFFSET 2u // PORTx = TRISx + 2
#define DSPIC30_LAT_OFFSET  4u // LATx = TRISx + 4
#define DSPIC30_PORTC       (DSPIC30_TRISC + DSPIC30_PORT_OFFSET)
#define DSPIC30_PORTD       (DSPIC30_TRISD + DSPIC30_PORT_OFFSET)

// --- access -----------------------------------------------------------------------------------
#ifdef DSPIC30_SIMULATED_REGISTERS

// Provided by the test: the simulated chip.
uint16_t dspic30_simulated_read(uint16_t address);
void dspic30_simulated_write(uint16_t address, uint16_t value);
void dspic30_simulated_write_byte(uint16_t address, uint8_t value);
void dspic30_simulated_table_write_low(uint16_t offset, uint16_t value);
void dspic30_simulated_table_write_high(uint16_t offset, uint16_t value);
uint16_t dspic30_simulated_table_read_low(uint16_t offset);
uint16_t dspic30_simulated_table_read_high(uint16_t offset);
void dspic30_simulated_nvm_unlock_and_start(void);
void dspic30_simulated_special(const char *instruction);
void dspic30_simulated_jump(uint16_t address);

static inline uint16_t dspic30_read(uint16_t address)
{
    return dspic30_simulated_read(address);
}
static inline void dspic30_write(uint16_t address, uint16_t value)
{
    dspic30_simulated_write(address, value);
}
static inline void dspic30_write_byte(uint16_t address, uint8_t value)
{
    dspic30_simulated_write_byte(address, value);
}
static inline void dspic30_table_write_low(uint16_t offset, uint16_t value)
{
    dspic30_simulated_table_write_low(offset, value);
}
static inline void dspic30_table_write_high(uint16_t offset, uint16_t value)
{
    dspic30_simulated_table_write_high(offset, value);
}
static inline uint16_t dspic30_table_read_low(uint16_t offset)
{
    return dspic30_simulated_table_read_low(offset);
}
static inline uint16_t dspic30_table_read_high(uint16_t offset)
{
    return dspic30_simulated_table_read_high(offset);
}
static inline void dspic30_nvm_unlock_and_start(void)
{
    dspic30_simulated_nvm_unlock_and_start();
}
static inline void dspic30_nop(void)
{
    dspic30_simulated_special("nop");
}
static inline void dspic30_idle_instruction(void)
{
    dspic30_simulated_special("pwrsav #1");
}
static inline void dspic30_reset_instruction(void)
{
    dspic30_simulated_special("reset");
}

static inline void dspic30_jump(uint16_t address)
{
    dspic30_simulated_jump(address);
}

// Interrupt handlers and configuration words are plain on the host.
#define DSPIC30_INTERRUPT
#define DSPIC30_CONFIG_WORD(name, value) const uint16_t dspic30_config_##name = (value)

#else // the chip, compiled by XC16 or the GPL pic30-elf GCC

// Each accessor is one or two instructions: always inlined, since -Os
// otherwise keeps one out-of-line copy per file and calls it.
#define DSPIC30_ACCESSOR  static inline __attribute__((always_inline))

DSPIC30_ACCESSOR uint16_t dspic30_read(uint16_t address)
{
    return *(volatile uint16_t *)address;
}
DSPIC30_ACCESSOR void dspic30_write(uint16_t address, uint16_t value)
{
    *(volatile uint16_t *)address = value;
}
// One byte of data space (RAM), at any address.
DSPIC30_ACCESSOR void dspic30_write_byte(uint16_t address, uint8_t value)
{
    *(volatile uint8_t *)address = value;
}
// TBLWTL/TBLWTH/TBLRDL/TBLRDH at TBLPAG:offset.
DSPIC30_ACCESSOR void dspic30_table_write_low(uint16_t offset, uint16_t value)
{
    __builtin_tblwtl(offset, value);
}
DSPIC30_ACCESSOR void dspic30_table_write_high(uint16_t offset, uint16_t value)
{
    __builtin_tblwth(offset, value);
}
DSPIC30_ACCESSOR uint16_t dspic30_table_read_low(uint16_t offset)
{
    return __builtin_tblrdl(offset);
}
DSPIC30_ACCESSOR uint16_t dspic30_table_read_high(uint16_t offset)
{
    return __builtin_tblrdh(offset);
}
// DISI #5, 0x55 then 0xAA into NVMKEY, set NVMCON.WR, two NOPs: XC16's
// builtin emits exactly the unlock sequence of §1.3.
DSPIC30_ACCESSOR void dspic30_nvm_unlock_and_start(void)
{
    __builtin_write_NVM();
}
DSPIC30_ACCESSOR void dspic30_nop(void)
{
    __builtin_nop();
}
DSPIC30_ACCESSOR void dspic30_idle_instruction(void)
{
    __asm__ volatile("pwrsav #1");
}
DSPIC30_ACCESSOR void dspic30_reset_instruction(void)
{
    __asm__ volatile("reset");
}

// Continues at PC `address` (below 0x10000), never to return. XC16's
// function pointers are 16 bits (fact sheet §5.2, [XC16] C guide "Function
// Pointers"), so a pointer holding `address` calls it directly, without a
// handle. The return address this pushes is dropped when the code there
// (an application's start-up) sets the stack pointer again.
// ⚠ Not yet run on a robot.
typedef void (*dspic30_code_address)(void);
static inline void dspic30_jump(uint16_t address)
{
    ((dspic30_code_address)address)();
}

// auto_psv: handlers may read constants through the PSV window (§5.3).
#define DSPIC30_INTERRUPT __attribute__((interrupt, auto_psv))
// A configuration word in its own section, placed by linker/epuck-app.gld.
#define DSPIC30_CONFIG_WORD(name, value)                                                           \
    unsigned int __attribute__((space(prog), section("__" #name ".sec"))) dspic30_config_##name =  \
      (value)

#endif

// Read-modify-write helpers on top of the two accessors.
static inline void dspic30_set_bits(uint16_t address, uint16_t mask)
{
    dspic30_write(address, (uint16_t)(dspic30_read(address) | mask));
}
static inline void dspic30_clear_bits(uint16_t address, uint16_t mask)
{
    dspic30_write(address, (uint16_t)(dspic30_read(address) & (uint16_t)~mask));
}
// Sets the 3-bit priority field at `shift` of interrupt priority register `ipc`.
static inline void dspic30_set_priority(uint16_t ipc, uint16_t shift, uint16_t priority)
{
    uint16_t value = dspic30_read(ipc);
    value = (uint16_t)(value & ~(uint16_t)(DSPIC30_PRIORITY_FIELD_MASK << shift));
    dspic30_write(ipc, (uint16_t)(value | (uint16_t)(priority << shift)));
}

#endif
