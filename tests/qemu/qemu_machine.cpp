#include "tests/qemu/qemu_machine.hpp"

#include <arpa/inet.h>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <stdexcept>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace qemu_test
{

namespace
{

constexpr auto start_limit = std::chrono::seconds(10);
constexpr auto stop_limit = std::chrono::seconds(3);
constexpr int start_attempts = 3; // a free port may be taken before QEMU binds it

int free_port()
{
    int probe = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t length = sizeof address;
    if (probe < 0 || ::bind(probe, reinterpret_cast<sockaddr *>(&address), length) != 0 ||
        ::getsockname(probe, reinterpret_cast<sockaddr *>(&address), &length) != 0) {
        if (probe >= 0)
            ::close(probe);
        throw std::runtime_error("no free TCP port on 127.0.0.1");
    }
    ::close(probe);
    return ntohs(address.sin_port);
}

int try_connect(int port)
{
    int socket = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(uint16_t(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (socket >= 0 &&
        ::connect(socket, reinterpret_cast<sockaddr *>(&address), sizeof address) == 0) {
        int one = 1;
        ::setsockopt(socket, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
        return socket;
    }
    if (socket >= 0)
        ::close(socket);
    return -1;
}

// Whether the process has ended (and reaps it).
bool ended(pid_t pid)
{
    int status = 0;
    return ::waitpid(pid, &status, WNOHANG) == pid;
}

void stop(pid_t pid)
{
    ::kill(pid, SIGTERM);
    auto deadline = std::chrono::steady_clock::now() + stop_limit;
    while (std::chrono::steady_clock::now() < deadline) {
        if (ended(pid))
            return;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
}

} // namespace

QemuMachine::QemuMachine(const std::string &image, bool icount, Start start)
{
    for (int attempt = 0; attempt < start_attempts; attempt++) {
        port_ = free_port();
        std::string port = std::to_string(port_);
        pid_ = ::fork();
        if (pid_ < 0)
            throw std::runtime_error("cannot start QEMU: fork failed");
        if (pid_ == 0) {
            // QEMU must not outlive a test program that crashes.
            ::prctl(PR_SET_PDEATHSIG, SIGKILL);
            std::vector<const char *> arguments = { "qemu-node.sh", "--port", port.c_str() };
            if (icount)
                arguments.push_back("--icount");
            if (start == Start::on_first_connection)
                arguments.push_back("--wait");
            arguments.push_back(image.c_str());
            arguments.push_back(nullptr);
            ::execv("scripts/qemu-node.sh", const_cast<char *const *>(arguments.data()));
            ::_exit(127);
        }
        auto deadline = std::chrono::steady_clock::now() + start_limit;
        while (std::chrono::steady_clock::now() < deadline && !ended(pid_)) {
            int socket = try_connect(port_);
            if (socket >= 0) {
                if (start == Start::on_first_connection)
                    first_connection_ = socket;
                else
                    ::close(socket);
                return;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        stop(pid_);
        pid_ = -1;
    }
    throw std::runtime_error("QEMU did not start " + image + " (scripts/qemu-node.sh)");
}

QemuMachine::~QemuMachine()
{
    if (pid_ > 0)
        stop(pid_);
}

std::string QemuMachine::target() const
{
    return "tcp:127.0.0.1;" + std::to_string(port_);
}

int QemuMachine::connect() const
{
    int socket = try_connect(port_);
    if (socket < 0)
        throw std::runtime_error("cannot connect to QEMU on port " + std::to_string(port_));
    return socket;
}

void write_all(int socket, const void *bytes, size_t count)
{
    const char *at = static_cast<const char *>(bytes);
    while (count > 0) {
        ssize_t written = ::send(socket, at, count, MSG_NOSIGNAL);
        if (written < 0 && errno == EINTR)
            continue;
        if (written <= 0)
            throw std::runtime_error("the connection to QEMU broke while sending");
        at += written;
        count -= size_t(written);
    }
}

void read_exactly(int socket, void *bytes, size_t count, int timeout_ms)
{
    char *at = static_cast<char *>(bytes);
    auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (count > 0) {
        auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          deadline - std::chrono::steady_clock::now());
        pollfd waiting{ socket, POLLIN, 0 };
        if (left.count() <= 0 || ::poll(&waiting, 1, int(left.count())) <= 0)
            throw std::runtime_error("QEMU's node did not answer within " +
                                     std::to_string(timeout_ms) + " ms");
        ssize_t got = ::recv(socket, at, count, 0);
        if (got < 0 && errno == EINTR)
            continue;
        if (got <= 0)
            throw std::runtime_error("the connection to QEMU closed");
        at += got;
        count -= size_t(got);
    }
}

} // namespace qemu_test
