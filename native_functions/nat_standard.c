// Descriptions of the standard natives: names, documentation strings and
// parameters exactly as upstream sends them (language.md §13.1), so that
// our nodes describe themselves like upstream ones and the compiler numbers
// them the same way. Packed (vm.h): the words they share are one byte each
// (nat_words.h), and the dictionary of those words is here.

#include "nat_internal.h"
#include "nat_standard.h"
#include "nat_words.h"

// The words of nat_words.h, in code order; the literal's own NUL ends the
// last word twice.
#define NAT_WORD_TEXT(name, code, text) text "\0"
const char nat_words[] = NAT_WORD_LIST(NAT_WORD_TEXT);
#undef NAT_WORD_TEXT

NATIVE(math_copy,
       3,
       W_MATH "copy",
       "copies " W_SRC W_TO W_DEST W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC));
NATIVE(math_fill,
       3,
       W_MATH W_FILL,
       W_FILL "s " W_DEST " with constant " W_VALUE,
       P(N, W_DEST) P(1, W_VALUE));
NATIVE(math_addscalar,
       4,
       W_MATH W_ADD W_SCALAR,
       W_ADD " " W_SCALAR W_TO "each" W_ELEMENT W_OF W_SRC W_AND "store result" W_TO W_DEST,
       P(N, W_DEST) P(N, W_SRC) P(1, W_SCALAR));
NATIVE(math_add,
       4,
       W_MATH W_ADD,
       W_ADD "s " W_SRC1 W_AND W_SRC2 ", " W_WRITE W_TO W_DEST "," W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC1) P(N, W_SRC2));
NATIVE(math_sub,
       4,
       W_MATH "sub",
       "substracts " W_SRC2 W_FROM W_SRC1 W_TO W_DEST "," W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC1) P(N, W_SRC2));
NATIVE(math_mul,
       4,
       W_MATH "mul",
       "multiplies " W_SRC1 W_AND W_SRC2 W_TO W_DEST "," W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC1) P(N, W_SRC2));
NATIVE(math_div,
       4,
       W_MATH "div",
       "divides " W_SRC1 W_BY W_SRC2 W_TO W_DEST "," W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC1) P(N, W_SRC2));
NATIVE(math_min,
       4,
       W_MATH "min",
       W_WRITE "s" W_THE "minimum" W_OF W_SRC1 W_AND W_SRC2 W_TO W_DEST "," W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC1) P(N, W_SRC2));
NATIVE(math_max,
       4,
       W_MATH "max",
       W_WRITE "s" W_THE "maximum" W_OF W_SRC1 W_AND W_SRC2 W_TO W_DEST "," W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC1) P(N, W_SRC2));
NATIVE(math_clamp,
       5,
       W_MATH "clamp",
       "clamp " W_SRC W_TO "low/high bounds into " W_DEST "," W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC) P(N, "low") P(N, "high"));
NATIVE(math_dot,
       5,
       W_MATH "dot",
       W_WRITE "s" W_THE "dot product" W_OF W_SRC1 W_AND W_SRC2 W_TO W_DEST ", after a " W_SHIFT,
       P(1, W_DEST) P(N, W_SRC1) P(N, W_SRC2) P(1, W_SHIFT));
NATIVE(math_stat,
       5,
       W_MATH "stat",
       W_PERFORMS "statistics on " W_SRC,
       P(N, W_SRC) P(1, "min") P(1, "max") P(1, "mean"));
NATIVE(math_argbounds,
       4,
       W_MATH "argbounds",
       "get" W_THE "indices (argmin, argmax)" W_OF "the limit " W_VALUE "s" W_OF W_SRC,
       P(N, W_SRC) P(1, "argmin") P(1, "argmax"));
NATIVE(math_sort, 2, W_MATH "sort", "sort " W_ARRAY " in place", P(N, W_ARRAY));
NATIVE(math_muldiv,
       5,
       W_MATH "muldiv",
       W_PERFORMS W_DEST " = (a*b)/c in 32 bits" W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, "a") P(N, "b") P(N, "c"));
NATIVE(math_atan2,
       4,
       W_MATH "atan2",
       W_PERFORMS W_DEST " = atan2(y,x)" W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, "y") P(N, "x"));
NATIVE(math_sin,
       3,
       W_MATH "sin",
       W_PERFORMS W_DEST " = sin(x)" W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, "x"));
NATIVE(math_cos,
       3,
       W_MATH "cos",
       W_PERFORMS W_DEST " = cos(x)" W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, "x"));
NATIVE(math_rot2,
       3,
       W_MATH "rot2",
       "rotates v" W_OF "angle a" W_TO W_DEST,
       P(2, W_DEST) P(2, "v") P(1, "a"));
NATIVE(math_sqrt,
       3,
       W_MATH "sqrt",
       W_PERFORMS W_DEST " = sqrt(x)" W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, "x"));
NATIVE(math_rand, 2, W_MATH "rand", W_FILL " " W_ARRAY " with random " W_VALUE "s", P(N, W_DEST));
NATIVE(deque_size, 3, W_DEQUE "." W_SIZE, "report " W_SIZE W_OF W_DEST, P(N, W_DEQUE) P(1, W_SIZE));
NATIVE(deque_get,
       5,
       W_DEQUE ".get",
       W_FILL " " W_DEST W_FROM W_DEQUE " at " W_INDEX,
       P(N, W_DEQUE) P(M, W_DEST) P(1, W_INDEX));
NATIVE(deque_set,
       5,
       W_DEQUE ".set",
       "copies " W_SRC W_TO W_DEQUE " at " W_INDEX,
       P(N, W_DEQUE) P(M, W_SRC) P(1, W_INDEX));
NATIVE(deque_insert,
       5,
       W_DEQUE "." W_INSERT,
       W_SHIFT " " W_DEQUE " at " W_INDEX W_BY "len(" W_SRC ")" W_AND W_INSERT " " W_SRC,
       P(N, W_DEQUE) P(M, W_SRC) P(1, W_INDEX));
NATIVE(deque_erase,
       4,
       W_DEQUE "." W_ERASE,
       W_SHIFT " " W_DEQUE " at " W_INDEX W_BY "len" W_TO W_ERASE,
       P(N, W_DEQUE) P(1, W_INDEX) P(1, "len"));
NATIVE(deque_push_front,
       4,
       W_DEQUE ".push_" W_FRONT,
       W_INSERT " " W_SRC " before" W_THE W_FRONT W_OF W_DEQUE,
       P(N, W_DEQUE) P(M, W_SRC));
NATIVE(deque_push_back,
       4,
       W_DEQUE ".push_" W_BACK,
       W_INSERT " " W_SRC " after" W_THE W_BACK W_OF W_DEQUE,
       P(N, W_DEQUE) P(M, W_SRC));
NATIVE(deque_pop_front,
       4,
       W_DEQUE ".pop_" W_FRONT,
       W_FILL " " W_DEST W_FROM W_FRONT W_OF W_DEQUE " then " W_ERASE W_ELEMENT "s",
       P(N, W_DEQUE) P(M, W_DEST));
NATIVE(deque_pop_back,
       4,
       W_DEQUE ".pop_" W_BACK,
       W_FILL " " W_DEST W_FROM W_BACK W_OF W_DEQUE " then " W_ERASE W_ELEMENT "s",
       P(N, W_DEQUE) P(M, W_DEST));

static const vm_native standard_natives[NAT_STANDARD_COUNT] = { NAT_STANDARD_LIST };

const vm_native_table nat_standard_table = { standard_natives, NAT_STANDARD_COUNT, nat_words };
