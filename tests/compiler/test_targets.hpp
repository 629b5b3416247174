// The targets and project definitions the compiler tests compile for, built
// from the specifications (not from our own code), so that our compiler and
// the reference compiler see exactly the same node.

#pragma once

#include <vector>

#include "tools/compiler/target.hpp"

namespace compiler_tests
{

// The 30 standard natives of language.md §13.1, in their standard order.
std::vector<aseba::NativeFunction> standard_natives();

// The fake node `testvm` of the corpus README §1 (256 words, no named
// variables, local event `test`) with the given natives.
aseba::TargetDescription corpus_target(const std::vector<aseba::NativeFunction> &natives);

// Global events event1/0, event2/3 and constant FOO = 2 (corpus README §1).
aseba::CommonDefinitions corpus_definitions();

// The desktop dummy node of bytecode.md §10: id, source, args[32],
// _productId, timer.period; local event `timer`; 1060 words of variables.
aseba::TargetDescription dummy_node_target();

} // namespace compiler_tests
