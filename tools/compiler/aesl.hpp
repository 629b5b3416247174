// Reads .aesl project files (aesl.md): global events and constants, and one
// program per node.

#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "target.hpp"

namespace aseba
{

struct AeslNode {
    std::string name;
    uint16_t node_id = 0;
    std::string source;        // the program text, entities decoded
    unsigned first_line = 1;   // line of the file where the program text starts
    unsigned first_column = 0; // characters before it on that line
};

struct AeslProject {
    CommonDefinitions definitions;
    std::vector<AeslNode> nodes;
};

struct AeslReadResult {
    bool ok = false;
    AeslProject project;
    unsigned error_line = 0; // of the file, when !ok
    std::string error;
};

// Reads an .aesl document; malformed XML or values give an error, never a crash.
AeslReadResult read_aesl(std::string_view text);

} // namespace aseba
