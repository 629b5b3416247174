// The read of one camera row on the parallel port, timed by the
// instructions as the library's capture is (§3.5): the camera puts a byte on
// RD8..RD15 every DSPIC30_CAMERA_CYCLES_PER_BYTE instruction cycles from
// HREF's rising edge, faster than a loop watching PCLK could follow, so the
// bytes are read at that very rate from the moment HREF is seen. One
// inline assembly block, written from the 16-bit MCU and DSC Programmer's
// Reference Manual's cycle counts (BTSC, BRA, MOV, LSR, REPEAT, DEC): C
// gives no control over the cycles between two reads. Not compiled by the
// checks on other chips (ports/dspic30/module.mk), nor into the board's
// tests on the PC, which stand a function of their own for it.
//
// Timing (cycles from the start of byte 0 of the row, HREF's rising edge):
// the loop that waits for HREF samples it every 5 cycles, so it sees it 0
// to 4 cycles late, and the first read comes 3 cycles after that sample:
// each byte is read 3 to 7 cycles into its 8.

#include "dspic30_pin_map.h"
#include "epuck_dspic30_board.h"
#include "ports/dspic30/dspic30_registers.h"

typedef char loop_is_written_for_8_cycles_a_byte[DSPIC30_CAMERA_CYCLES_PER_BYTE == 8u ? 1 : -1];
typedef char wait_ends_on_a_high_href[DSPIC30_CAMERA_SYNC_ACTIVE_LEVEL == 1 ? 1 : -1];

bool dspic30_camera_read_row(uint8_t *bytes, uint16_t pixels, uint16_t polls)
{
    uint16_t read = 0;
    uint16_t byte;

    if (pixels == 0)
        return true;
    // Each pixel pair is 32 cycles: its two bytes read 8 cycles apart and
    // kept, then the two of the pixel skipped, 16 cycles of loop.
    __asm__ volatile(
      "1:  btsc   %c[portc], #%c[href]\n" // HREF active: leave the wait
      "    bra    2f\n"
      "    dec    %[polls], %[polls]\n"
      "    bra    nz, 1b\n"
      "    bra    3f\n"                 // HREF never came
      "2:  mov    %c[portd], %[byte]\n" // 0: the pixel's first byte
      "    lsr    %[byte], #8, %[byte]\n"
      "    mov.b  %[byte], [%[bytes]++]\n"
      "    repeat #3\n"
      "    nop\n"                       // 4 cycles: on to 8
      "    mov    %c[portd], %[byte]\n" // 8: its second byte
      "    lsr    %[byte], #8, %[byte]\n"
      "    mov.b  %[byte], [%[bytes]++]\n"
      "    repeat #16\n"
      "    nop\n" // 17 cycles: on to 29
      "    dec    %[pixels], %[pixels]\n"
      "    bra    nz, 2b\n" // 30-31: the next pixel at 32
      "    mov    #1, %[read]\n"
      "3:\n"
      : [read] "+r"(read),
        [bytes] "+r"(bytes),
        [pixels] "+r"(pixels),
        [polls] "+r"(polls),
        [byte] "=&r"(byte)
      : [portc] "i"(DSPIC30_PORTC), [portd] "i"(DSPIC30_PORTD), [href] "i"(DSPIC30_CAMERA_HREF_BIT)
      : "memory");
    return read != 0;
}
