#include "child_process.hpp"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <poll.h>
#include <sstream>
#include <stdexcept>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace interop
{

namespace
{

// Time a child has to end by itself after SIGTERM before it gets SIGKILL.
constexpr Milliseconds stop_grace_period{ 2000 };
// How often waiting loops look at the child again.
constexpr Milliseconds poll_interval{ 10 };
// Exit code of a child whose exec failed (the shell's convention).
constexpr int exec_failed_code = 127;

} // namespace

ChildProcess::ChildProcess(std::vector<std::string> argv,
                           const std::string &log_path,
                           OutputMode mode)
  : argv_(std::move(argv))
{
    if (argv_.empty())
        throw std::invalid_argument("ChildProcess: empty command line");

    // Everything the child needs is prepared before fork: after it, the
    // child may only make async-signal-safe calls.
    std::vector<char *> arguments;
    for (auto &argument : argv_)
        arguments.push_back(argument.data());
    arguments.push_back(nullptr);

    int log = open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (log < 0)
        throw std::runtime_error("cannot open " + log_path + ": " + strerror(errno));
    int pipe_ends[2] = { -1, -1 };
    if (mode == OutputMode::ToPipe && pipe2(pipe_ends, O_CLOEXEC) != 0) {
        close(log);
        throw std::runtime_error(std::string("cannot create a pipe: ") + strerror(errno));
    }
    int null_input = open("/dev/null", O_RDONLY | O_CLOEXEC);
    pid_t parent = getpid();

    pid_ = fork();
    if (pid_ == 0) {
        // If the test program dies without running destructors (a sanitizer
        // abort, SIGKILL), the kernel still stops this child.
        prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (getppid() != parent)
            _exit(exec_failed_code);
        setpgid(0, 0); // a terminal's Ctrl-C reaches the test, which stops us
        dup2(null_input, STDIN_FILENO);
        dup2(mode == OutputMode::ToPipe ? pipe_ends[1] : log, STDOUT_FILENO);
        dup2(log, STDERR_FILENO);
        execvp(arguments[0], arguments.data());
        _exit(exec_failed_code);
    }
    int fork_error = errno;
    close(log);
    close(null_input);
    if (mode == OutputMode::ToPipe) {
        close(pipe_ends[1]);
        stdout_pipe_ = pipe_ends[0];
    }
    if (pid_ < 0) {
        if (stdout_pipe_ >= 0)
            close(stdout_pipe_);
        throw std::runtime_error(std::string("fork failed: ") + strerror(fork_error));
    }
}

ChildProcess::~ChildProcess()
{
    stop();
    if (stdout_pipe_ >= 0)
        close(stdout_pipe_);
}

std::string ChildProcess::command_line() const
{
    std::string line;
    for (const auto &argument : argv_)
        line += (line.empty() ? "" : " ") + argument;
    return line;
}

bool ChildProcess::reap(int options)
{
    if (ended_)
        return true;
    int status = 0;
    pid_t result = waitpid(pid_, &status, options);
    if (result == pid_) {
        ended_ = true;
        wait_status_ = status;
    }
    return ended_;
}

bool ChildProcess::wait_for_exit(Milliseconds timeout)
{
    auto deadline = Clock::now() + timeout;
    while (!reap(WNOHANG)) {
        if (Clock::now() >= deadline)
            return false;
        std::this_thread::sleep_for(poll_interval);
    }
    return true;
}

bool ChildProcess::running()
{
    return !reap(WNOHANG);
}

std::optional<int> ChildProcess::exit_code() const
{
    if (ended_ && WIFEXITED(wait_status_))
        return WEXITSTATUS(wait_status_);
    return std::nullopt;
}

std::string ChildProcess::exit_description() const
{
    if (!ended_)
        return "still running";
    if (WIFEXITED(wait_status_))
        return "exit code " + std::to_string(WEXITSTATUS(wait_status_));
    if (WIFSIGNALED(wait_status_))
        return "killed by signal " + std::to_string(WTERMSIG(wait_status_)) + " (" +
               strsignal(WTERMSIG(wait_status_)) + ")";
    return "ended with wait status " + std::to_string(wait_status_);
}

std::optional<std::string> ChildProcess::read_line(Milliseconds timeout)
{
    if (stdout_pipe_ < 0)
        return std::nullopt;
    auto deadline = Clock::now() + timeout;
    for (;;) {
        size_t newline = pipe_buffer_.find('\n');
        if (newline != std::string::npos) {
            std::string line = pipe_buffer_.substr(0, newline);
            pipe_buffer_.erase(0, newline + 1);
            return line;
        }
        auto left = std::chrono::duration_cast<Milliseconds>(deadline - Clock::now());
        if (left.count() <= 0)
            return std::nullopt;
        pollfd readable = { stdout_pipe_, POLLIN, 0 };
        if (poll(&readable, 1, int(left.count())) <= 0)
            continue;
        char buffer[512];
        ssize_t count = read(stdout_pipe_, buffer, sizeof buffer);
        if (count <= 0)
            return std::nullopt;
        pipe_buffer_.append(buffer, size_t(count));
    }
}

void ChildProcess::stop()
{
    if (pid_ <= 0 || reap(WNOHANG))
        return;
    kill(pid_, SIGTERM);
    if (wait_for_exit(stop_grace_period))
        return;
    kill(pid_, SIGKILL);
    reap(0);
}

std::string read_file(const std::string &path)
{
    std::ifstream file(path, std::ios::binary);
    std::ostringstream content;
    content << file.rdbuf();
    return content.str();
}

} // namespace interop
