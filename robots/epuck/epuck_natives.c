// The e-puck's native table.

#include "epuck_natives.h"

#include "native_functions/nat_dsp.h"
#include "native_functions/nat_standard.h"
#include "native_functions/nat_words.h"

static const vm_native epuck_native_list[] = { NAT_STANDARD_LIST NAT_DSP_LIST };

const vm_native_table epuck_native_table = {
    epuck_native_list,
    sizeof(epuck_native_list) / sizeof(epuck_native_list[0]),
    nat_words,
};
