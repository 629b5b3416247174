// Programs the client compiles for live nodes: a script or an .aesl project
// read from a file, compiled against a node's description, and what the
// network model needs afterwards (variable map, line of each bytecode word,
// global event names).

#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "tools/compiler/aesl.hpp"
#include "tools/compiler/compiler.hpp"

namespace aseba::client
{

// A program file that cannot be read or does not compile; what() is ready
// for people (a compile error has file:line:column, the line and a caret).
class ProgramError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// A program file that cannot be read, or a project that is not valid.
class FileError : public ProgramError
{
  public:
    using ProgramError::ProgramError;
};

// A program file as read: a bare script, or an .aesl project with one
// program per node.
struct ProgramFile {
    std::string file_name;
    bool is_project = false;
    std::string script;            // when !is_project
    AeslProject project;           // when is_project
    CommonDefinitions definitions; // the project's, or the ones given for a script
};

// Reads `path` (an .aesl project if its name ends in .aesl, else a script);
// `script_definitions` declares global events and constants for scripts.
// Throws FileError.
ProgramFile read_program_file(const std::string &path,
                              const CommonDefinitions &script_definitions = {});

// A program compiled for one node.
struct CompiledProgram {
    std::string file_name;
    std::string source;
    unsigned line_offset = 0;   // lines of the file before the program text
    unsigned column_offset = 0; // characters before it on its first line
    CommonDefinitions definitions;
    CompileResult result; // always ok
};

// Compiles the program of `file` meant for the node (`node_name`, `node_id`):
// the script, or the project's program for that id and name, else the one
// for that name, else the project's only program. Throws ProgramError with
// the compiler's message.
CompiledProgram compile_program(const ProgramFile &file,
                                const TargetDescription &target,
                                uint16_t node_id);

// The source line (1-based, in the file) of the bytecode word at `pc`, or 0.
unsigned source_line_of(const CompiledProgram &program, uint16_t pc);

// The first bytecode address generated for file line `line` (what a
// breakpoint on that line is set at), if code was generated for it.
std::optional<uint16_t> address_of_line(const CompiledProgram &program, unsigned line);

// The text of file line `line` of the program, without its line break.
std::string source_line_text(const CompiledProgram &program, unsigned line);

// The id of global event `name`, if the program's definitions declare it.
std::optional<uint16_t> global_event_id(const CommonDefinitions &definitions,
                                        const std::string &name);

} // namespace aseba::client
