// The project the IDE edits, as an .aesl file holds it (aesl.md): global
// events and constants, and each robot's script. Programs of an opened
// project whose robot is not on the network yet wait for it, as Aseba
// Studio's "absent" tabs do, and are written back when saving.

#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "tools/client/network.hpp"
#include "tools/compiler/aesl.hpp"

namespace aseba::ide
{

using client::NodeKey;

// A project file that cannot be read or written; what() names the file.
class ProjectError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

struct Workspace {
    CommonDefinitions definitions;
    std::map<NodeKey, std::string> scripts;
    std::vector<AeslNode> waiting; // programs whose robot has not appeared
    std::string file_path;         // where it was opened from, or empty

    // Replaces everything with the project in `text` (named `file_name` in
    // errors); the programs wait for their robots. Throws ProjectError.
    void open(const std::string &file_name, const std::string &text);

    // Gives the robots on the network (`robots`: each one's name) the
    // waiting programs, in file order: each goes to a robot of its name,
    // preferably of its id (aesl.md §2.2), that got none yet. Returns the
    // robots given a program.
    std::vector<NodeKey> assign(const std::map<NodeKey, std::string> &robots);

    // Gives a robot that just described itself a waiting program of its
    // name, preferably of its id. Returns whether it got one.
    bool match(NodeKey key, const std::string &robot_name);

    // The project as .aesl text; `names` gives each robot's name.
    std::string to_aesl(const std::map<NodeKey, std::string> &names) const;
};

// Reads a whole file; throws ProjectError.
std::string read_project_file(const std::string &path);

// Replaces `path` with `text` through a temporary file, so that a crash or a
// full disk never leaves a half-written project; throws ProjectError.
void write_project_file(const std::string &path, const std::string &text);

} // namespace aseba::ide
