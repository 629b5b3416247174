// nodes, compile, load, save, reboot: what is on the network and what runs
// on it.

#include <iostream>
#include <memory>

#include "console.hpp"
#include "tools/compiler/disassembler.hpp"

namespace aseba::console
{

namespace
{

// How long `save` listens for a node's report of the write.
constexpr Milliseconds SAVE_REPORT_WAIT{ 200 };

void print_description(const TargetDescription &description)
{
    std::cout << "  variables:";
    for (const NamedVariable &variable : description.named_variables) {
        std::cout << " " << variable.name;
        if (variable.size != 1)
            std::cout << "[" << variable.size << "]";
    }
    std::cout << "\n  local events:";
    for (const LocalEvent &event : description.local_events)
        std::cout << " " << event.name;
    std::cout << "\n  native functions:\n";
    for (const NativeFunction &function : description.native_functions) {
        std::cout << "    " << function.name << "(";
        for (size_t i = 0; i < function.parameters.size(); i++) {
            const NativeParameter &parameter = function.parameters[i];
            std::cout << (i == 0 ? "" : ", ") << parameter.name;
            if (parameter.size > 1)
                std::cout << "[" << parameter.size << "]";
            else if (parameter.size < 0)
                std::cout << "[<" << -parameter.size << ">]";
            else if (parameter.size == 0)
                std::cout << "[]";
        }
        std::cout << ")\n";
    }
}

// Compiles the file for every selected node; the programs come back in the
// order of `nodes`.
std::vector<std::shared_ptr<client::CompiledProgram>>
compile_for_nodes(Session &session, const std::vector<NodeKey> &nodes, const std::string &path)
{
    client::ProgramFile file = client::read_program_file(path, session.options().declared);
    std::vector<std::shared_ptr<client::CompiledProgram>> programs;
    for (NodeKey key : nodes) {
        const client::Node &node = session.network().node(key);
        programs.push_back(std::make_shared<client::CompiledProgram>(
          client::compile_program(file, node.description, key.id)));
    }
    return programs;
}

std::string file_argument(const Session &session, const char *command)
{
    const std::vector<std::string> &arguments = session.options().arguments;
    if (arguments.size() != 1)
        throw UsageError(std::string(command) + " expects one FILE");
    return arguments[0];
}

// Uploads each program and, unless --paused, runs it; records the loads.
// Returns whether every load was recorded.
bool load_programs(Session &session,
                   const std::vector<NodeKey> &nodes,
                   const std::vector<std::shared_ptr<client::CompiledProgram>> &programs,
                   const std::string &path,
                   bool run)
{
    bool recorded = true;
    for (size_t i = 0; i < nodes.size(); i++) {
        const client::CompiledProgram &program = *programs[i];
        session.network().upload(nodes[i], program.result.bytecode);
        session.network().set_program(nodes[i], programs[i]);
        recorded = session.record_load(nodes[i], path) && recorded;
        client::ExecutionState state =
          run ? session.network().run(nodes[i]) : *session.network().node(nodes[i]).execution;
        std::cout << session.label(nodes[i]) << ": loaded " << path << " ("
                  << program.result.bytecode.size() << " words), " << state.name() << "\n";
    }
    return recorded;
}

} // namespace

int command_nodes(Session &session)
{
    if (!session.options().arguments.empty())
        throw UsageError("nodes takes no arguments");
    client::Network &network = session.network();
    for (NodeKey key : session.selected_nodes()) {
        const client::Node &node = network.node(key);
        client::ExecutionState state = network.execution_state(key);
        const TargetDescription &description = node.description;
        std::cout << "node " << key.id << " \"" << description.name << "\" on "
                  << network.target_name(key.target) << ": protocol " << node.protocol_version
                  << ", bytecode " << description.bytecode_size << " words, stack "
                  << description.stack_size << ", variables " << description.variables_size
                  << " words (" << description.named_variables.size() << " named), "
                  << description.local_events.size() << " local events, "
                  << description.native_functions.size() << " native functions; " << state.name()
                  << "\n";
        if (session.options().describe)
            print_description(description);
    }
    return 0;
}

int command_compile(Session &session)
{
    std::string path = file_argument(session, "compile");
    std::vector<NodeKey> nodes = session.selected_nodes();
    auto programs = compile_for_nodes(session, nodes, path);
    for (size_t i = 0; i < nodes.size(); i++) {
        const client::CompiledProgram &program = *programs[i];
        const TargetDescription &description = session.network().node(nodes[i]).description;
        std::cout << path << " for " << session.label(nodes[i]) << ": "
                  << program.result.bytecode.size() << " of " << description.bytecode_size
                  << " words of bytecode, " << program.result.allocated_variables << " of "
                  << description.variables_size << " words of variables\n";
        if (session.options().listing)
            std::cout << listing(
              program.result.bytecode, program.result.line_of_word, program.source);
    }
    return 0;
}

int command_load(Session &session)
{
    std::string path = file_argument(session, "load");
    std::vector<NodeKey> nodes = session.selected_nodes();
    // Compile for everyone first: one bad program loads nothing.
    auto programs = compile_for_nodes(session, nodes, path);
    bool recorded = load_programs(session, nodes, programs, path, !session.options().paused);
    return recorded ? 0 : EXIT_FAILED;
}

int command_save(Session &session)
{
    const std::vector<std::string> &arguments = session.options().arguments;
    if (arguments.size() > 1)
        throw UsageError("save takes at most one FILE");
    std::vector<NodeKey> nodes = session.selected_nodes();
    bool recorded = true;
    if (arguments.size() == 1) {
        auto programs = compile_for_nodes(session, nodes, arguments[0]);
        recorded = load_programs(session, nodes, programs, arguments[0], true);
    }
    for (NodeKey key : nodes) {
        session.network().write_bytecode(key);
        std::cout << session.label(key) << ": asked to write its bytecode to storage\n";
    }
    // A node that reports the outcome does so with NODE_SPECIFIC_ERROR.
    session.network().set_listener([&](const client::ReceivedFrame &frame) {
        if (!frame.message)
            return;
        if (const auto *report = std::get_if<client::NodeSpecificError>(&*frame.message))
            std::cout << "node " << frame.frame.source << ": " << report->message << "\n";
    });
    session.network().wait_until([] { return false; }, SAVE_REPORT_WAIT);
    return recorded ? 0 : EXIT_FAILED;
}

int command_reboot(Session &session)
{
    if (!session.options().arguments.empty())
        throw UsageError("reboot takes no arguments");
    for (NodeKey key : session.selected_nodes()) {
        session.network().reboot(key);
        std::cout << session.label(key) << ": reboot requested\n";
    }
    return 0;
}

} // namespace aseba::console
