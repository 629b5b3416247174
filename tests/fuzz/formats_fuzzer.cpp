// libFuzzer target for the file formats read through libraries: .aesl
// projects (pugixml, tools/compiler/aesl) and target descriptions
// (nlohmann-json, tools/compiler/target_json). Any input is read without a
// crash or an escaping exception, and what reads well round-trips: written
// back, it reads again as the same project or description.
//
// Input: the text itself; scripts/fuzz.sh seeds it with the examples and the
// test programs (projects) and the test targets.
//
// Built and run by `make fuzz` (scripts/fuzz.sh).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string_view>

#include "tools/compiler/aesl.hpp"
#include "tools/compiler/target_json.hpp"

namespace
{

[[noreturn]] void fail(const char *why)
{
    std::fprintf(stderr, "formats_fuzzer: %s\n", why);
    __builtin_trap();
}

bool same(const aseba::AeslProject &a, const aseba::AeslProject &b)
{
    if (a.show_keywords != b.show_keywords || a.nodes.size() != b.nodes.size() ||
        a.definitions.events.size() != b.definitions.events.size() ||
        a.definitions.constants.size() != b.definitions.constants.size())
        return false;
    for (size_t i = 0; i < a.definitions.events.size(); i++)
        if (a.definitions.events[i].name != b.definitions.events[i].name ||
            a.definitions.events[i].size != b.definitions.events[i].size)
            return false;
    for (size_t i = 0; i < a.definitions.constants.size(); i++)
        if (a.definitions.constants[i].name != b.definitions.constants[i].name ||
            a.definitions.constants[i].value != b.definitions.constants[i].value)
            return false;
    for (size_t i = 0; i < a.nodes.size(); i++)
        if (a.nodes[i].name != b.nodes[i].name || a.nodes[i].node_id != b.nodes[i].node_id ||
            a.nodes[i].source != b.nodes[i].source ||
            a.nodes[i].tools_plugins != b.nodes[i].tools_plugins)
            return false;
    return true;
}

bool same(const aseba::TargetDescription &a, const aseba::TargetDescription &b)
{
    if (a.name != b.name || a.protocol_version != b.protocol_version ||
        a.bytecode_size != b.bytecode_size || a.variables_size != b.variables_size ||
        a.stack_size != b.stack_size || a.named_variables.size() != b.named_variables.size() ||
        a.local_events.size() != b.local_events.size() ||
        a.native_functions.size() != b.native_functions.size())
        return false;
    for (size_t i = 0; i < a.named_variables.size(); i++)
        if (a.named_variables[i].name != b.named_variables[i].name ||
            a.named_variables[i].size != b.named_variables[i].size)
            return false;
    for (size_t i = 0; i < a.local_events.size(); i++)
        if (a.local_events[i].name != b.local_events[i].name ||
            a.local_events[i].description != b.local_events[i].description)
            return false;
    for (size_t i = 0; i < a.native_functions.size(); i++) {
        const aseba::NativeFunction &x = a.native_functions[i], &y = b.native_functions[i];
        if (x.name != y.name || x.description != y.description ||
            x.parameters.size() != y.parameters.size())
            return false;
        for (size_t p = 0; p < x.parameters.size(); p++)
            if (x.parameters[p].name != y.parameters[p].name ||
                x.parameters[p].size != y.parameters[p].size)
                return false;
    }
    return true;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    std::string_view text(reinterpret_cast<const char *>(data), size);
    try {
        aseba::AeslReadResult project = aseba::read_aesl(text);
        if (project.ok) {
            aseba::AeslReadResult again = aseba::read_aesl(aseba::write_aesl(project.project));
            if (!again.ok)
                fail("a written project does not read back");
            if (!same(project.project, again.project))
                fail("a written project reads back different");
        }
        aseba::TargetReadResult target = aseba::read_target_json(text);
        if (target.ok) {
            aseba::TargetReadResult again =
              aseba::read_target_json(aseba::write_target_json(target.target));
            if (!again.ok)
                fail("a written target description does not read back");
            if (!same(target.target, again.target))
                fail("a written target description reads back different");
        }
    } catch (...) {
        fail("an exception escaped");
    }
    return 0;
}
