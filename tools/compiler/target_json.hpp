// Target descriptions in JSON, the project's own file format
// (docs/target-description.md).

#pragma once

#include <string>
#include <string_view>

#include "target.hpp"

namespace aseba
{

struct TargetReadResult {
    bool ok = false;
    TargetDescription target;
    // When !ok: "parse error at line L, column C: ..." for bad JSON, "PATH:
    // ..." for a value
    // the format does not allow (PATH as `natives[3].parameters[0].size`).
    std::string error;
};

// Reads a target description from JSON text; never throws.
TargetReadResult read_target_json(std::string_view text);

// Writes `target` as JSON that read_target_json reads back identically.
std::string write_target_json(const TargetDescription &target);

} // namespace aseba
