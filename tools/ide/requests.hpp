// What a browser may ask of the IDE server: one JSON object per WebSocket
// message (docs/ide-protocol.md), parsed and checked here into typed
// requests, so that the server's handlers never see a malformed value.

#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "tools/client/network.hpp"
#include "tools/compiler/target.hpp"

namespace aseba::ide
{

using client::NodeKey;

// The longest script a browser may send (the robot's bytecode is far
// smaller; this only keeps a paste of a whole log out of the compiler).
constexpr size_t MAX_SCRIPT_BYTES = 256 * 1024;
// The largest project file a browser may open.
constexpr size_t MAX_PROJECT_BYTES = 2 * 1024 * 1024;
// Global events and constants a project may declare.
constexpr size_t MAX_DEFINITIONS = 1024;

// A message that is not a request the server understands; what() says why.
class RequestError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// "TARGET:ID", the way robots are named between browser and server.
std::string robot_name(NodeKey key);

struct CompileRequest {
    NodeKey robot;
    std::string source;
    // Whether `source` becomes the robot's script; false for a text the page
    // got from the server (so it never sends back a text already replaced).
    bool remember = true;
};

struct LoadRequest {
    struct Program {
        NodeKey robot;
        std::string source;
        std::vector<unsigned> breakpoints; // source lines
    };
    std::vector<Program> programs;
    bool run = true;
};

enum class Action { run, pause, step, stop, reset, store, reboot };

struct ControlRequest {
    std::vector<NodeKey> robots;
    Action action = Action::run;
};

struct BreakpointsRequest {
    NodeKey robot;
    std::vector<unsigned> lines; // the whole set wanted on that robot
};

struct SetVariableRequest {
    NodeKey robot;
    std::string name;
    unsigned index = 0; // first word written, inside the variable
    std::vector<int16_t> values;
};

struct EmitRequest {
    std::string event;
    std::vector<int16_t> arguments;
};

struct DefinitionsRequest {
    CommonDefinitions definitions;
};

struct WatchRequest {
    std::vector<NodeKey> robots; // whose variables this browser shows
};

struct ScriptRequest { // text edited but not to be compiled (a robot offline)
    NodeKey robot;
    std::string source;
};

struct OpenProjectRequest {
    std::string file_name;
    std::string content; // .aesl text
};

struct SaveProjectRequest {
    bool to_server_file = false; // else the text comes back for a download
};

struct BytecodeRequest { // Studio's "save the binary code" (.abo)
    NodeKey robot;
    std::string source;
};

using Request = std::variant<CompileRequest,
                             LoadRequest,
                             ControlRequest,
                             BreakpointsRequest,
                             SetVariableRequest,
                             EmitRequest,
                             DefinitionsRequest,
                             WatchRequest,
                             ScriptRequest,
                             OpenProjectRequest,
                             SaveProjectRequest,
                             BytecodeRequest>;

struct ParsedRequest {
    uint64_t id = 0; // echoed in the reply; 0 when the browser wants none
    Request request;
};

// Parses one browser message; throws RequestError naming the first problem
// (never anything else, whatever the bytes).
ParsedRequest parse_request(std::string_view text);

// The request id of a message, if one can be read even from a bad request
// (so that its error reply reaches the right promise in the browser).
uint64_t request_id_of(std::string_view text);

// The word used for `action` in messages ("run", "store", ...).
const char *action_name(Action action);

} // namespace aseba::ide
