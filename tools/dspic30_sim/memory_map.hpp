// The dsPIC30F6014A's address spaces as the simulator models them: program
// memory (PC addresses, 2 per 24-bit word), data memory (byte addresses)
// and the special function registers (hardware fact sheet
// ../shared/hardware/epuck1.md §1.1, §1.8, §2; DS70157).

#pragma once

#include <cstdint>

namespace aseba::dspic30
{

// --- program space (PC addresses) ------------------------------------------
inline constexpr uint32_t flash_end = 0x018000; // 48 K instruction words from 0
inline constexpr uint32_t flash_words = flash_end / 2;
inline constexpr uint32_t pc_mask = 0x7FFFFE;     // the PC is 23 bits, bit 0 always 0
inline constexpr uint32_t ivt_base = 0x000004;    // vector k at ivt_base + 2k
inline constexpr uint32_t aivt_base = 0x000084;   // alternate table (INTCON2.ALTIVT)
inline constexpr uint32_t eeprom_base = 0x7FF000; // data EEPROM, 2048 16-bit words
inline constexpr uint32_t eeprom_end = 0x800000;
inline constexpr uint32_t eeprom_words = (eeprom_end - eeprom_base) / 2;
inline constexpr uint32_t config_base = 0xF80000; // FOSC, FWDT, FBORPOR, FBS, FSS, FGS, FICD
inline constexpr uint32_t config_end = 0xF80010;
inline constexpr uint32_t config_words = (config_end - config_base) / 2;
inline constexpr uint32_t device_id_address = 0xFF0000;
inline constexpr uint32_t device_revision_address = 0xFF0002;
inline constexpr uint16_t device_id = 0x02C3;       // dsPIC30F6014A (FPS Table 10-1)
inline constexpr uint16_t device_revision = 0x1040; // rev B0 silicon
inline constexpr uint32_t erased_word = 0xFFFFFF;
inline constexpr uint32_t flash_row_words = 32; // erase and write unit
inline constexpr uint32_t eeprom_row_words = 16;
inline constexpr uint32_t fosc_address = 0xF80000; // oscillator configuration word
// FOSC.FCKSM<1:0>: both 0 = clock switching and the fail-safe clock monitor
// on (⚠ from the dsPIC30F data sheets' FCKSM table, DS70138G §20.2.7).
inline constexpr uint16_t fosc_fcksm = 3u << 14;
inline constexpr uint32_t fwdt_address = 0xF80002; // watchdog configuration word
inline constexpr uint16_t fwdt_enable = 1u << 15;  // FWDT.FWDTEN
// The watchdog's nominal 2 ms period before its prescalers, in cycles.
inline constexpr uint64_t watchdog_base_cycles = 29491;

// --- data space (byte addresses) -------------------------------------------
inline constexpr uint16_t sfr_end = 0x0800;   // SFRs below, RAM above
inline constexpr uint16_t ram_start = 0x0800; // X RAM, then Y RAM
inline constexpr uint16_t y_ram_start = 0x1800;
inline constexpr uint16_t ram_end = 0x2800; // 8 KB of RAM; unimplemented above
inline constexpr uint16_t ram_size = ram_end - ram_start;
inline constexpr uint32_t psv_window = 0x8000;    // EA<15> = 1: program space when CORCON.PSV
inline constexpr uint16_t near_data_end = 0x2000; // reach of the file-register forms

// --- core SFRs -------------------------------------------------------------
namespace sfr
{
inline constexpr uint16_t WREG0 = 0x0000; // W0..W15 at 0x0000..0x001E
inline constexpr uint16_t WREG_END = 0x0020;
inline constexpr uint16_t SPLIM = 0x0020;
inline constexpr uint16_t ACCAL = 0x0022;
inline constexpr uint16_t ACCAH = 0x0024;
inline constexpr uint16_t ACCAU = 0x0026;
inline constexpr uint16_t ACCBL = 0x0028;
inline constexpr uint16_t ACCBH = 0x002A;
inline constexpr uint16_t ACCBU = 0x002C;
inline constexpr uint16_t PCL = 0x002E;
inline constexpr uint16_t PCH = 0x0030;
inline constexpr uint16_t TBLPAG = 0x0032;
inline constexpr uint16_t PSVPAG = 0x0034;
inline constexpr uint16_t RCOUNT = 0x0036;
inline constexpr uint16_t DCOUNT = 0x0038;
inline constexpr uint16_t DOSTARTL = 0x003A;
inline constexpr uint16_t DOSTARTH = 0x003C;
inline constexpr uint16_t DOENDL = 0x003E;
inline constexpr uint16_t DOENDH = 0x0040;
inline constexpr uint16_t SR = 0x0042;
inline constexpr uint16_t CORCON = 0x0044;
inline constexpr uint16_t MODCON = 0x0046;
inline constexpr uint16_t XMODSRT = 0x0048;
inline constexpr uint16_t XMODEND = 0x004A;
inline constexpr uint16_t YMODSRT = 0x004C;
inline constexpr uint16_t YMODEND = 0x004E;
inline constexpr uint16_t XBREV = 0x0050;
inline constexpr uint16_t DISICNT = 0x0052;
inline constexpr uint16_t CORE_END = 0x0054;

inline constexpr uint16_t INTCON1 = 0x0080;
inline constexpr uint16_t INTCON2 = 0x0082;
inline constexpr uint16_t IFS0 = 0x0084; // IFS0..IFS2
inline constexpr uint16_t IEC0 = 0x008C; // IEC0..IEC2
inline constexpr uint16_t IPC0 = 0x0094; // IPC0..IPC10
inline constexpr uint16_t IPC_END = 0x00AA;
inline constexpr uint16_t INTTREG = 0x00B0;

inline constexpr uint16_t U1MODE = 0x020C;
inline constexpr uint16_t U1STA = 0x020E;
inline constexpr uint16_t U1TXREG = 0x0210;
inline constexpr uint16_t U1RXREG = 0x0212;
inline constexpr uint16_t U1BRG = 0x0214;
inline constexpr uint16_t U2MODE = 0x0216; // U2STA ... U2BRG follow as for UART1

inline constexpr uint16_t RCON = 0x0740;
inline constexpr uint16_t OSCCON = 0x0742;
inline constexpr uint16_t NVMCON = 0x0760;
inline constexpr uint16_t NVMADR = 0x0762;
inline constexpr uint16_t NVMADRU = 0x0764;
inline constexpr uint16_t NVMKEY = 0x0766;
} // namespace sfr

// --- SR bits -----------------------------------------------------------------
namespace sr
{
inline constexpr uint16_t C = 1u << 0;
inline constexpr uint16_t Z = 1u << 1;
inline constexpr uint16_t OV = 1u << 2;
inline constexpr uint16_t N = 1u << 3;
inline constexpr uint16_t RA = 1u << 4;
inline constexpr int IPL_SHIFT = 5;
inline constexpr uint16_t IPL = 7u << IPL_SHIFT;
inline constexpr uint16_t DC = 1u << 8;
inline constexpr uint16_t DA = 1u << 9;
inline constexpr uint16_t SAB = 1u << 10;
inline constexpr uint16_t OAB = 1u << 11;
inline constexpr uint16_t SB = 1u << 12;
inline constexpr uint16_t SA = 1u << 13;
inline constexpr uint16_t OB = 1u << 14;
inline constexpr uint16_t OA = 1u << 15;
inline constexpr uint16_t ALU_FLAGS = C | Z | OV | N | DC; // what PUSH.S/POP.S shadow
} // namespace sr

// --- CORCON bits ---------------------------------------------------------------
namespace corcon
{
inline constexpr uint16_t IF = 1u << 0;   // integer (1) or fractional multiplies
inline constexpr uint16_t RND = 1u << 1;  // biased (1) or convergent rounding
inline constexpr uint16_t PSV = 1u << 2;  // program space visible at 0x8000
inline constexpr uint16_t IPL3 = 1u << 3; // CPU priority bit 3 (a trap is being serviced)
inline constexpr uint16_t ACCSAT = 1u << 4;
inline constexpr uint16_t SATDW = 1u << 5;
inline constexpr uint16_t SATB = 1u << 6;
inline constexpr uint16_t SATA = 1u << 7;
inline constexpr int DL_SHIFT = 8;
inline constexpr uint16_t DL = 7u << DL_SHIFT;
inline constexpr uint16_t EDT = 1u << 11;
inline constexpr uint16_t US = 1u << 12;
inline constexpr uint16_t RESET_VALUE = SATDW;
inline constexpr uint16_t WRITABLE = IF | RND | PSV | ACCSAT | SATDW | SATB | SATA | US;
} // namespace corcon

// --- INTCON1 / INTCON2 / RCON bits ---------------------------------------------
namespace osccon
{
inline constexpr uint16_t OSWEN = 1u << 0; // a clock switch requested
inline constexpr uint16_t CF = 1u << 3;    // the clock monitor saw a failure
} // namespace osccon

namespace intcon1
{
inline constexpr uint16_t OSCFAIL = 1u << 1;
inline constexpr uint16_t STKERR = 1u << 2;
inline constexpr uint16_t ADDRERR = 1u << 3;
inline constexpr uint16_t MATHERR = 1u << 4;
inline constexpr uint16_t COVTE = 1u << 8;
inline constexpr uint16_t OVBTE = 1u << 9;
inline constexpr uint16_t OVATE = 1u << 10;
inline constexpr uint16_t NSTDIS = 1u << 15;
} // namespace intcon1

namespace intcon2
{
inline constexpr uint16_t DISI = 1u << 14;
inline constexpr uint16_t ALTIVT = 1u << 15;
} // namespace intcon2

namespace rcon
{
inline constexpr uint16_t POR = 1u << 0;
inline constexpr uint16_t SLEEP = 1u << 3;
inline constexpr uint16_t IDLE = 1u << 2;
inline constexpr uint16_t WDTO = 1u << 4;
inline constexpr uint16_t SWDTEN = 1u << 5;
inline constexpr uint16_t SWR = 1u << 6;
inline constexpr uint16_t TRAPR = 1u << 15;
} // namespace rcon

// --- clock -----------------------------------------------------------------------
inline constexpr double instruction_clock_hz = 14745600.0; // the e-puck's FCY (7.3728 MHz x 8 / 4)

} // namespace aseba::dspic30
