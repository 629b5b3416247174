// The standard natives' table (their modules), and the dictionary of the words their
// descriptions share. The descriptions (beside each native's body) give
// names, documentation strings and parameters exactly as upstream sends
// them (language.md §13.1), so that our nodes describe themselves like
// upstream ones and the compiler numbers them the same way. Packed (vm.h):
// the words they share are one byte each (nat_words.h).

#include "nat_standard.h"
#include "nat_words.h"

// The words of nat_words.h, in code order; the literal's own NUL ends the
// last word twice.
#define NAT_WORD_TEXT(name, code, text) text "\0"
const char nat_words[] = NAT_WORD_LIST(NAT_WORD_TEXT);
#undef NAT_WORD_TEXT

static const vm_native_module *const standard_modules[] = { NAT_STANDARD_MODULES };

const vm_native_table nat_standard_table = {
    standard_modules,
    sizeof standard_modules / sizeof standard_modules[0],
    nat_words,
};
