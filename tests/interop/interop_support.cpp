#include "interop_support.hpp"

#include <arpa/inet.h>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <filesystem>
#include <fstream>
#include <netinet/in.h>
#include <poll.h>
#include <stdexcept>
#include <string_view>
#include <sys/socket.h>
#include <thread>
#include <unistd.h>

namespace interop
{

namespace
{

constexpr const char *programs_folder = "tests/interop/programs/";
// The emulator stops by itself after this long, in case everything else
// failed to stop it; no test runs that long.
constexpr const char *emulator_lifetime_seconds = "120";
constexpr Milliseconds emulator_start_timeout{ 5000 };
// Ports picked by find_free_port may be taken by someone else before the
// emulator binds them: try a few.
constexpr int emulator_start_attempts = 3;
constexpr Milliseconds retry_interval{ 20 };
constexpr std::string_view content_length_field = "Content-Length: ";

int loopback_socket()
{
    int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0)
        throw std::runtime_error(std::string("socket: ") + strerror(errno));
    return fd;
}

sockaddr_in loopback_address(uint16_t port)
{
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = htons(port);
    return address;
}

bool connect_once(int fd, uint16_t port)
{
    sockaddr_in address = loopback_address(port);
    return connect(fd, reinterpret_cast<sockaddr *>(&address), sizeof address) == 0;
}

} // namespace

uint16_t find_free_port()
{
    int fd = loopback_socket();
    sockaddr_in address = loopback_address(0);
    socklen_t length = sizeof address;
    if (bind(fd, reinterpret_cast<sockaddr *>(&address), sizeof address) != 0 ||
        getsockname(fd, reinterpret_cast<sockaddr *>(&address), &length) != 0) {
        std::string reason = strerror(errno);
        close(fd);
        throw std::runtime_error("cannot find a free port: " + reason);
    }
    close(fd);
    return ntohs(address.sin_port);
}

bool wait_until_listening(uint16_t port, Milliseconds timeout)
{
    auto deadline = Clock::now() + timeout;
    for (;;) {
        int fd = loopback_socket();
        bool connected = connect_once(fd, port);
        close(fd);
        if (connected)
            return true;
        if (Clock::now() >= deadline)
            return false;
        std::this_thread::sleep_for(retry_interval);
    }
}

ScratchFolder::ScratchFolder()
{
    const char *base = std::getenv("TMPDIR");
    std::string pattern = std::string(base && *base ? base : "/tmp") + "/interop_test.XXXXXX";
    if (mkdtemp(pattern.data()) == nullptr)
        throw std::runtime_error("cannot create a folder from " + pattern + ": " + strerror(errno));
    path_ = pattern;
}

ScratchFolder::~ScratchFolder()
{
    // The folder holds only the files the tests wrote: no subfolders.
    if (DIR *folder = opendir(path_.c_str())) {
        while (dirent *entry = readdir(folder)) {
            std::string name = entry->d_name;
            if (name != "." && name != "..")
                unlink(file(name).c_str());
        }
        closedir(folder);
    }
    rmdir(path_.c_str());
}

std::string tcp_target(uint16_t port)
{
    return "tcp:localhost;" + std::to_string(port);
}

std::string program_path(const std::string &name)
{
    return programs_folder + name;
}

// build/VARIANT/bin beside build/VARIANT/tests, or the bin folder itself for
// a benchmark program.
std::string our_program_path(const std::string &name)
{
    std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe");
    return (self.parent_path().parent_path() / "bin" / name).string();
}

