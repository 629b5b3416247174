// vars and watch: variables by name, read, written and watched.

#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <unistd.h>

#include "console.hpp"
#include "tools/client/terminal_text.hpp"
#include "tools/client/variables.hpp"

namespace aseba::console
{

namespace
{

struct Assignment {
    std::string reference;
    std::vector<int16_t> values;
};

// What `vars` was asked: references to read and assignments to make.
struct VariablesRequest {
    std::vector<std::string> reads;
    std::vector<Assignment> writes;
};

int16_t parse_value(const std::string &text)
{
    char *end = nullptr;
    long value = std::strtol(text.c_str(), &end, 0);
    if (text.empty() || *end != '\0' || value < INT16_MIN || value > UINT16_MAX)
        throw UsageError("'" + text + "' is not a 16-bit value");
    return int16_t(value); // 0..65535 is accepted and wraps, as on the node
}

void append_values(std::vector<int16_t> &values, const std::string &text)
{
    std::istringstream items(text);
    std::string item;
    while (std::getline(items, item, ','))
        if (!item.empty())
            values.push_back(parse_value(item));
}

// Accepts `NAME`, `NAME=V,V`, and `NAME = V V` (the values up to the next
// argument that is not a number).
VariablesRequest parse_request(const std::vector<std::string> &arguments)
{
    VariablesRequest request;
    for (size_t i = 0; i < arguments.size(); i++) {
        const std::string &argument = arguments[i];
        size_t equals = argument.find('=');
        if (equals == std::string::npos &&
            (i + 1 >= arguments.size() || arguments[i + 1][0] != '=')) {
            request.reads.push_back(argument);
            continue;
        }
        Assignment assignment;
        if (equals == std::string::npos) {
            assignment.reference = argument;
            equals = 0;
            i++; // the argument starting with '='
        } else {
            assignment.reference = argument.substr(0, equals);
        }
        append_values(assignment.values, arguments[i].substr(equals + 1));
        while (i + 1 < arguments.size() && arguments[i + 1].find('=') == std::string::npos &&
               (std::isdigit(static_cast<unsigned char>(arguments[i + 1][0])) ||
                arguments[i + 1][0] == '-')) {
            append_values(assignment.values, arguments[++i]);
        }
        if (assignment.reference.empty() || assignment.values.empty())
            throw UsageError("'" + argument + "': expected NAME=VALUE[,VALUE...]");
        request.writes.push_back(assignment);
    }
    return request;
}

std::string values_text(const std::vector<int16_t> &values)
{
    std::string text;
    for (size_t i = 0; i < values.size(); i++)
        text += (i == 0 ? "" : " ") + std::to_string(values[i]);
    return text;
}

std::vector<client::VariableSlice> resolve_all(Session &session,
                                               NodeKey key,
                                               const std::vector<std::string> &references)
{
    const client::Node &node = session.network().node(key);
    auto map = client::variable_map(node.description, node.program.get());
    std::vector<client::VariableSlice> slices;
    if (references.empty()) {
        for (const client::VariableLocation &variable : map)
            slices.push_back({ variable.name, variable.address, variable.size });
        return slices;
    }
    for (const std::string &reference : references) {
        try {
            slices.push_back(
              client::resolve_variable(client::parse_variable_reference(reference), map));
        } catch (const client::VariableError &error) {
            throw client::VariableError(session.label(key) + ": " + error.what());
        }
    }
    return slices;
}

} // namespace

int command_vars(Session &session)
{
    VariablesRequest request = parse_request(session.options().arguments);
    std::vector<NodeKey> nodes = session.selected_nodes();
    session.attach_programs(nodes);
    client::Network &network = session.network();
    bool several = nodes.size() > 1;
    for (NodeKey key : nodes) {
        for (const Assignment &assignment : request.writes) {
            client::VariableSlice slice = resolve_all(session, key, { assignment.reference })[0];
            if (assignment.values.size() != slice.length && assignment.values.size() != 1)
                throw client::VariableError(
                  session.label(key) + ": " + slice.text + " has " + std::to_string(slice.length) +
                  " words, " + std::to_string(assignment.values.size()) + " values given");
            // One value fills the whole slice.
            std::vector<int16_t> values = assignment.values;
            values.resize(slice.length, assignment.values[0]);
            network.write_variables(key, slice.address, values);
        }
        if (!request.writes.empty() && request.reads.empty())
            continue;
        for (const client::VariableSlice &slice : resolve_all(session, key, request.reads)) {
            std::vector<int16_t> values = network.read_variables(key, slice.address, slice.length);
            if (several)
                std::cout << session.label(key) << ": ";
            std::cout << slice.text << " = " << values_text(values) << "\n";
        }
    }
    return 0;
}

int command_watch(Session &session)
{
    const Options &options = session.options();
    if (options.arguments.empty())
        throw UsageError("watch expects the names of the variables to watch");
    std::vector<NodeKey> nodes = session.selected_nodes();
    session.attach_programs(nodes);
    client::Network &network = session.network();
    std::vector<std::vector<client::VariableSlice>> slices;
    for (NodeKey key : nodes)
        slices.push_back(resolve_all(session, key, options.arguments));

    bool on_terminal = isatty(STDOUT_FILENO) != 0;
    const char *clear_screen = "\033[H\033[2J";
    size_t label_width = 4;
    for (NodeKey key : nodes)
        label_width = std::max(label_width, session.label(key).size());

    for (unsigned long refresh = 0; !interrupted(); refresh++) {
        if (options.count && refresh >= *options.count)
            break;
        network.keep_alive();
        std::vector<std::vector<std::string>> cells(nodes.size());
        for (size_t row = 0; row < nodes.size(); row++)
            for (const client::VariableSlice &slice : slices[row])
                cells[row].push_back(
                  values_text(network.read_variables(nodes[row], slice.address, slice.length)));
        std::vector<size_t> widths;
        for (size_t column = 0; column < options.arguments.size(); column++) {
            size_t width = slices[0][column].text.size();
            for (const auto &row : cells)
                width = std::max(width, row[column].size());
            widths.push_back(width);
        }
        // One line per node under a header; columns as wide as their widest
        // cell, without trailing blanks.
        std::string table;
        auto add_line = [&](const std::string &label, auto cell_of) {
            std::ostringstream line;
            line << std::left << std::setw(int(label_width)) << label;
            for (size_t column = 0; column < widths.size(); column++)
                line << "  " << std::setw(int(widths[column])) << cell_of(column);
            std::string text = line.str();
            text.erase(text.find_last_not_of(' ') + 1);
            table += text + "\n";
        };
        add_line("node", [&](size_t column) { return slices[0][column].text; });
        for (size_t row = 0; row < nodes.size(); row++)
            add_line(session.label(nodes[row]), [&](size_t column) { return cells[row][column]; });
        if (on_terminal)
            client::TerminalFilter::write_control(std::cout, clear_screen);
        else if (refresh > 0)
            std::cout << "\n";
        std::cout << table << std::flush;
        // Keep reading the links between refreshes, so nothing piles up.
        network.wait_until([] { return interrupted(); }, options.interval);
    }
    return 0;
}

} // namespace aseba::console
