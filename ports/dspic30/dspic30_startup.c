// The data initialisation of the dsPIC30F start-up, in C: dspic30_reset.s
// sets the stack and PSV and calls it before main. Nothing here may use a
// variable of static storage: they are what it initialises.

#include "dspic30_registers.h"
#include "dspic30_startup.h"

#define TEMPLATE_WORD_SPAN 2u // PC units per program word

// The low 16 bits of the program word at `*address`; moves to the next.
static uint16_t next_template_word(uint32_t *address)
{
    dspic30_write(DSPIC30_TBLPAG, (uint16_t)(*address >> 16));
    uint16_t word = dspic30_table_read_low((uint16_t)*address);
    *address += TEMPLATE_WORD_SPAN;
    return word;
}

bool dspic30_initialise_data(uint32_t template_address)
{
    uint32_t address = template_address;

    // A program with no data at all has no template: the linker gives its
    // address as 0, where the reset vector lies.
    if (template_address == 0)
        return true;
    for (;;) {
        uint16_t destination = next_template_word(&address);
        if (destination == 0)
            return true;
        uint16_t length = next_template_word(&address);
        uint16_t format = next_template_word(&address);

        if (format == DSPIC30_DINIT_CLEAR) {
            for (; length > 0; length--)
                dspic30_write_byte(destination++, 0);
        } else if (format == DSPIC30_DINIT_COPY_TWO_BYTES) {
            while (length > 0) {
                uint16_t word = next_template_word(&address);
                dspic30_write_byte(destination++, (uint8_t)word);
                if (--length > 0) {
                    dspic30_write_byte(destination++, (uint8_t)(word >> 8));
                    --length;
                }
            }
        } else {
            return false;
        }
    }
}
