// Runs one data-driven VM test: a listing for tests/support/assembler.hpp
// whose `#` lines say what to do and what to expect (format in
// tests/vm/README.md). Failures are reported with the line they come from.

#pragma once

#include <string>
#include <vector>

namespace vm_tests
{

// Assembles and runs `text` (named `name` in messages) on a fresh VM. Returns
// the list of failures, empty when every expectation held.
std::vector<std::string> run_program_script(const std::string &name, const std::string &text);

} // namespace vm_tests
