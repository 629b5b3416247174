// The connection shared by the subcommands, and the record of loaded
// programs that lets `aseba vars counter` find a user variable after
// `aseba load prog.aseba`.

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include "console.hpp"
#include "tools/client/terminal_text.hpp"
#include "tools/command_line/command_line.hpp"

namespace aseba::console
{

namespace
{

namespace fs = std::filesystem;

// One line per loaded node: target, node id, absolute file path and the
// events declared for it on the command line (NAME:SIZE, comma-separated).
struct LoadRecord {
    std::string target;
    uint16_t node_id = 0;
    std::string file;
    std::string declared_events;
};

fs::path record_path()
{
    if (const char *state = std::getenv("XDG_STATE_HOME"); state != nullptr && *state != '\0')
        return fs::path(state) / "aseba" / "loaded-programs";
    if (const char *home = std::getenv("HOME"); home != nullptr && *home != '\0')
        return fs::path(home) / ".local" / "state" / "aseba" / "loaded-programs";
    return {};
}

std::vector<LoadRecord> read_records()
{
    std::vector<LoadRecord> records;
    fs::path path = record_path();
    if (path.empty())
        return records;
    std::ifstream file(path);
    std::string line;
    while (std::getline(file, line)) {
        std::istringstream fields(line);
        LoadRecord record;
        std::string id;
        if (!std::getline(fields, record.target, '\t') || !std::getline(fields, id, '\t') ||
            !std::getline(fields, record.file, '\t'))
            continue; // a damaged line is only a forgotten program
        std::getline(fields, record.declared_events);
        record.node_id = uint16_t(std::strtoul(id.c_str(), nullptr, 10));
        records.push_back(record);
    }
    return records;
}

std::string events_text(const CommonDefinitions &definitions)
{
    std::string text;
    for (const GlobalEvent &event : definitions.events)
        text += (text.empty() ? "" : ",") + event.name + ":" + std::to_string(event.size);
    return text;
}

CommonDefinitions events_from_text(const std::string &text)
{
    CommonDefinitions definitions;
    std::istringstream items(text);
    std::string item;
    while (std::getline(items, item, ',')) {
        size_t colon = item.find(':');
        if (colon == std::string::npos)
            continue;
        GlobalEvent event;
        event.name = item.substr(0, colon);
        event.size = uint16_t(std::strtoul(item.c_str() + colon + 1, nullptr, 10));
        definitions.events.push_back(event);
    }
    return definitions;
}

} // namespace

Session::Session(const Options &options)
  : options_(options)
  , network_(options.timeout)
{
    for (const std::string &target : options_.targets)
        network_.connect(target);
    network_.discover();
}

std::vector<NodeKey> Session::selected_nodes() const
{
    if (network_.node_keys().empty()) {
        std::string targets;
        for (size_t target = 0; target < network_.target_count(); target++)
            targets += (targets.empty() ? "" : ", ") + network_.target_name(target);
        throw client::NetworkError("no node answered on " + targets + " within " +
                                   std::to_string(options_.timeout.count()) + " ms");
    }
    std::vector<std::string> selectors = options_.node_selectors;
    if (selectors.empty())
        selectors.push_back("all");
    std::vector<NodeKey> selected;
    for (const std::string &selector : selectors)
        for (NodeKey key : network_.select(selector))
            if (std::find(selected.begin(), selected.end(), key) == selected.end())
                selected.push_back(key);
    std::sort(selected.begin(), selected.end());
    return selected;
}

void Session::attach_programs(const std::vector<NodeKey> &nodes)
{
    std::vector<LoadRecord> records =
      options_.program_file.empty() ? read_records() : std::vector<LoadRecord>{};
    std::map<std::string, client::ProgramFile> files;
    for (NodeKey key : nodes) {
        std::string path = options_.program_file;
        CommonDefinitions declared = options_.declared;
        if (path.empty()) {
            std::string target = network_.target_name(key.target);
            for (const LoadRecord &record : records)
                if (record.target == target && record.node_id == key.id) {
                    path = record.file;
                    declared = events_from_text(record.declared_events);
                }
            if (path.empty())
                continue;
        }
        auto file = files.find(path);
        if (file == files.end())
            file = files.emplace(path, client::read_program_file(path, declared)).first;
        const client::Node &node = network_.node(key);
        auto program = std::make_shared<client::CompiledProgram>(
          client::compile_program(file->second, node.description, key.id));
        network_.set_program(key, program);
    }
}

bool Session::record_load(NodeKey key, const std::string &file)
{
    fs::path path = record_path();
    if (path.empty())
        return true; // nowhere to remember: later commands need --program
    std::string target = network_.target_name(key.target);
    std::vector<LoadRecord> records = read_records();
    std::erase_if(records, [&](const LoadRecord &record) {
        return record.target == target && record.node_id == key.id;
    });
    records.push_back(
      { target, key.id, fs::absolute(file).string(), events_text(options_.declared) });
    std::error_code error;
    fs::create_directories(path.parent_path(), error);
    std::string text;
    for (const LoadRecord &record : records)
        text += record.target + '\t' + std::to_string(record.node_id) + '\t' + record.file + '\t' +
                record.declared_events + '\n';
    std::string failure = command_line::write_whole_file(path.string(), text);
    if (!failure.empty())
        std::cerr << "aseba: the load is not recorded (later commands need --program): " << failure
                  << "\n";
    return failure.empty();
}

const CommonDefinitions &Session::definitions_for(NodeKey key) const
{
    const client::Node &node = network_.node(key);
    if (node.program)
        return node.program->definitions;
    return options_.declared;
}

std::string Session::label(NodeKey key) const
{
    std::string text = client::escaped_name(network_.node(key).label());
    if (network_.target_count() > 1)
        text += " (" + network_.target_name(key.target) + ")";
    return text;
}

} // namespace aseba::console
