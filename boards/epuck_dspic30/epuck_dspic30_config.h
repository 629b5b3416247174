// The e-puck target, the e-puck on its dsPIC30F6014A: every size and switch
// of the dsPIC build in one place, with the chip in numbers: clock, memory
// sizes, the values the port and the board write into registers, and every
// unverified (⚠) fact they rely on, each behind one name. Sections refer to
// the hardware fact sheet (hardware/epuck1.md). The dsPIC build names this
// file as TARGET_CONFIG; only constants, so that the host tests can compile
// the port and the board against it too.

#ifndef EPUCK_DSPIC30_CONFIG_H
#define EPUCK_DSPIC30_CONFIG_H

#include <stdint.h>

// The flash (the chip's geometry) and how the e-puck's images divide it:
// the bytecode store's slots among them.
#include "robots/epuck/epuck_flash_layout.h"

// --- the robot and the node's memory ------------------------------------------------
// The robot package the firmware runs (firmware/firmware.h).
#define ROBOT_HEADER "robots/epuck/epuck_robot.h"
// The VM's memories, as the node describes them to hosts: bytecode, stack,
// and the variable words after the robot's named ones (user variables and
// temporaries).
#define FIRMWARE_BYTECODE_WORDS      1024
#define FIRMWARE_STACK_WORDS         32
#define FIRMWARE_FREE_VARIABLE_WORDS 256
// The settings record (store/bytecode_store.h): the node id, then words
// for calibration (they fit one flash row, the settings slot).
#define STORE_SETTINGS_WORDS 44u

// --- the portable layers' switches (vm/vm_config.h, vm/node_config.h) -------------
// Switch dispatch: XC16's support of `&&label` is unverified. A build of
// the VM both ways (scripts/bench.sh) gives its own.
#ifndef VM_USE_COMPUTED_GOTO
#define VM_USE_COMPUTED_GOTO 0
#endif
#define VM_MAX_NATIVE_ARGUMENTS    16   // stack words of the widest native
#define NODE_INTER_BYTE_TIMEOUT_MS 500  // as GCtronic's e-puck firmware
#define NODE_STEP_BUDGET           1000 // as upstream's microcontroller glue
#define NODE_TRANSMIT_CHUNK        32   // one piece of a frame on its way out
// One description frame per poll, between the received frames: the whole
// of it (0.17 s) let the receive ring overflow (docs/dspic30-sim.md).
#define NODE_DESCRIPTION_FRAMES_PER_POLL 1

// --- clock (§1.6) ---------------------------------------------------------------
#define DSPIC30_CRYSTAL_HZ       7372800ul
#define DSPIC30_PLL_FACTOR       8ul
#define DSPIC30_CLOCKS_PER_CYCLE 4ul // FCY = Fosc / 4
#define DSPIC30_FCY_HZ           (DSPIC30_CRYSTAL_HZ * DSPIC30_PLL_FACTOR / DSPIC30_CLOCKS_PER_CYCLE)
// FCY in cycles per microsecond as a fraction in lowest terms (14.7456 =
// 9216 / 625), so that a timer's period takes one 32-bit division
// (dspic30_timers.c checks it against DSPIC30_FCY_HZ).
#define DSPIC30_CYCLES_PER_US_NUMERATOR   9216ul
#define DSPIC30_CYCLES_PER_US_DENOMINATOR 625ul

// FOSC configuration word (§1.5): FCKSM = 10 (clock switching and fail-safe
// monitor off), FOS = 111 (primary oscillator), FPR = 00110 (XT with PLL x8).
#define DSPIC30_FOSC_FCKSM_OFF   0x8000u // bits 15:14 = 10
#define DSPIC30_FOSC_FOS_PRIMARY 0x0700u // bits 10:8 = 111
#define DSPIC30_FOSC_FPR_XT_PLL8 0x0006u // bits 4:0 = 00110
#define DSPIC30_FOSC_UNUSED_BITS 0x38E0u // unimplemented bits, programmed 1
#define DSPIC30_FOSC_VALUE                                                                         \
    (DSPIC30_FOSC_FCKSM_OFF | DSPIC30_FOSC_FOS_PRIMARY | DSPIC30_FOSC_FPR_XT_PLL8 |                \
     DSPIC30_FOSC_UNUSED_BITS)
