// A program started by the interoperability tests (epuck-emu or one of the
// reference Aseba tools), owned by one object: its destructor stops it, so no
// process outlives the test that started it, even when an assertion fails.

#ifndef INTEROP_CHILD_PROCESS_HPP
#define INTEROP_CHILD_PROCESS_HPP

#include <chrono>
#include <optional>
#include <string>
#include <sys/types.h>
#include <vector>

namespace interop
{

using Clock = std::chrono::steady_clock;
using Milliseconds = std::chrono::milliseconds;

// How the child's standard output reaches the test.
enum class OutputMode {
    ToFile, // stdout and stderr both appended to a file
    ToPipe, // stdout to a pipe the test reads line by line, stderr to a file
};

class ChildProcess
{
  public:
    // Starts argv[0] (searched in PATH) with its output sent as `mode` says;
    // `log_path` receives what is not piped. Throws if fork or exec fails.
    ChildProcess(std::vector<std::string> argv,
                 const std::string &log_path,
                 OutputMode mode = OutputMode::ToFile);
    ~ChildProcess();
    ChildProcess(const ChildProcess &) = delete;
    ChildProcess &operator=(const ChildProcess &) = delete;

    // The child's process id, as recorded at fork time.
    pid_t pid() const
    {
        return pid_;
    }

    // The command line, for failure messages.
    std::string command_line() const;

    // Waits at most `timeout` for the child to end; true if it has ended.
    bool wait_for_exit(Milliseconds timeout);

    // Whether the child is still running (reaps it if it has just ended).
    bool running();

    // After the child ended: its exit code, or nullopt if a signal killed it.
    std::optional<int> exit_code() const;

    // After the child ended: "exit code N" or "killed by signal N".
    std::string exit_description() const;

    // Reads one line of the piped stdout (without the newline) within
    // `timeout`; nullopt on timeout or end of output.
    std::optional<std::string> read_line(Milliseconds timeout);

    // Sends SIGTERM, waits a grace period, then SIGKILL; always reaps.
    void stop();

  private:
    bool reap(int options);

    std::vector<std::string> argv_;
    pid_t pid_ = -1;
    bool ended_ = false;
    int wait_status_ = 0;
    int stdout_pipe_ = -1;
    std::string pipe_buffer_;
};

// The whole content of a file ("" if it cannot be read).
std::string read_file(const std::string &path);

} // namespace interop

#endif
