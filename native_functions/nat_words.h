// The words that the descriptions of the standard and DSP natives share:
// in a packed description (vm.h, vm_native) each is one byte from 0x80,
// which the node expands as it sends the description. Of the standard
// natives' 1,890 bytes of text (names, documentation, parameter names),
// 1,363 are these words; packed, their descriptions take 956 bytes.
//
// NAT_WORD_LIST gives each word's code and text; the W_ macros below are
// the same codes as string literals, for writing descriptions (a string
// literal cannot be made from a number). tests/native_functions checks
// that both agree.

#ifndef NAT_WORDS_H
#define NAT_WORDS_H

// X(name, code, text), in code order from VM_NATIVE_WORD_FIRST.
#define NAT_WORD_LIST(X)                                                                           \
    X(ELEMENT_BY_ELEMENT, 0x80, " element by element")                                             \
    X(MATH, 0x81, "math.")                                                                         \
    X(DEST, 0x82, "dest")                                                                          \
    X(DEQUE, 0x83, "deque")                                                                        \
    X(SRC, 0x84, "src")                                                                            \
    X(PERFORMS, 0x85, "performs ")                                                                 \
    X(INSERT, 0x86, "insert")                                                                      \
    X(ERASE, 0x87, "erase")                                                                        \
    X(SCALAR, 0x88, "scalar")                                                                      \
    X(ARRAY, 0x89, "array")                                                                        \
    X(VALUE, 0x8A, "value")                                                                        \
    X(SHIFT, 0x8B, "shift")                                                                        \
    X(FILL, 0x8C, "fill")                                                                          \
    X(OF, 0x8D, " of ")                                                                            \
    X(TO, 0x8E, " to ")                                                                            \
    X(FROM, 0x8F, " from ")                                                                        \
    X(AND, 0x90, " and ")                                                                          \
    X(FRONT, 0x91, "front")                                                                        \
    X(BACK, 0x92, "back")                                                                          \
    X(SIZE, 0x93, "size")                                                                          \
    X(ELEMENT, 0x94, " element")                                                                   \
    X(INDEX, 0x95, "index")                                                                        \
    X(THE, 0x96, " the ")                                                                          \
    X(WRITE, 0x97, "write")                                                                        \
    X(ADD, 0x98, "add")                                                                            \
    X(BY, 0x99, " by ")                                                                            \
    X(SRC1, 0x9A, "src1")                                                                          \
    X(SRC2, 0x9B, "src2")

#define W_ELEMENT_BY_ELEMENT "\x80"
#define W_MATH               "\x81"
#define W_DEST               "\x82"
#define W_DEQUE              "\x83"
#define W_SRC                "\x84"
#define W_PERFORMS           "\x85"
#define W_INSERT             "\x86"
#define W_ERASE              "\x87"
#define W_SCALAR             "\x88"
#define W_ARRAY              "\x89"
#define W_VALUE              "\x8A"
#define W_SHIFT              "\x8B"
#define W_FILL               "\x8C"
#define W_OF                 "\x8D"
#define W_TO                 "\x8E"
#define W_FROM               "\x8F"
#define W_AND                "\x90"
#define W_FRONT              "\x91"
#define W_BACK               "\x92"
#define W_SIZE               "\x93"
#define W_ELEMENT            "\x94"
#define W_INDEX              "\x95"
#define W_THE                "\x96"
#define W_WRITE              "\x97"
#define W_ADD                "\x98"
#define W_BY                 "\x99"
#define W_SRC1               "\x9A"
#define W_SRC2               "\x9B"

// The dictionary of a native table (vm_native_table.words) whose natives'
// descriptions use these words.
extern const char nat_words[];

#endif
