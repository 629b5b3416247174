// emit and monitor: global events into the network, and everything that
// happens on it.

#include <algorithm>
#include <cstdlib>
#include <iostream>

#include "console.hpp"
#include "tools/client/message_text.hpp"

namespace aseba::console
{

namespace
{

bool is_number(const std::string &text)
{
    return !text.empty() &&
           std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

int16_t parse_argument(const std::string &text)
{
    char *end = nullptr;
    long value = std::strtol(text.c_str(), &end, 0);
    if (text.empty() || *end != '\0' || value < INT16_MIN || value > INT16_MAX)
        throw UsageError("event argument '" + text + "' is not a number from -32768 to 32767");
    return int16_t(value);
}

// The global events known on the network: the programs' (the first node
// with a program), else the ones declared with --event.
const CommonDefinitions &known_events(Session &session)
{
    for (NodeKey key : session.network().node_keys())
        if (session.network().node(key).program)
            return session.definitions_for(key);
    return session.options().declared;
}

// Messages a monitor shows without --all: events, errors, and execution
// state changes (breakpoints, steps).
bool is_monitored(const client::Message &message)
{
    return std::holds_alternative<client::UserEvent>(message) ||
           std::holds_alternative<client::ArrayAccessOutOfBounds>(message) ||
           std::holds_alternative<client::DivisionByZero>(message) ||
           std::holds_alternative<client::EventExecutionKilled>(message) ||
           std::holds_alternative<client::NodeSpecificError>(message) ||
           std::holds_alternative<client::ExecutionStateChanged>(message) ||
           std::holds_alternative<client::BreakpointSetResult>(message) ||
           std::holds_alternative<client::Disconnected>(message);
}

void attach_programs_quietly(Session &session)
{
    // The monitor works without programs; a program that no longer compiles
    // only costs names.
    for (NodeKey key : session.network().node_keys()) {
        if (!session.network().node(key).described)
            continue;
        try {
            session.attach_programs({ key });
        } catch (const std::exception &error) {
            std::cerr << "aseba: " << session.label(key) << ": " << error.what() << "\n";
        }
    }
}

} // namespace

int command_emit(Session &session)
{
    const std::vector<std::string> &arguments = session.options().arguments;
    if (arguments.empty())
        throw UsageError("emit expects an EVENT and its arguments");
    const std::string &name = arguments[0];
    attach_programs_quietly(session);
    const CommonDefinitions &events = known_events(session);
    std::vector<int16_t> values;
    for (size_t i = 1; i < arguments.size(); i++)
        values.push_back(parse_argument(arguments[i]));
    uint16_t id = 0;
    if (std::optional<uint16_t> declared = client::global_event_id(events, name)) {
        id = *declared;
        uint16_t size = events.events[id].size;
        if (values.size() != size)
            throw UsageError("event " + name + " has " + std::to_string(size) + " argument" +
                             (size == 1 ? "" : "s") + ", " + std::to_string(values.size()) +
                             " given");
    } else if (is_number(name)) {
        id = uint16_t(std::strtoul(name.c_str(), nullptr, 10));
    } else {
        std::string known;
        for (const GlobalEvent &event : events.events)
            known += (known.empty() ? "" : ", ") + event.name;
        throw client::NetworkError("no global event '" + name + "' (" +
                                   (known.empty() ? std::string("no program declares events; "
                                                                "load one or use --event NAME:SIZE")
                                                  : "known: " + known) +
                                   ")");
    }
    session.network().emit(id, values);
    std::cout << "sent " << client::event_name(id, &events) << "(";
    for (size_t i = 0; i < values.size(); i++)
        std::cout << (i == 0 ? "" : ", ") << values[i];
    std::cout << ")\n";
    return 0;
}

int command_monitor(Session &session)
{
    const Options &options = session.options();
    if (!options.arguments.empty())
        throw UsageError("monitor takes no arguments (filters are --node and --event)");
    client::Network &network = session.network();
    attach_programs_quietly(session);
    const CommonDefinitions &events = known_events(session);

    std::vector<NodeKey> nodes;
    if (!options.node_selectors.empty())
        nodes = session.selected_nodes();
    std::vector<uint16_t> event_ids;
    for (const std::string &name : options.event_filters) {
        if (std::optional<uint16_t> id = client::global_event_id(events, name))
            event_ids.push_back(*id);
        else if (is_number(name))
            event_ids.push_back(uint16_t(std::strtoul(name.c_str(), nullptr, 10)));
        else
            throw client::NetworkError("no global event '" + name + "' to filter on");
    }

    unsigned long shown = 0;
    network.set_listener([&](const client::ReceivedFrame &frame) {
        if (options.count && shown >= *options.count)
            return;
        NodeKey key{ frame.target, frame.frame.source };
        if (!nodes.empty() && std::find(nodes.begin(), nodes.end(), key) == nodes.end())
            return;
        std::string sender = frame.frame.source == client::HOST_SOURCE
                               ? "host"
                               : "node " + std::to_string(frame.frame.source);
        const client::CompiledProgram *program = nullptr;
        if (frame.frame.source != client::HOST_SOURCE) {
            for (NodeKey known : network.node_keys())
                if (known == key) {
                    sender = session.label(key);
                    program = network.node(key).program.get();
                }
        }
        std::string text;
        if (!frame.message) {
            text = "malformed " + client::message_type_name(frame.frame.type) + ": " + frame.error;
        } else {
            const client::Message &message = *frame.message;
            const auto *event = std::get_if<client::UserEvent>(&message);
            if (!event_ids.empty() &&
                (event == nullptr ||
                 std::find(event_ids.begin(), event_ids.end(), event->id) == event_ids.end()))
                return;
            if (!options.all_messages && !is_monitored(message))
                return;
            text = client::message_text(message, &events, program);
        }
        shown++;
        std::cout << client::timestamp_text(frame.wall_time) << "  " << sender << "  " << text
                  << "\n"
                  << std::flush;
    });
    client::Milliseconds duration = client::Milliseconds::max();
    if (options.duration_seconds)
        duration = client::Milliseconds(long(*options.duration_seconds * 1000));
    const auto start = client::Clock::now();
    // Wait in slices so that Ctrl-C and the end of the duration are noticed.
    constexpr client::Milliseconds slice{ 100 };
    while (!interrupted() && !(options.count && shown >= *options.count)) {
        auto elapsed =
          std::chrono::duration_cast<client::Milliseconds>(client::Clock::now() - start);
        if (elapsed >= duration)
            break;
        network.keep_alive();
        network.poll(std::min(slice, duration - elapsed));
    }
    network.set_listener(nullptr);
    return 0;
}

} // namespace aseba::console
