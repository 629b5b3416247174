// Reading and compiling program files for live nodes.

#include "program.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tools/compiler/error_format.hpp"

namespace aseba::client
{

namespace
{

bool ends_with(const std::string &text, const std::string &suffix)
{
    return text.size() >= suffix.size() &&
           text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

const AeslNode &project_program_for(const ProgramFile &file,
                                    const std::string &node_name,
                                    uint16_t node_id)
{
    const std::vector<AeslNode> &nodes = file.project.nodes;
    for (const AeslNode &node : nodes)
        if (node.node_id == node_id && node.name == node_name)
            return node;
    for (const AeslNode &node : nodes)
        if (node.name == node_name)
            return node;
    if (nodes.size() == 1)
        return nodes.front();
    throw ProgramError(file.file_name + ": no program for node '" + node_name + "' (id " +
                       std::to_string(node_id) + ") in this project");
}

} // namespace

ProgramFile read_program_file(const std::string &path, const CommonDefinitions &script_definitions)
{
    std::error_code ignored;
    if (std::filesystem::is_directory(path, ignored))
        throw FileError(path + ": is a folder, not a program file");
    std::ifstream stream(path, std::ios::binary);
    if (!stream)
        throw FileError(path + ": cannot open the file (" + std::strerror(errno) + ")");
    std::ostringstream text;
    text << stream.rdbuf();
    ProgramFile file;
    file.file_name = path;
    if (!ends_with(path, ".aesl")) {
        file.script = text.str();
        file.definitions = script_definitions;
        return file;
    }
    AeslReadResult read = read_aesl(text.str());
    if (!read.ok)
        throw FileError(path + ":" + std::to_string(read.error_line) + ": " + read.error);
    file.is_project = true;
    file.project = std::move(read.project);
    file.definitions = file.project.definitions;
    return file;
}

CompiledProgram compile_program(const ProgramFile &file,
                                const TargetDescription &target,
                                uint16_t node_id)
{
    CompiledProgram program;
    program.file_name = file.file_name;
    program.definitions = file.definitions;
    if (file.is_project) {
        const AeslNode &node = project_program_for(file, target.name, node_id);
        program.source = node.source;
        program.line_offset = node.first_line - 1;
        program.column_offset = node.first_column;
    } else {
        program.source = file.script;
    }
    program.result = compile(program.source, target, program.definitions);
    if (!program.result.ok)
        throw ProgramError(format_error(program.file_name,
                                        program.source,
                                        program.result.error,
                                        program.line_offset,
                                        program.column_offset));
    return program;
}

unsigned source_line_of(const CompiledProgram &program, uint16_t pc)
{
    const std::vector<unsigned> &lines = program.result.line_of_word;
    if (pc >= lines.size() || lines[pc] == 0)
        return 0;
    return lines[pc] + program.line_offset;
}

std::optional<uint16_t> address_of_line(const CompiledProgram &program, unsigned line)
{
    if (line <= program.line_offset)
        return std::nullopt;
    unsigned program_line = line - program.line_offset;
    const std::vector<unsigned> &lines = program.result.line_of_word;
    for (size_t address = 0; address < lines.size(); address++)
        if (lines[address] == program_line)
            return uint16_t(address);
    return std::nullopt;
}

std::string source_line_text(const CompiledProgram &program, unsigned line)
{
    if (line <= program.line_offset)
        return {};
    std::istringstream lines(program.source);
    std::string text;
    for (unsigned i = program.line_offset; i < line; i++)
        if (!std::getline(lines, text))
            return {};
    if (!text.empty() && text.back() == '\r')
        text.pop_back();
    return text;
}

std::optional<uint16_t> global_event_id(const CommonDefinitions &definitions,
                                        const std::string &name)
{
    for (size_t i = 0; i < definitions.events.size(); i++)
        if (definitions.events[i].name == name)
            return uint16_t(i);
    return std::nullopt;
}

} // namespace aseba::client
