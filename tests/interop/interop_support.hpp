// What every interoperability test needs around the processes it starts:
// free loopback ports, a private scratch folder, epuck-emu ready to accept
// clients, a reference tool run to completion, and a raw HTTP request.

#ifndef INTEROP_SUPPORT_HPP
#define INTEROP_SUPPORT_HPP

#include "child_process.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace interop
{

// A TCP port on the loopback interface that nothing listens on right now
// (the kernel's choice for a socket bound to port 0).
uint16_t find_free_port();

// Whether something accepts connections on 127.0.0.1:port within `timeout`.
bool wait_until_listening(uint16_t port, Milliseconds timeout);

// A private folder under $TMPDIR (or /tmp), removed with its files.
class ScratchFolder
{
  public:
    ScratchFolder();
    ~ScratchFolder();
    ScratchFolder(const ScratchFolder &) = delete;
    ScratchFolder &operator=(const ScratchFolder &) = delete;

    // The path of a file called `name` in the folder.
    std::string file(const std::string &name) const
    {
        return path_ + "/" + name;
    }

  private:
    std::string path_;
};

// The Dashel target string of a TCP port on this machine.
std::string tcp_target(uint16_t port);

// The path of a test program in tests/interop/programs/.
std::string program_path(const std::string &name);

// One of our programs (epuck-emu, epuck-image) of the same build as the
// running test or benchmark: build/VARIANT/bin/NAME.
std::string our_program_path(const std::string &name);

// epuck-emu with `robots` robots on a free port, listening when constructed
// (throws with the emulator's output otherwise); stopped on destruction.
class EmulatedRobots
{
  public:
    EmulatedRobots(const ScratchFolder &scratch, unsigned robots);

    uint16_t port() const
    {
        return port_;
    }
    std::string target() const
    {
        return tcp_target(port_);
    }
    ChildProcess &process()
    {
        return *process_;
    }

  private:
    uint16_t port_ = 0;
    std::unique_ptr<ChildProcess> process_;
};

// A tool run to completion (or stopped at its time limit).
struct ToolRun {
    bool finished_in_time = false;
    std::optional<int> exit_code; // nullopt if a signal ended it
    std::string how_it_ended;     // "exit code 0", "killed by signal 6 (...)"
    std::string output;           // stdout and stderr
};

// Runs `argv` and waits at most `timeout` for it; `log_name` names its
// output file in `scratch` (emptied first).
ToolRun run_tool(const ScratchFolder &scratch,
                 const std::string &log_name,
                 const std::vector<std::string> &argv,
                 Milliseconds timeout);

// Waits until the file at `path` contains `text`; true if it did in time.
bool wait_for_text_in_file(const std::string &path, const std::string &text, Milliseconds timeout);

struct HttpResponse {
    int status = 0;
    std::string body;
};

// One HTTP/1.1 request with an empty body to 127.0.0.1:port, answer read
// until the server closes; nullopt on connection failure or timeout.
std::optional<HttpResponse> http_request(uint16_t port,
                                         const std::string &method,
                                         const std::string &path,
                                         Milliseconds timeout);

} // namespace interop

#endif
