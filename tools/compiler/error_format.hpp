// Renders a compile error for people: `file:line:column: error: message`,
// then the offending source line and a caret under the column.

#pragma once

#include <string>
#include <string_view>

#include "compiler.hpp"

namespace aseba
{

// The error as text ending with a line break. `line_offset` is added to the
// line shown (for programs embedded in a file, e.g. .aesl), `column_offset`
// to the column when the error is on the program's first line.
std::string format_error(std::string_view file_name,
                         std::string_view source,
                         const CompileError &error,
                         unsigned line_offset = 0,
                         unsigned column_offset = 0);

} // namespace aseba
