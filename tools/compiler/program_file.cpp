// Reading programs from script and project files.

#include "program_file.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include "aesl.hpp"
#include "error_format.hpp"

namespace aseba
{

namespace
{

// At most MAX_PROGRAM_FILE_BYTES of `input`: a device or a pipe that never
// ends (/dev/zero) is refused rather than read without bound.
// Reads in chunks, so that a small file touches little memory: a buffer of
// the largest size, zero-filled for every file, cost the compiler a third of
// its start-up.
std::string read_bounded(std::istream &input, const std::string &name)
{
    constexpr size_t CHUNK_BYTES = 64 * 1024;
    std::string text;
    while (text.size() <= MAX_PROGRAM_FILE_BYTES) {
        size_t before = text.size();
        text.resize(before + CHUNK_BYTES);
        input.read(text.data() + before, static_cast<std::streamsize>(CHUNK_BYTES));
        text.resize(before + static_cast<size_t>(input.gcount()));
        if (input.bad())
            throw std::runtime_error(name + ": error: cannot read the file");
        if (input.eof())
            break;
    }
    if (text.size() > MAX_PROGRAM_FILE_BYTES)
        throw std::runtime_error(name + ": error: the file is larger than " +
                                 std::to_string(MAX_PROGRAM_FILE_BYTES / 1024 / 1024) +
                                 " MiB, the most a program file may be");
    return text;
}

std::string read_whole(const std::string &path)
{
    if (path == "-")
        return read_bounded(std::cin, "<stdin>");
    std::error_code error;
    if (std::filesystem::is_directory(path, error))
        throw std::runtime_error(path + ": error: this is a folder, not a program file");
    std::ifstream file(path, std::ios::binary);
    if (!file)
        throw std::runtime_error(path + ": error: cannot read the file");
    return read_bounded(file, path);
}

bool is_project(const std::string &path)
{
    const std::string suffix = ".aesl";
    return path.size() >= suffix.size() &&
           path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
}

} // namespace

ProgramFile read_program_file(const std::string &path, const std::string &node)
{
    ProgramFile program;
    program.file_name = path == "-" ? "<stdin>" : path;
    std::string text = read_whole(path);
    if (!is_project(path)) {
        program.source = std::move(text);
        return program;
    }
    AeslReadResult project = read_aesl(text);
    if (!project.ok)
        throw std::runtime_error(program.file_name + ":" + std::to_string(project.error_line) +
                                 ": error: " + project.error);
    for (const AeslNode &candidate : project.project.nodes) {
        if (node.empty() || candidate.name == node) {
            program.source = candidate.source;
            program.node_name = candidate.name;
            program.definitions = project.project.definitions;
            program.line_offset = candidate.first_line - 1;
            program.column_offset = candidate.first_column;
            return program;
        }
    }
    throw std::runtime_error(
      program.file_name + ": error: " +
      (node.empty() ? "the project has no node" : "the project has no node named " + node));
}

CompileResult compile_program_file(const ProgramFile &program,
                                   const TargetDescription &target,
                                   std::string &error_text)
{
    CompileResult result = compile(program.source, target, program.definitions);
    if (!result.ok)
        error_text = format_error(program.file_name,
                                  program.source,
                                  result.error,
                                  program.line_offset,
                                  program.column_offset);
    return result;
}

} // namespace aseba
