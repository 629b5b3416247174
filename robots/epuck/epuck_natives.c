// The e-puck's native table: the modules it exports, in NATIVE_CALL order.

#include "epuck_natives.h"

#include "native_functions/nat_dsp.h"
#include "native_functions/nat_standard.h"
#include "native_functions/nat_words.h"

// The e-puck has no natives of its own: a file of natives lists its module
// here, before or after the libraries' (the order is the natives' ids).
static const vm_native_module *const epuck_modules[] = { NAT_STANDARD_MODULES NAT_DSP_MODULES };

const vm_native_table epuck_native_table = {
    epuck_modules,
    sizeof epuck_modules / sizeof epuck_modules[0],
    nat_words,
};
