// Reads and writes .aesl project files (aesl.md): global events and
// constants, and one program per node. The XML itself is pugixml's job.

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
    // The <toolsPlugins> element (plugin state, such as Thymio VPL programs)
    // as XML text, empty when absent: kept, never interpreted.
    std::string tools_plugins;
};

struct AeslProject {
    CommonDefinitions definitions;
    std::vector<AeslNode> nodes;
    bool show_keywords = true; // Studio's <keywords flag=...>; compilers ignore it
};

struct AeslReadResult {
    bool ok = false;
    AeslProject project;
    unsigned error_line = 0; // of the file, when !ok
    std::string error;
};

// Reads an .aesl document; malformed XML or values give an error, never a crash.
AeslReadResult read_aesl(std::string_view text);

// Writes `project` as Aseba Studio 1.6 writes projects (aesl.md §4): events
// and constants before the nodes, each node's program as one text, its
// plugin state after it. read_aesl gives back the same project. Throws
// std::invalid_argument for what no reader would take back: an event size
// above 258 words, an empty name, a plugin state that is not XML.
std::string write_aesl(const AeslProject &project);

} // namespace aseba
