// Runs bench/avr_workload.c, linked for an ATmega1284P, under simavr and
// counts the AVR instructions and cycles executed while port B bit 0 is set
// (the workload's event `go`), then prints them with the checksum of the
// variables the program leaves in ports C and D:
//
//   avr-step-counter IMAGE.elf      ->  instructions cycles checksum
//
// (on the last line of the output: simavr prints what it loads before).
// Instruction by instruction: simavr's avr_run executes one per call.

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <simavr/sim_avr.h>
#include <simavr/sim_elf.h>

// ATmega1284P data addresses of the ports the workload writes.
#define PORTB_ADDRESS 0x25
#define PORTC_ADDRESS 0x28
#define PORTD_ADDRESS 0x2B
#define MARKER_BIT    0x01
#define CLOCK_HZ      16000000u
// A run of the workload takes a few million instructions; far more means
// the image never got to its end.
#define INSTRUCTION_LIMIT 2000000000ull

int main(int argc, char **argv)
{
    elf_firmware_t firmware;
    avr_t *avr;
    uint64_t executed = 0, counted = 0;
    avr_cycle_count_t cycles_before = 0, cycles = 0;
    int state;
    int was_marked = 0;

    if (argc != 2) {
        fprintf(stderr, "usage: avr-step-counter IMAGE.elf\n");
        return 2;
    }
    memset(&firmware, 0, sizeof firmware);
    if (elf_read_firmware(argv[1], &firmware) != 0) {
        fprintf(stderr, "avr-step-counter: cannot read %s\n", argv[1]);
        return 1;
    }
    avr = avr_make_mcu_by_name("atmega1284p");
    if (avr == NULL || avr_init(avr) != 0) {
        fprintf(stderr, "avr-step-counter: simavr has no atmega1284p\n");
        return 1;
    }
    avr->frequency = CLOCK_HZ;
    avr_load_firmware(avr, &firmware);
    do {
        int marked = (avr->data[PORTB_ADDRESS] & MARKER_BIT) != 0;
        if (marked && !was_marked)
            cycles_before = avr->cycle;
        if (!marked && was_marked)
            cycles += avr->cycle - cycles_before;
        was_marked = marked;
        state = avr_run(avr);
        counted += marked;
        executed++;
    } while (state != cpu_Done && state != cpu_Crashed && executed < INSTRUCTION_LIMIT);
    if (state != cpu_Done) {
        fprintf(stderr, "avr-step-counter: the image did not end (state %d)\n", state);
        return 1;
    }
    printf("%" PRIu64 " %" PRIu64 " %u\n",
           counted,
           (uint64_t)cycles,
           (unsigned)(avr->data[PORTC_ADDRESS] | avr->data[PORTD_ADDRESS] << 8));
    return 0;
}
