// What the console's end-to-end tests need around them: epuck-emu on a free
// port, the `aseba` program run with a time limit, and a scratch folder.
// Every process is owned by an object whose destructor stops it (by its
// recorded pid), so nothing outlives a failing test.

#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <sys/types.h>
#include <thread>
#include <vector>

#include "tools/client/wire.hpp"

namespace console_test
{

using Milliseconds = std::chrono::milliseconds;

// A program under test (epuck-emu, aseba, asebac, epuck-image) of the same
// build as the test itself: build/VARIANT/bin/NAME beside
// build/VARIANT/tests/, so that `make test` builds each program once, with
// the sanitizers.
std::string program_path(const std::string &name);

// A private temporary folder, removed with its content at the end.
class ScratchFolder
{
  public:
    ScratchFolder();
    ~ScratchFolder();
    ScratchFolder(const ScratchFolder &) = delete;
    ScratchFolder &operator=(const ScratchFolder &) = delete;
    const std::string &path() const
    {
        return path_;
    }
    // Writes `content` to `name` in the folder; returns the file's path.
    std::string write(const std::string &name, const std::string &content) const;

  private:
    std::string path_;
};

// epuck-emu with `robots` robots, listening on `port` of the loopback (0: a
// free one) once constructed (throws if it does not start within a few
// seconds).
class Emulator
{
  public:
    explicit Emulator(unsigned robots = 1,
                      const std::vector<std::string> &options = {},
                      uint16_t port = 0);
    ~Emulator();
    // Stops it as Ctrl-C would, and waits.
    void stop();
    // Kills it as `kill -9` would (no chance to save or clean anything up),
    // and waits.
    void kill_now();
    Emulator(const Emulator &) = delete;
    Emulator &operator=(const Emulator &) = delete;

    uint16_t port() const
    {
        return port_;
    }
    // "tcp:localhost;PORT".
    std::string target() const;

  private:
    pid_t pid_ = -1;
    uint16_t port_ = 0;
};

struct CommandResult {
    int exit_code = -1; // -1 when killed (time limit or crash)
    std::string out;
    std::string err;
};

// Runs `aseba ARGS` with XDG_STATE_HOME in `state_folder` (so loads are
// recorded there), killing it after `limit`.
CommandResult run_console(const std::vector<std::string> &arguments,
                          const std::string &state_folder,
                          Milliseconds limit = Milliseconds(10000));

// Runs `PROGRAM ARGS` (one of program_path's), killing it after `limit`;
// its standard output goes to `stdout_path` when given (then `out` is empty).
CommandResult run_program(const std::string &program,
                          const std::vector<std::string> &arguments,
                          const std::string &state_folder,
                          Milliseconds limit = Milliseconds(10000),
                          const std::string &stdout_path = "");

// A running `aseba ARGS` (e.g. monitor), or another program of ours, whose
// output is collected when it ends.
class BackgroundConsole
{
  public:
    BackgroundConsole(const std::vector<std::string> &arguments,
                      const std::string &state_folder,
                      const std::string &program = "aseba",
                      const std::string &stdout_path = "");
    ~BackgroundConsole();
    BackgroundConsole(const BackgroundConsole &) = delete;
    BackgroundConsole &operator=(const BackgroundConsole &) = delete;
    // Waits at most `limit` for the end (then kills it) and returns its output.
    CommandResult finish(Milliseconds limit);

  private:
    pid_t pid_ = -1;
    bool own_output_ = true; // out_path_ is its file, read at the end
    std::string out_path_;
    std::string err_path_;
    std::string folder_;
};

// A reference program (searched in PATH) with extra environment variables,
// its output appended to `log_path`; stopped by the destructor.
class ReferenceProgram
{
  public:
    ReferenceProgram(const std::vector<std::string> &arguments,
                     const std::vector<std::string> &environment, // "NAME=VALUE"
                     const std::string &log_path);
    ~ReferenceProgram();
    ReferenceProgram(const ReferenceProgram &) = delete;
    ReferenceProgram &operator=(const ReferenceProgram &) = delete;
    // Whether it still runs (reaps it if it has ended).
    bool running();

  private:
    pid_t pid_ = -1;
};

// A reference node to test a tool against: one e-puck (node id 1) of
// Debian's asebaplayground, headless, behind Debian's asebaswitch (the
// playground serves one client at a time). Throws std::runtime_error when a
// tool is missing or does not start; stopped by the destructor.
class PlaygroundBehindSwitch
{
  public:
    PlaygroundBehindSwitch();
    // "tcp:localhost;PORT" of the switch.
    const std::string &target() const
    {
        return target_;
    }
    // Whether both reference programs still run.
    bool running();

  private:
    ScratchFolder scratch_;
    std::unique_ptr<ReferenceProgram> playground_;
    std::unique_ptr<ReferenceProgram> relay_;
    std::string target_;
};

// A scripted peer on a free loopback port, for clients under test: it
// accepts one connection and answers every frame it receives with the
// frames `answer` returns, in a thread, until destroyed.
class ScriptedPeer
{
  public:
    using Answer = std::function<std::vector<aseba::client::Frame>(const aseba::client::Frame &)>;
    explicit ScriptedPeer(Answer answer);
    ~ScriptedPeer();
    ScriptedPeer(const ScriptedPeer &) = delete;
    ScriptedPeer &operator=(const ScriptedPeer &) = delete;
    // "tcp:127.0.0.1;PORT".
    std::string target() const;

  private:
    void serve();

    Answer answer_;
    int listener_ = -1;
    uint16_t port_ = 0;
    std::thread thread_;
};

// Whether `name` is an executable in PATH.
bool in_path(const std::string &name);

// A loopback TCP port nothing listens on now.
uint16_t find_free_port();

// Whether a socket listens on `port`, read from /proc/net/tcp* without
// connecting (the reference playground may crash if connected to while it
// starts).
bool is_listening(uint16_t port);

// The lines of `text`.
std::vector<std::string> lines_of(const std::string &text);

} // namespace console_test