#define DSPIC30_FWDT_VALUE    0x7FFFu // watchdog off (FWDTEN = 0)
#define DSPIC30_FBORPOR_VALUE 0xFF7Fu // brown-out reset off, MCLR on, 64 ms power-up timer
#define DSPIC30_FGS_VALUE     0xFFFFu // no code protection

// Loop iterations the start-up waits for the PLL to lock (OSCCON.LOCK)
// before going on anyway; each is a few cycles, so this is about 10 ms.
#define DSPIC30_PLL_LOCK_ATTEMPTS 30000u

// --- the millisecond clock: Timer1 interrupts 1024 times a second --------------
// 1 ms is 14745.6 cycles, not a whole number; 1/1024 s is exactly 14400.
#define DSPIC30_CLOCK_TICK_HZ 1024ul

// --- UART1, the Bluetooth link (§2.1, §3.11, §6.5) -------------------------------
#define DSPIC30_LINK_BAUD           115200ul
#define DSPIC30_UART_CLOCKS_PER_BIT 16ul // UxBRG = FCY / (16 × baud) − 1
#define DSPIC30_UART_BRG(baud)                                                                     \
    ((uint16_t)(DSPIC30_FCY_HZ / (DSPIC30_UART_CLOCKS_PER_BIT * (baud)) - 1ul))
// The link's rings (hal.h). Transmission: one of the node's 32-byte pieces
// (NODE_TRANSMIT_CHUNK): the main loop waits while a longer frame drains
// (45 ms for the largest at 115200 baud), in order; a whole frame would
// cost 512 bytes of the 8 KB for no byte more on the wire. Reception: one
// largest frame (6-byte header and 516 bytes of payload, protocol.md §2),
// what arrives at 115200 baud while the main loop sends one: the main loop
// moves bytes on into the node's frame meanwhile, so the ring fills only
// while the node holds a whole frame (the GCtronic port's 1,024 bytes held
// two).
#define HAL_LINK_RECEIVE_CAPACITY  522u
#define HAL_LINK_TRANSMIT_CAPACITY 32u

// --- interrupt priorities (§1.7; 7 is highest, 0 disables) ------------------------
// The ADC scan comes 16384 times a second and must not be late; the UART's
// 4-byte FIFO fills in 350 µs; motor and agenda timers tolerate some jitter;
// the millisecond clock least of all matters.
#define DSPIC30_PRIORITY_ADC    6u
#define DSPIC30_PRIORITY_UART1  5u // as the GCtronic library
#define DSPIC30_PRIORITY_TIMERS 4u
#define DSPIC30_PRIORITY_REMOTE 4u
// Timer4 counting the camera's rows: its interrupt waits for a row to end
// (dspic30_camera.c), so below UART1 and the timers, which come in
// meanwhile (the remote's samples have a third of a millisecond to spare).
#define DSPIC30_PRIORITY_CAMERA 3u
#define DSPIC30_PRIORITY_CLOCK  3u
#define DSPIC30_PRIORITY_ALL    7u // the CPU priority that masks every source

// --- timers (§2.2) -----------------------------------------------------------------
// ⚠ The period formula (PR + 1) × prescale × Tcy is recalled from the data
// sheet, not read (§2.2, §7): every period computation uses this one offset.
#define DSPIC30_TIMER_PERIOD_OFFSET 1u
// The e-puck's board asks for 20 µs to 1 s (EPUCK_TIMER_*_PERIOD_US):
// 65536 × 256 × Tcy is 1.14 s, checked in dspic30_timers.c.