EmulatedRobots::EmulatedRobots(const ScratchFolder &scratch, unsigned robots)
{
    const char *configured = std::getenv("EPUCK_EMU");
    // Unless EPUCK_EMU says otherwise, the emulator of the same build.
    std::string emulator = configured && *configured ? configured : our_program_path("epuck-emu");
    if (access(emulator.c_str(), X_OK) != 0)
        throw std::runtime_error(emulator + " is not an executable (build it with `make " +
                                 emulator + "` or set EPUCK_EMU)");

    std::string log = scratch.file("epuck-emu.log");
    for (int attempt = 0; attempt < emulator_start_attempts; attempt++) {
        port_ = find_free_port();
        process_ =
          std::make_unique<ChildProcess>(std::vector<std::string>{ emulator,
                                                                   "--port",
                                                                   std::to_string(port_),
                                                                   "--robots",
                                                                   std::to_string(robots),
                                                                   "--duration",
                                                                   emulator_lifetime_seconds },
                                         log,
                                         OutputMode::ToPipe);
        // It prints "epuck-emu: N robots on tcp:port=P" once it listens.
        auto line = process_->read_line(emulator_start_timeout);
        if (line && line->find("tcp:port=" + std::to_string(port_)) != std::string::npos)
            return;
        process_->stop();
        if (line || attempt + 1 == emulator_start_attempts)
            throw std::runtime_error("epuck-emu did not report listening on port " +
                                     std::to_string(port_) + " (first line: '" +
                                     line.value_or("none") + "', " + process_->exit_description() +
                                     "); its log:\n" + read_file(log));
    }
}

ToolRun run_tool(const ScratchFolder &scratch,
                 const std::string &log_name,
                 const std::vector<std::string> &argv,
                 Milliseconds timeout)
{
    std::string log = scratch.file(log_name);
    std::ofstream(log, std::ios::trunc); // only this run's output
    ToolRun run;
    {
        ChildProcess tool(argv, log);
        run.finished_in_time = tool.wait_for_exit(timeout);
        tool.stop();
        run.exit_code = tool.exit_code();
        run.how_it_ended = run.finished_in_time
                             ? tool.exit_description()
                             : "still running after " + std::to_string(timeout.count()) +
                                 " ms, then " + tool.exit_description();
    }
    run.output = read_file(log);
    return run;
}

bool wait_for_text_in_file(const std::string &path, const std::string &text, Milliseconds timeout)
{
    auto deadline = Clock::now() + timeout;
    while (read_file(path).find(text) == std::string::npos) {
        if (Clock::now() >= deadline)
            return false;
        std::this_thread::sleep_for(retry_interval);
    }
    return true;
}

std::optional<HttpResponse> http_request(uint16_t port,
                                         const std::string &method,
                                         const std::string &path,
                                         Milliseconds timeout)
{
    auto deadline = Clock::now() + timeout;
    int fd = loopback_socket();
    if (!connect_once(fd, port)) {
        close(fd);
        return std::nullopt;
    }
    std::string request = method + " " + path +
                          " HTTP/1.1\r\nHost: localhost\r\nContent-Length: 0\r\n"
                          "Connection: close\r\n\r\n";
    if (send(fd, request.data(), request.size(), MSG_NOSIGNAL) != ssize_t(request.size())) {
        close(fd);
        return std::nullopt;
    }
    std::string answer;
    for (;;) {
        auto left = std::chrono::duration_cast<Milliseconds>(deadline - Clock::now());
        pollfd readable = { fd, POLLIN, 0 };
        if (left.count() <= 0 || poll(&readable, 1, int(left.count())) <= 0) {
            close(fd);
            return std::nullopt;
        }
        char buffer[4096];
        ssize_t count = recv(fd, buffer, sizeof buffer, 0);
        if (count <= 0)
            break;
        answer.append(buffer, size_t(count));
        // The server may keep the connection open: stop once the announced
        // body is complete.
        size_t body_start = answer.find("\r\n\r\n");
        size_t length_field = answer.find(content_length_field);
        if (body_start != std::string::npos && length_field != std::string::npos &&
            length_field < body_start) {
            size_t length = std::strtoul(
              answer.c_str() + length_field + content_length_field.size(), nullptr, 10);
            if (answer.size() >= body_start + 4 + length)
                break;
        }
    }
    close(fd);

    // "HTTP/1.1 200 OK\r\n...\r\n\r\nbody"
    HttpResponse response;
    size_t space = answer.find(' ');
    size_t body_start = answer.find("\r\n\r\n");
    if (answer.rfind("HTTP/", 0) != 0 || space == std::string::npos ||
        body_start == std::string::npos)
        return std::nullopt;
    response.status = std::atoi(answer.c_str() + space + 1);
    response.body = answer.substr(body_start + 4);
    return response;
}

} // namespace interop
