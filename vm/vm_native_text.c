// Reading the packed descriptions of native functions (vm.h, vm_native):
// what the node sends and what host tools show of a native.

#include "vm.h"

#include <stddef.h>

const char *vm_native_text_end(const char *text)
{
    while ((uint8_t)*text >= VM_NATIVE_TEXT_FIRST)
        text++;
    return text;
}

// The word of code `code` (from VM_NATIVE_WORD_FIRST) in `words`; an empty
// one past the last (the dictionary's literal ends with an empty word).
static const char *word_of(const char *words, uint8_t code)
{
    for (code = (uint8_t)(code - VM_NATIVE_WORD_FIRST); code > 0 && *words != '\0'; code--) {
        while (*words != '\0')
            words++;
        words++;
    }
    return words;
}

uint8_t vm_native_text_next(vm_native_text *reader)
{
    for (;;) {
        uint8_t byte;

        if (reader->word != NULL) {
            byte = (uint8_t)*reader->word;
            if (byte != '\0') {
                reader->word++;
                return byte;
            }
            reader->word = NULL;
        }
        byte = (uint8_t)*reader->text;
        if (byte < VM_NATIVE_TEXT_FIRST)
            return 0;
        reader->text++;
        if (byte < VM_NATIVE_WORD_FIRST || reader->words == NULL)
            return byte;
        reader->word = word_of(reader->words, byte);
    }
}
