// The IDE's project: opening, matching programs to robots, saving.

#include "workspace.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <pugixml.hpp>

namespace aseba::ide
{

AeslProject read_project(const std::string &file_name, const std::string &text)
{
    AeslReadResult read = read_aesl(text);
    if (!read.ok)
        throw ProjectError(file_name + ":" + std::to_string(read.error_line) + ": " + read.error);
    return std::move(read.project);
}

void Workspace::open(const std::string &file_name, const std::string &text)
{
    open(read_project(file_name, text));
}

void Workspace::open(AeslProject &&project)
{
    definitions = std::move(project.definitions);
    scripts.clear();
    programs = std::move(project.nodes);
    waiting = programs;
}

const AeslNode *Workspace::program_for(NodeKey key, const std::string &robot_name) const
{
    const AeslNode *best = nullptr;
    for (const AeslNode &program : programs) {
        if (program.name != robot_name)
            continue;
        if (program.node_id == key.id)
            return &program;
        if (!best)
            best = &program;
    }
    return best;
}

bool Workspace::match(NodeKey key, const std::string &robot_name)
{
    if (scripts.count(key))
        return false;
    const AeslNode *program = program_for(key, robot_name);
    if (!program)
        return false;
    scripts[key] = program->source;
    waiting.erase(std::remove_if(waiting.begin(),
                                 waiting.end(),
                                 [&](const AeslNode &left) {
                                     return left.name == program->name &&
                                            left.node_id == program->node_id;
                                 }),
                  waiting.end());
    return true;
}

std::vector<NodeKey> Workspace::assign(const std::map<NodeKey, std::string> &robots)
{
    std::vector<NodeKey> given;
    for (const auto &[key, name] : robots)
        if (match(key, name))
            given.push_back(key);
    return given;
}

std::string Workspace::to_aesl(const std::map<NodeKey, std::string> &names) const
{
    // Studio's layout (aesl.md §4): events and constants before the nodes,
    // each group after two blank lines and a comment, each program one text
    // node.
    pugi::xml_document document;
    pugi::xml_node network = document.append_child("network");
    auto group = [&](const std::string &comment) {
        network.append_child(pugi::node_pcdata).set_value("\n\n\n");
        network.append_child(pugi::node_comment).set_value(comment.c_str());
        network.append_child(pugi::node_pcdata).set_value("\n");
    };
    group("list of global events");
    for (const GlobalEvent &event : definitions.events) {
        pugi::xml_node element = network.append_child("event");
        element.append_attribute("size") = event.size;
        element.append_attribute("name") = event.name.c_str();
        network.append_child(pugi::node_pcdata).set_value("\n");
    }
    group("list of constants");
    for (const Constant &constant : definitions.constants) {
        pugi::xml_node element = network.append_child("constant");
        element.append_attribute("value") = constant.value;
        element.append_attribute("name") = constant.name.c_str();
        network.append_child(pugi::node_pcdata).set_value("\n");
    }
    auto add_program = [&](const std::string &name, uint16_t id, const std::string &source) {
        group("node " + name);
        pugi::xml_node element = network.append_child("node");
        element.append_attribute("nodeId") = id;
        element.append_attribute("name") = name.c_str();
        element.append_child(pugi::node_pcdata).set_value(source.c_str());
    };
    for (const auto &[key, source] : scripts) {
        auto name = names.find(key);
        if (!source.empty() && name != names.end())
            add_program(name->second, key.id, source);
    }
    for (const AeslNode &program : waiting)
        add_program(program.name, program.node_id, program.source);
    network.append_child(pugi::node_pcdata).set_value("\n\n\n");
    std::ostringstream text;
    text << "<!DOCTYPE aesl-source>\n";
    network.print(text, "", pugi::format_raw);
    text << "\n";
    return text.str();
}

std::string read_project_file(const std::string &path)
{
    std::ifstream stream(path, std::ios::binary);
    if (!stream)
        throw ProjectError(path + ": cannot open the file");
    std::ostringstream text;
    text << stream.rdbuf();
    if (stream.bad())
        throw ProjectError(path + ": cannot read the file");
    return text.str();
}

void write_project_file(const std::string &path, const std::string &text)
{
    std::string temporary = path + ".saving";
    {
        std::ofstream stream(temporary, std::ios::binary | std::ios::trunc);
        stream << text;
        stream.flush();
        if (!stream)
            throw ProjectError(temporary + ": cannot write the file");
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
        std::remove(temporary.c_str());
        throw ProjectError(path + ": cannot replace the file");
    }
}

} // namespace aseba::ide
