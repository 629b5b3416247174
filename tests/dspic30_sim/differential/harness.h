/* The differential programs of the simulator's tests: each computes values
   with well-defined C (fixed-width types, no signed overflow, no shift past
   the width) and reports them; the same source is compiled for the dsPIC
   (pic30-elf-gcc -Os, run on the simulator) and for the host (gcc), and the
   two reports must be identical (tests/dspic30_sim/differential_test.cpp). */

#ifndef DIFFERENTIAL_HARNESS_H
#define DIFFERENTIAL_HARNESS_H

#include <stdint.h>

/* Prints "NAME VALUE" (VALUE in hexadecimal) on its own line. */
void report(const char *name, uint32_t value);

/* The program's body, called once by the platform's main. */
void differential_main(void);

#endif
