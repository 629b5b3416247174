// The natives' lookups of our_node.hpp that are not the node's: a native by
// name and its description, from the host's own tables. Apart from
// our_node.cpp so that the node's stand-in on a simulated chip
// (tests/ports/dspic30/remote_our_node.cpp) shares them.

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
