// The project the IDE edits, as an .aesl file holds it (aesl.md): global
// events and constants, and each robot's script. Programs of an opened
// project that no robot on the network took wait for one, as Aseba Studio's
// "absent" tabs do, and are written back when saving.

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
    std::vector<AeslNode> programs; // the opened project's, as in its file
    std::vector<AeslNode> waiting;  // of those, the ones no robot has taken
    std::string file_path;          // where it was opened from, or empty

    // Replaces everything with the project in `text` (named `file_name` in
    // errors); the programs wait for their robots. Throws ProjectError.
    void open(const std::string &file_name, const std::string &text);
    // The same with a project already read (read_project).
    void open(AeslProject &&project);

    // Gives a robot without a script the project's program for it: the
    // program of its name and id, else the first of its name, as
    // asebamassloader loads a program into every robot of its name (a swarm
    // runs one controller). Returns whether it got one.
    bool match(NodeKey key, const std::string &robot_name);

    // match() for every robot on the network (`robots`: each one's name);
    // returns the robots given a program.
    std::vector<NodeKey> assign(const std::map<NodeKey, std::string> &robots);

    // The project as .aesl text; `names` gives each robot's name.
    std::string to_aesl(const std::map<NodeKey, std::string> &names) const;

  private:
    // The program for a robot: same name and id, else the first of its name.
    const AeslNode *program_for(NodeKey key, const std::string &robot_name) const;
};

// The project in `text` (named `file_name` in errors); throws ProjectError.
AeslProject read_project(const std::string &file_name, const std::string &text);

// Reads a whole file; throws ProjectError.
std::string read_project_file(const std::string &path);

// Replaces `path` with `text` through a temporary file, so that a crash or a
// full disk never leaves a half-written project; throws ProjectError.
void write_project_file(const std::string &path, const std::string &text);

} // namespace aseba::ide
