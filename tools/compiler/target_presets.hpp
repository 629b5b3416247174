// Built-in target descriptions: our e-puck (from the firmware's own
// description) and the reference's desktop dummy node.

#pragma once

#include <optional>
#include <string>

#include "target.hpp"

extern "C" {
#include "vm/vm.h"
}

namespace aseba
{

// Native `index` of a C native table (vm.h), its packed description expanded.
NativeFunction native_function(const vm_native_table &table, uint16_t index);

// Every native of a C native table, in NATIVE_CALL order.
std::vector<NativeFunction> native_functions(const vm_native_table &table);

// The 30 standard natives (language.md §13.1), from the firmware's C table.
std::vector<NativeFunction> standard_native_functions();

// Our e-puck, built from robots/epuck/epuck_description.h and the standard natives.
TargetDescription epuck_target();

// The reference's asebadummynode "dummynode-0".
TargetDescription dummy_target();

// The preset called `name` ("epuck" or "dummy"), if there is one.
std::optional<TargetDescription> target_preset(const std::string &name);

} // namespace aseba
