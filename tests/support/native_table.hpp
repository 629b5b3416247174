// A native table (vm.h) over one array of records, for tests that list
// natives of their own or pick some of a library's: a table names its
// modules by pointer, so the module and the list of one live here beside it.
#pragma once

#include <cstdint>
#include <vector>

extern "C" {
#include "vm.h"
}

namespace test_support
{

class OneModuleTable
{
  public:
    constexpr OneModuleTable(const vm_native *natives, uint16_t count, const char *words = nullptr)
      : module_{ natives, count }
      , modules_{ &module_ }
      , table_{ modules_, 1, words }
    {
    }

    OneModuleTable(const std::vector<vm_native> &natives, const char *words = nullptr)
      : OneModuleTable(natives.data(), static_cast<uint16_t>(natives.size()), words)
    {
    }

    // The table points into this object: it cannot move.
    OneModuleTable(const OneModuleTable &) = delete;
    OneModuleTable &operator=(const OneModuleTable &) = delete;

    const vm_native_table &table() const
    {
        return table_;
    }

    operator const vm_native_table &() const
    {
        return table_;
    }

  private:
    vm_native_module module_;
    const vm_native_module *modules_[1];
    vm_native_table table_;
};

// Every native of `table` in NATIVE_CALL order, as one array of records.
inline std::vector<vm_native> natives_of(const vm_native_table &table)
{
    std::vector<vm_native> natives;
    for (uint16_t id = 0; id < vm_native_count(&table); ++id)
        natives.push_back(*vm_native_at(&table, id));
    return natives;
}

} // namespace test_support
