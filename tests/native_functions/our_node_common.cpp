// What of our_node.hpp does not depend on where the node's VM runs: a
// native by name and its description, from the host's own tables, and the
// record of the errors the VM reports. Apart from our_node.cpp so that the
// node's stand-in on a simulated chip (tests/ports/dspic30/remote_our_node.cpp)
// shares them.

#include "our_node.hpp"

#include <map>
#include <stdexcept>

#include "tests/support/native_table.hpp"
#include "tools/compiler/target_presets.hpp"

extern "C" {
#include "nat_words.h"
}

aseba::NativeFunction description_of(const vm_native &native)
{
    const test_support::OneModuleTable table(&native, 1, nat_words);
    return aseba::native_function(table, 0);
}

const vm_native &standard_native(std::string_view name)
{
    // Built once: the deque tests call natives by name in long loops.
    static const std::map<std::string, const vm_native *, std::less<>> by_name = [] {
        std::map<std::string, const vm_native *, std::less<>> natives;
        for (uint16_t id = 0; id < vm_native_count(&nat_standard_table); ++id) {
            const vm_native *native = vm_native_at(&nat_standard_table, id);
            natives[description_of(*native).name] = native;
        }
        return natives;
    }();
    const auto found = by_name.find(name);
    if (found == by_name.end())
        throw std::invalid_argument("no standard native " + std::string(name));
    return *found->second;
}

namespace
{

OurNode &node_of(void *context)
{
    return *static_cast<OurNode *>(context);
}

void ignore_emit(void *, uint16_t, const int16_t *, uint16_t) {}

void record_array_access(void *context, uint16_t pc, uint16_t size, uint16_t index)
{
    node_of(context).errors.push_back({ ErrorReport::Kind::array_access, pc, size, index, {} });
}

void record_division_by_zero(void *context, uint16_t pc)
{
    node_of(context).errors.push_back({ ErrorReport::Kind::division_by_zero, pc, 0, 0, {} });
}

void record_node_specific(void *context, uint16_t pc, const char *message)
{
    node_of(context).errors.push_back({ ErrorReport::Kind::node_specific, pc, 0, 0, message });
}

// Records the errors among the VM's word reports; state changes and killed
// events are not errors.
void record_report(void *context, uint16_t type, const uint16_t *words, uint16_t count)
{
    if (type == VM_REPORT_ARRAY_ACCESS_OUT_OF_BOUNDS && count == 3)
        record_array_access(context, words[0], words[1], words[2]);
    else if (type == VM_REPORT_DIVISION_BY_ZERO && count == 1)
        record_division_by_zero(context, words[0]);
    else if (type != VM_REPORT_EXECUTION_STATE_CHANGED && type != VM_REPORT_EVENT_EXECUTION_KILLED)
        record_node_specific(context, count > 0 ? words[0] : 0, "unexpected report");
}

} // namespace

const vm_callbacks our_node_callbacks = { ignore_emit, record_report, record_node_specific };
