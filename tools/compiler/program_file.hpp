// A program to compile, read from a file as users write them: a bare script,
// or one node's program in an .aesl project with the project's definitions.
// Shared by every host tool that loads programs (asebac, epuck-emu, console).

#pragma once

#include <string>

#include "compiler.hpp"
#include "target.hpp"

namespace aseba
{

struct ProgramFile {
    std::string file_name;         // as given, for messages
    std::string source;            // the program text
    CommonDefinitions definitions; // the project's (empty for a script)
    std::string node_name;         // the project node the program is for
    unsigned line_offset = 0;      // where the program starts in the file
    unsigned column_offset = 0;
};

// The largest program file read: an .aesl project of several nodes may be
// larger than one program (compiler.hpp, MAX_SOURCE_BYTES), not much more.
inline constexpr size_t MAX_PROGRAM_FILE_BYTES = 4 * 1024 * 1024;

// Reads `path` ("-" for standard input). An .aesl file gives the program of
// the node named `node`, or of its first node when `node` is empty. Throws
// std::runtime_error with a message "FILE[:LINE]: error: ..." when the file
// cannot be read (a folder, larger than MAX_PROGRAM_FILE_BYTES) or is not a
// valid project.
ProgramFile read_program_file(const std::string &path, const std::string &node = "");

// Compiles the program for `target`. On failure, `error_text` holds the error
// as people read it: file:line:column, the source line and a caret.
CompileResult compile_program_file(const ProgramFile &program,
                                   const TargetDescription &target,
                                   std::string &error_text);

} // namespace aseba
