// Processes and files for the console's end-to-end tests.

#include "console_support.hpp"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <optional>
#include <netinet/in.h>
#include <poll.h>
#include <sstream>
#include <stdexcept>
#include <sys/socket.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace console_test
{

namespace
{

using Clock = std::chrono::steady_clock;

constexpr Milliseconds EMULATOR_START_LIMIT{ 5000 };
constexpr Milliseconds STOP_GRACE{ 2000 };
constexpr Milliseconds REAP_INTERVAL{ 5 };
// epuck-emu stops by itself after this, should a test process die unclean.
constexpr const char *EMULATOR_SAFETY_SECONDS = "120";

} // namespace

std::string program_path(const std::string &name)
{
    std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe");
    return (self.parent_path().parent_path() / "bin" / name).string();
}

uint16_t find_free_port()
{
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = 0;
    socklen_t length = sizeof address;
    if (fd < 0 || bind(fd, reinterpret_cast<sockaddr *>(&address), sizeof address) != 0 ||
        getsockname(fd, reinterpret_cast<sockaddr *>(&address), &length) != 0)
        throw std::runtime_error(std::string("no free port: ") + std::strerror(errno));
    close(fd);
    return ntohs(address.sin_port);
}

namespace
{

std::vector<char *> argv_of(std::vector<std::string> &arguments)
{
    std::vector<char *> argv;
    for (std::string &argument : arguments)
        argv.push_back(argument.data());
    argv.push_back(nullptr);
    return argv;
}

// Waits for `pid` at most `limit`; returns the wait status, or nullopt.
std::optional<int> wait_for(pid_t pid, Milliseconds limit)
{
    auto deadline = Clock::now() + limit;
    while (true) {
        int status = 0;
        pid_t ended = waitpid(pid, &status, WNOHANG);
        if (ended == pid)
            return status;
        if (ended < 0 || Clock::now() >= deadline)
            return std::nullopt;
        std::this_thread::sleep_for(REAP_INTERVAL);
    }
}

// SIGTERM, a grace period, then SIGKILL; always reaps.
void stop_process(pid_t pid)
{
    if (pid <= 0)
        return;
    kill(pid, SIGTERM);
    if (!wait_for(pid, STOP_GRACE)) {
        kill(pid, SIGKILL);
        waitpid(pid, nullptr, 0);
    }
}

// Starts `arguments` with stdout/stderr to the given files (or `stdout_fd`).
pid_t start(std::vector<std::string> arguments,
            const std::string &state_folder,
            int stdout_fd,
            const std::string &out_path,
            const std::string &err_path)
{
    std::vector<char *> argv = argv_of(arguments);
    pid_t pid = fork();
    if (pid < 0)
        throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
    if (pid == 0) {
        if (!state_folder.empty())
            setenv("XDG_STATE_HOME", state_folder.c_str(), 1);
        int out =
          stdout_fd >= 0 ? stdout_fd : open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int err = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (out < 0 || err < 0)
            _exit(126);
        dup2(out, STDOUT_FILENO);
        dup2(err, STDERR_FILENO);
        execv(argv[0], argv.data());
        _exit(127);
    }
    return pid;
}

std::string read_whole_file(const std::string &path)
{
    std::ifstream file(path);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

int exit_code_of(std::optional<int> status)
{
    if (status && WIFEXITED(*status))
        return WEXITSTATUS(*status);
    return -1;
}

} // namespace

ScratchFolder::ScratchFolder()
{
    std::string pattern =
      (std::filesystem::temp_directory_path() / "aseba-console-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr)
        throw std::runtime_error(std::string("mkdtemp failed: ") + std::strerror(errno));
    path_ = pattern;
}

ScratchFolder::~ScratchFolder()
{
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
}

std::string ScratchFolder::write(const std::string &name, const std::string &content) const
{
    std::string file = path_ + "/" + name;
    std::ofstream(file) << content;
    return file;
}

Emulator::Emulator(unsigned robots, const std::vector<std::string> &options, uint16_t port)
{
    port_ = port != 0 ? port : find_free_port();
    int output[2];
    if (pipe(output) != 0)
        throw std::runtime_error("pipe failed");
    std::vector<std::string> arguments = { program_path("epuck-emu"), "--port",
                                           std::to_string(port_),     "--robots",
                                           std::to_string(robots),    "--duration",
                                           EMULATOR_SAFETY_SECONDS };
    arguments.insert(arguments.end(), options.begin(), options.end());
    pid_ = start(arguments, "", output[1], "", "/dev/null");
    close(output[1]);
    // Ready when it says where it listens.
    std::string seen;
    auto deadline = Clock::now() + EMULATOR_START_LIMIT;
    while (seen.find("robot") == std::string::npos || seen.find('\n') == std::string::npos) {
        auto left = std::chrono::duration_cast<Milliseconds>(deadline - Clock::now());
        pollfd waiting{ output[0], POLLIN, 0 };
        char buffer[256];
        ssize_t count = 0;
        if (left.count() <= 0 || poll(&waiting, 1, int(left.count())) <= 0 ||
            (count = read(output[0], buffer, sizeof buffer)) <= 0) {
            close(output[0]);
            stop_process(pid_);
            throw std::runtime_error(program_path("epuck-emu") + " did not start (output: '" +
                                     seen + "')");
        }
        seen.append(buffer, size_t(count));
    }
    // Its later output is not read: it only prints again when it stops.
    close(output[0]);
}

Emulator::~Emulator()
{
    stop();
}

void Emulator::stop()
{
    stop_process(pid_);
    pid_ = -1;
}

void Emulator::kill_now()
{
    if (pid_ > 0) {
        kill(pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
    }
    pid_ = -1;
}

std::string Emulator::target() const
{
    return "tcp:localhost;" + std::to_string(port_);
}

CommandResult run_console(const std::vector<std::string> &arguments,
                          const std::string &state_folder,
                          Milliseconds limit)
{
    BackgroundConsole console(arguments, state_folder);
    return console.finish(limit);
}

CommandResult run_program(const std::string &program,
                          const std::vector<std::string> &arguments,
                          const std::string &state_folder,
                          Milliseconds limit,
                          const std::string &stdout_path)
{
    BackgroundConsole running(arguments, state_folder, program, stdout_path);
    return running.finish(limit);
}

BackgroundConsole::BackgroundConsole(const std::vector<std::string> &arguments,
                                     const std::string &state_folder,
                                     const std::string &program,
                                     const std::string &stdout_path)
  : folder_(state_folder)
{
    static unsigned counter = 0;
    std::string stem =
      state_folder + "/console-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
    own_output_ = stdout_path.empty();
    out_path_ = own_output_ ? stem + ".out" : stdout_path;
    err_path_ = stem + ".err";
    std::vector<std::string> command{ program_path(program) };
    command.insert(command.end(), arguments.begin(), arguments.end());
    pid_ = start(command, state_folder, -1, out_path_, err_path_);
}

BackgroundConsole::~BackgroundConsole()
{
    stop_process(pid_);
}

CommandResult BackgroundConsole::finish(Milliseconds limit)
{
    CommandResult result;
    std::optional<int> status = wait_for(pid_, limit);
    if (!status) {
        stop_process(pid_);
        result.err = "(killed after " + std::to_string(limit.count()) + " ms)\n";
    }
    pid_ = -1;
    result.exit_code = exit_code_of(status);
    if (own_output_)
        result.out = read_whole_file(out_path_);
    result.err += read_whole_file(err_path_);
    return result;
}

std::vector<std::string> lines_of(const std::string &text)
{
    std::vector<std::string> lines;
    std::istringstream stream(text);
    std::string line;
    while (std::getline(stream, line))
        lines.push_back(line);
    return lines;
}

ReferenceProgram::ReferenceProgram(const std::vector<std::string> &arguments,
                                   const std::vector<std::string> &environment,
                                   const std::string &log_path)
{
    std::vector<std::string> owned = arguments;
    std::vector<char *> argv = argv_of(owned);
    pid_ = fork();
    if (pid_ < 0)
        throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
    if (pid_ == 0) {
        for (const std::string &setting : environment)
            putenv(const_cast<char *>(setting.c_str()));
        int log = open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
        if (log < 0)
            _exit(126);
        dup2(log, STDOUT_FILENO);
        dup2(log, STDERR_FILENO);
        execvp(argv[0], argv.data());
        _exit(127);
    }
}

ReferenceProgram::~ReferenceProgram()
{
    stop_process(pid_);
}

bool ReferenceProgram::running()
{
    if (pid_ <= 0)
        return false;
    if (waitpid(pid_, nullptr, WNOHANG) == pid_) {
        pid_ = -1;
        return false;
    }
    return true;
}

bool in_path(const std::string &name)
{
    const char *path = std::getenv("PATH");
    std::istringstream folders(path != nullptr ? path : "");
    std::string folder;
    while (std::getline(folders, folder, ':'))
        if (!folder.empty() && access((folder + "/" + name).c_str(), X_OK) == 0)
            return true;
    return false;
}

bool is_listening(uint16_t port)
{
    const char listen_state[] = "0A";
    for (const char *table : { "/proc/net/tcp", "/proc/net/tcp6" }) {
        std::ifstream file(table);
        std::string line;
        std::getline(file, line); // the header
        while (std::getline(file, line)) {
            std::istringstream fields(line);
            std::string slot, local, remote, state;
            fields >> slot >> local >> remote >> state;
            size_t colon = local.rfind(':');
            if (colon == std::string::npos)
                continue;
            unsigned long local_port = std::strtoul(local.c_str() + colon + 1, nullptr, 16);
            if (local_port == port && state == listen_state)
                return true;
        }
    }
    return false;
}

ScriptedPeer::ScriptedPeer(Answer answer)
  : answer_(std::move(answer))
{
    listener_ = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t length = sizeof address;
    if (listener_ < 0 ||
        bind(listener_, reinterpret_cast<sockaddr *>(&address), sizeof address) != 0 ||
        listen(listener_, 1) != 0 ||
        getsockname(listener_, reinterpret_cast<sockaddr *>(&address), &length) != 0)
        throw std::runtime_error(std::string("scripted peer: ") + std::strerror(errno));
    port_ = ntohs(address.sin_port);
    thread_ = std::thread([this] { serve(); });
}

ScriptedPeer::~ScriptedPeer()
{
    // Ends a waiting accept() or read().
    shutdown(listener_, SHUT_RDWR);
    close(listener_);
    thread_.join();
}

std::string ScriptedPeer::target() const
{
    return "tcp:127.0.0.1;" + std::to_string(port_);
}

void ScriptedPeer::serve()
{
    int fd = accept(listener_, nullptr, nullptr);
    if (fd < 0)
        return;
    aseba::client::FrameAssembler assembler;
    uint8_t buffer[4096];
    ssize_t count;
    while ((count = read(fd, buffer, sizeof buffer)) > 0) {
        assembler.feed(buffer, size_t(count));
        while (std::optional<aseba::client::Frame> frame = assembler.next()) {
            for (const aseba::client::Frame &reply : answer_(*frame)) {
                std::vector<uint8_t> bytes = aseba::client::serialize_frame(reply);
                (void)!write(fd, bytes.data(), bytes.size());
            }
        }
    }
    close(fd);
}

namespace
{

// The playground may crash when a client connects while it starts: it is
// given this long once its port listens.
const Milliseconds PLAYGROUND_SETTLE{ 1000 };
const Milliseconds REFERENCE_START_LIMIT{ 10000 };

void wait_listening(uint16_t port, ReferenceProgram &program, const std::string &name)
{
    auto deadline = std::chrono::steady_clock::now() + REFERENCE_START_LIMIT;
    while (!is_listening(port)) {
        if (!program.running() || std::chrono::steady_clock::now() > deadline)
            throw std::runtime_error(name + " did not start");
        std::this_thread::sleep_for(Milliseconds(50));
    }
}

} // namespace

PlaygroundBehindSwitch::PlaygroundBehindSwitch()
{
    // The project's install script provides them; a missing tool is a failure.
    if (!in_path("asebaplayground") || !in_path("asebaswitch"))
        throw std::runtime_error(
          "Debian's aseba tools are not installed: run scripts/install-deps.sh test");
    uint16_t robot_port = find_free_port();
    // A small arena with one e-puck listening on robot_port, node id 1.
    std::string scene =
      scratch_.write("arena.playground",
                     "<!DOCTYPE aseba-playground>\n<aseba-playground>\n"
                     "<color name=\"wall\" r=\"0.9\" g=\"0.9\" b=\"0.9\"/>\n"
                     "<world w=\"110\" h=\"110\" color=\"wall\"/>\n"
                     "<robot type=\"e-puck\" x=\"40\" y=\"40\" port=\"" +
                       std::to_string(robot_port) + "\" nodeId=\"1\"/>\n</aseba-playground>\n");
    playground_ = std::make_unique<ReferenceProgram>(
      std::vector<std::string>{ "asebaplayground", scene },
      std::vector<std::string>{ "QT_QPA_PLATFORM=offscreen", "XDG_RUNTIME_DIR=" + scratch_.path() },
      scratch_.path() + "/playground.log");
    wait_listening(robot_port, *playground_, "asebaplayground");
    std::this_thread::sleep_for(PLAYGROUND_SETTLE);

    uint16_t switch_port = find_free_port();
    relay_ = std::make_unique<ReferenceProgram>(
      std::vector<std::string>{ "asebaswitch",
                                "-p",
                                std::to_string(switch_port),
                                "tcp:localhost;" + std::to_string(robot_port) },
      std::vector<std::string>{},
      scratch_.path() + "/switch.log");
    wait_listening(switch_port, *relay_, "asebaswitch");
    target_ = "tcp:localhost;" + std::to_string(switch_port);
}

bool PlaygroundBehindSwitch::running()
{
    return playground_->running() && relay_->running();
}

} // namespace console_test
