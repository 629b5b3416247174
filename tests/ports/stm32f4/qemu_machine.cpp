#include "tests/ports/stm32f4/qemu_machine.hpp"

#include <arpa/inet.h>
#include <cerrno>
#include <chrono>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <stdexcept>
#include <sys/socket.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace qemu_test
{

namespace
{

constexpr auto start_limit = std::chrono::seconds(10);
constexpr int start_attempts = 3; // a free port may be taken before QEMU binds it

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

} // namespace

QemuMachine::QemuMachine(const std::string &image, bool icount, Start start)
{
    std::string log = scratch_.file("qemu.log");
    for (int attempt = 0; attempt < start_attempts; attempt++) {
        port_ = interop::find_free_port();
        std::vector<std::string> arguments = { "scripts/qemu-node.sh",
                                               "--port",
                                               std::to_string(port_) };
        if (icount)
            arguments.push_back("--icount");
        if (start == Start::on_first_connection)
            arguments.push_back("--wait");
        arguments.push_back(image);
        process_ = std::make_unique<interop::ChildProcess>(arguments, log);
        auto deadline = std::chrono::steady_clock::now() + start_limit;
        while (std::chrono::steady_clock::now() < deadline && process_->running()) {
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
        process_->stop();
    }
    throw std::runtime_error("QEMU did not start " + image + " (" + process_->command_line() +
                             "); its messages:\n" + interop::read_file(log));
}

QemuMachine::~QemuMachine()
{
    process_->stop();
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