// --- ADC (§2.3) ------------------------------------------------------------------------
// Scans interrupt at EPUCK_ADC_SCAN_RATE_HZ (16384 Hz) like the library's
// advanced driver: a scan of n channels takes n × (SAMC + 14) Tad with Tad =
// Tcy × (ADCS + 1) / 2, so ADCS + 1 = 2 × cycles-per-scan / (n × (SAMC + 14)):
// 2 to 6 channels (EPUCK_ADC_SCAN_*_CHANNELS) give valid ADCS; 1 channel
// would need ADCS 119, 7 or more ADCS < 19.
#define DSPIC30_ADC_SAMPLE_TAD          1u    // SAMC
#define DSPIC30_ADC_CONVERSION_TAD      14u   // one conversion after sampling
#define DSPIC30_ADC_MIN_ADCS            19u   // Tad >= 667 ns at 3.3 V (§2.3)
#define DSPIC30_ADC_MAX_ADCS            63u   // 6-bit field
#define DSPIC30_ADC_SINGLE_ADCS         19u   // single reads: Tad = 678 ns
#define DSPIC30_ADC_SAMPLE_WAIT_US      10u   // sampling time of a single read
#define DSPIC30_ADC_CONVERSION_ATTEMPTS 2000u // polls of DONE before giving up
// AN0/AN1 are the programmer's PGD/PGC lines and stay digital (§2.3).
#define DSPIC30_ADC_DIGITAL_INPUTS 0x0003u

// --- I2C (§2.4) ------------------------------------------------------------------------
// ⚠ I2CBRG = FCY/FSCL − FCY/1 111 111 − 1 is a formula from public code, not
// from a Microchip document (§2.4); the library's 150 gives 90 to 97 kHz
// whichever delay term is right, under the 100 kHz the camera allows.
#define DSPIC30_I2C_BRG 150u
// Polls of a bus step before the transaction is abandoned.
#define DSPIC30_I2C_STEP_ATTEMPTS 5000u

// --- data EEPROM and program flash (§1.1, §1.3, §1.4; geometry: epuck_flash_layout.h)
#define DSPIC30_EEPROM_WORDS             2048u
#define DSPIC30_EEPROM_ERASED            0xFFFFu
#define DSPIC30_EEPROM_PAGE              0x7Fu   // TBLPAG / NVMADRU of the EEPROM
#define DSPIC30_EEPROM_BASE              0xF000u // offset of word 0 in that page
#define DSPIC30_NVMCON_FLASH_ROW_ERASE   0x4041u // [BL]; ICSP uses 0x4071
#define DSPIC30_NVMCON_FLASH_ROW_WRITE   0x4001u
#define DSPIC30_NVMCON_EEPROM_WORD_ERASE 0x4044u
#define DSPIC30_NVMCON_EEPROM_WORD_WRITE 0x4004u
#define DSPIC30_NVMKEY_FIRST             0x55u
#define DSPIC30_NVMKEY_SECOND            0xAAu
// ⚠ Whether the CPU stalls during a program-flash erase/write is recalled
// from the data sheet (§1.3); the HAL polls NVMCON.WR after every operation
// anyway, at most this many times (an EEPROM write takes about 2 ms).
#define DSPIC30_NVM_WAIT_ATTEMPTS 60000u

// --- camera pixel port (§3.5) ----------------------------------------------------------
// ⚠ The levels of VSYNC/HREF during a frame/row and the PCLK edge on which a
// byte is valid are not in the sources read (§3.5 only names the lines).
// VSYNC is taken as active during the window's rows (the PO3030K table's
// VSYNC start and stop rows are the window's), HREF during a row's bytes.
#define DSPIC30_CAMERA_SYNC_ACTIVE_LEVEL 1
// The library's capture reads a row with a loop of exactly 8 instruction
// cycles per byte (§3.5); dspic30_camera_row.c does the same, its loop
// written for this value (checked there).
#define DSPIC30_CAMERA_CYCLES_PER_BYTE 8u
// Polls of HREF (some 25 cycles each) for the row above the line to end,
// and (5 cycles each, every interrupt masked) for the line to begin: a row
// is 3,408 cycles at most (frame width 851, a quarter in QQVGA, 8 cycles a
// byte), so each allows about two rows before the read is abandoned.
#define DSPIC30_CAMERA_ROW_END_POLLS    300u
#define DSPIC30_CAMERA_LINE_START_POLLS 1400u
// A read whose line did not come within this time fails.
#define DSPIC30_CAMERA_FRAME_TIMEOUT_MS 500u

// --- busy waiting --------------------------------------------------------------------------
// ⚠ Cycles one iteration of the delay loop takes (a NOP plus loop overhead),
// estimated, not measured: hal_delay_microseconds is approximate.
#define DSPIC30_DELAY_CYCLES_PER_ITERATION 4u

#endif
