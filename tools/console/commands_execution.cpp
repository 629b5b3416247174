// run, pause, step, stop, reset and break: execution control, with positions
// shown as source lines when the node's program is known.

#include <chrono>
#include <algorithm>
#include <cstdlib>
#include <iostream>

#include "console.hpp"

namespace aseba::console
{

namespace
{

// "at pc 12, line 4: x = x + 1" or "at pc 12" without a program.
std::string position_text(const client::Node &node, uint16_t pc)
{
    std::string text = "at pc " + std::to_string(pc);
    if (!node.program)
        return text;
    unsigned line = client::source_line_of(*node.program, pc);
    if (line == 0)
        return text;
    return text + ", line " + std::to_string(line) + ": " +
           client::source_line_text(*node.program, line);
}

void print_state(Session &session, NodeKey key, const client::ExecutionState &state)
{
    std::cout << session.label(key) << ": " << state.name();
    if (state.flags & client::FLAG_EVENT_ACTIVE)
        std::cout << " " << position_text(session.network().node(key), state.pc);
    std::cout << "\n";
}

unsigned parse_line(const std::string &text)
{
    char *end = nullptr;
    unsigned long line = std::strtoul(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || line == 0)
        throw UsageError("LINE must be a line number, not '" + text + "'");
    return unsigned(line);
}

// Reports every node of `nodes` that stops on a breakpoint, counting the
// hits in `hits`. Installed before the breakpoints are set: a hit may arrive
// in the same read as the node's BREAKPOINT_SET_RESULT.
void report_hits(Session &session, const std::vector<NodeKey> &nodes, unsigned long &hits)
{
    client::Network &network = session.network();
    network.set_listener([&session, &network, nodes, &hits](const client::ReceivedFrame &frame) {
        if (!frame.message)
            return;
        const auto *state = std::get_if<client::ExecutionStateChanged>(&*frame.message);
        NodeKey key{ frame.target, frame.frame.source };
        if (state == nullptr || std::find(nodes.begin(), nodes.end(), key) == nodes.end())
            return;
        // A breakpoint stops the run loop with its running bit still set
        // (bytecode.md §6.2); a STEP or an event starting while paused
        // reports the same state without that bit.
        client::ExecutionState execution{ state->pc, state->flags };
        if (!execution.stepping() || !(state->flags & client::FLAG_EVENT_RUNNING))
            return;
        hits++;
        std::cout << session.label(key) << ": breakpoint hit "
                  << position_text(network.node(key), state->pc) << "\n"
                  << std::flush;
    });
}

// Waits until `hits` reaches `count`, Ctrl-C or `duration`; true if reached.
bool wait_for_hits(Session &session,
                   const unsigned long &hits,
                   unsigned long count,
                   Milliseconds duration)
{
    bool reached =
      session.network().wait_until([&] { return hits >= count || interrupted(); }, duration);
    session.network().set_listener(nullptr);
    return reached && hits >= count;
}

Milliseconds wait_duration(const Options &options)
{
    if (options.duration_seconds)
        return Milliseconds(long(*options.duration_seconds * 1000));
    return options.timeout;
}

} // namespace

int command_execution(Session &session)
{
    const std::string &command = session.options().command;
    if (!session.options().arguments.empty())
        throw UsageError(command + " takes no arguments");
    std::vector<NodeKey> nodes = session.selected_nodes();
    session.attach_programs(nodes);
    client::Network &network = session.network();
    for (NodeKey key : nodes) {
        client::ExecutionState state;
        if (command == "run")
            state = network.run(key);
        else if (command == "pause")
            state = network.pause(key);
        else if (command == "step")
            state = session.options().by_line ? network.step_line(key) : network.step(key);
        else if (command == "stop")
            state = network.stop(key);
        else
            state = network.reset(key);
        print_state(session, key, state);
    }
    return 0;
}

int command_break(Session &session)
{
    const Options &options = session.options();
    const std::vector<std::string> &arguments = options.arguments;
    if (arguments.empty())
        throw UsageError("break expects set LINE, clear LINE|all or wait");
    const std::string &action = arguments[0];
    std::vector<NodeKey> nodes = session.selected_nodes();
    client::Network &network = session.network();
    unsigned long wanted_hits = options.count.value_or(1);

    if (action == "wait") {
        if (arguments.size() != 1)
            throw UsageError("break wait takes no arguments");
        session.attach_programs(nodes);
        unsigned long hits = 0;
        report_hits(session, nodes, hits);
        if (!wait_for_hits(session, hits, wanted_hits, wait_duration(options))) {
            std::cerr << "aseba: " << hits << " breakpoint hit" << (hits == 1 ? "" : "s")
                      << " within " << wait_duration(options).count() << " ms\n";
            return EXIT_FAILED;
        }
        return 0;
    }
    if ((action != "set" && action != "clear") || arguments.size() != 2)
        throw UsageError("break expects set LINE, clear LINE|all or wait");
    if (action == "clear" && arguments[1] == "all") {
        for (NodeKey key : nodes) {
            network.clear_all_breakpoints(key);
            std::cout << session.label(key) << ": all breakpoints cleared\n";
        }
        return 0;
    }
    unsigned line = parse_line(arguments[1]);
    session.attach_programs(nodes);
    int status = 0;
    unsigned long hits = 0;
    if (action == "set" && options.wait)
        report_hits(session, nodes, hits);
    for (NodeKey key : nodes) {
        const client::Node &node = network.node(key);
        if (!node.program)
            throw client::NetworkError(session.label(key) +
                                       ": no program known (load one, or give --program)");
        std::optional<uint16_t> pc = client::address_of_line(*node.program, line);
        if (!pc)
            throw client::NetworkError(session.label(key) + ": no code on line " +
                                       std::to_string(line) + " of " + node.program->file_name);
        if (action == "clear") {
            network.clear_breakpoint(key, *pc);
            std::cout << session.label(key) << ": breakpoint cleared at line " << line << "\n";
        } else if (network.set_breakpoint(key, *pc)) {
            std::cout << session.label(key) << ": breakpoint set at line " << line << " (pc " << *pc
                      << "): " << client::source_line_text(*node.program, line) << "\n";
        } else {
            std::cout << session.label(key) << ": the node refused a breakpoint at pc " << *pc
                      << " (its table may be full)\n";
            status = EXIT_FAILED;
        }
    }
    std::cout << std::flush;
    if (action == "set" && options.wait && status == 0 &&
        !wait_for_hits(session, hits, wanted_hits, wait_duration(options))) {
        std::cerr << "aseba: no breakpoint hit within " << wait_duration(options).count()
                  << " ms\n";
        status = EXIT_FAILED;
    }
    return status;
}

} // namespace aseba::console
