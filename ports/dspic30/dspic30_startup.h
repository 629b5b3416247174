// The C half of the dsPIC30F start-up (dspic30_reset.s calls it before
// main): RAM initialised from the linker's template.

#ifndef DSPIC30_STARTUP_H
#define DSPIC30_STARTUP_H

#include <stdbool.h>
#include <stdint.h>

// The .dinit template's record formats (linked with --no-pack-data): each
// record is three program words (destination in data space, length in
// bytes, format) followed, for a copy, by the bytes, two in the low 16 bits
// of each program word. A record whose destination is 0 ends the template.
#define DSPIC30_DINIT_CLEAR          0u
#define DSPIC30_DINIT_COPY_TWO_BYTES 1u

// Writes every record of the template at PC address `template_address`
// (0: there is none) into RAM: zeros for a clearing record, the template's bytes for a copy.
// Returns false, having written nothing more, at a record of another format
// (a template packed three bytes per word: the image was linked without
// --no-pack-data).
bool dspic30_initialise_data(uint32_t template_address);

#endif
