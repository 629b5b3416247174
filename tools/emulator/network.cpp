// The host's Aseba network: POSIX sockets and a frame bus between boards and
// clients.

#include "network.hpp"

#include <algorithm>
#include <arpa/inet.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <stdexcept>
#include <sys/socket.h>
#include <unistd.h>

extern "C" {
#include "vm/node_protocol.h"
}

namespace aseba::host
{

namespace
{

// A client that reads nothing while this much waits for it is dropped, so a
// stalled tool cannot make the simulator's memory grow without bound.
constexpr size_t client_backlog_limit = 4 * 1024 * 1024;
// Where a frame's message type lies (protocol.md §2).
constexpr size_t type_offset = 4;

uint16_t read_u16(const uint8_t *bytes)
{
    return uint16_t(bytes[0] | (bytes[1] << 8));
}

void set_non_blocking(int fd)
{
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
}

} // namespace

bool FrameReader::feed(const uint8_t *bytes, size_t count)
{
    if (broken_)
        return false;
    pending_.insert(pending_.end(), bytes, bytes + count);
    if (pending_.size() >= 2 && read_u16(pending_.data()) > NODE_MAX_PAYLOAD)
        broken_ = true;
    return !broken_;
}

std::optional<Frame> FrameReader::next()
{
    if (broken_ || pending_.size() < NODE_HEADER_SIZE)
        return std::nullopt;
    size_t length = NODE_HEADER_SIZE + read_u16(pending_.data());
    if (pending_.size() < length)
        return std::nullopt;
    Frame frame(pending_.begin(), pending_.begin() + long(length));
    pending_.erase(pending_.begin(), pending_.begin() + long(length));
    if (pending_.size() >= 2 && read_u16(pending_.data()) > NODE_MAX_PAYLOAD)
        broken_ = true;
    return frame;
}

// A board or a client: what it sent, cut into frames, and what waits for it.
struct Network::Member {
    Network *network = nullptr;
    hal_board *board = nullptr; // for a board
    int fd = -1;                // for a client
    Member *robot = nullptr;    // for a client linked to this board alone
    FrameReader reader;
    std::deque<Frame> to_board;
    std::string to_client;
};

Network::Network() = default;

Network::~Network()
{
    for (const Listener &listener : listeners_)
        close(listener.fd);
    for (auto &client : clients_)
        close(client->fd);
}

int Network::open_listener(uint16_t &port)
{
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0)
        throw std::runtime_error(std::string("cannot create a socket: ") + strerror(errno));
    int yes = 1;
    setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_ANY);
    address.sin_port = htons(port);
    if (bind(fd, reinterpret_cast<sockaddr *>(&address), sizeof address) != 0 ||
        ::listen(fd, 8) != 0) {
        std::string reason = strerror(errno);
        close(fd);
        throw std::runtime_error("cannot listen on TCP port " + std::to_string(port) + ": " +
                                 reason);
    }
    socklen_t length = sizeof address;
    getsockname(fd, reinterpret_cast<sockaddr *>(&address), &length);
    port = ntohs(address.sin_port);
    set_non_blocking(fd);
    return fd;
}

uint16_t Network::listen(uint16_t port)
{
    int fd = open_listener(port);
    listeners_.push_back({ fd, nullptr });
    return port;
}

uint16_t Network::listen_robot(hal_board *board, uint16_t port)
{
    auto attached = std::find_if(boards_.begin(), boards_.end(), [board](const auto &member) {
        return member->board == board;
    });
    if (attached == boards_.end())
        throw std::invalid_argument("listen_robot: the board is not on the network");
    int fd = open_listener(port);
    listeners_.push_back({ fd, attached->get() });
    return port;
}

void Network::attach(hal_board *board)
{
    auto member = std::make_unique<Member>();
    member->network = this;
    member->board = board;
    board->link_output = board_output;
    board->link_context = member.get();
    boards_.push_back(std::move(member));
}

void Network::board_output(void *context, const uint8_t *bytes, uint16_t count)
{
    auto *member = static_cast<Member *>(context);
    // The node never announces an oversized frame, so the reader cannot break.
    member->reader.feed(bytes, count);
    while (auto frame = member->reader.next())
        member->network->broadcast(member, *frame);
}

void Network::broadcast(const Member *from, const Frame &frame)
{
    frames_moved_++;
    if (observer_)
        observer_(frame);
    if (from && from->robot) {
        // A client linked directly to one robot talks to it alone.
        from->robot->to_board.push_back(frame);
        return;
    }
    const bool user_event = read_u16(frame.data() + type_offset) < NODE_FIRST_SYSTEM_TYPE;
    const bool from_board = from && from->board;
    if (!from_board || !user_event || relay_robot_events_) {
        for (auto &board : boards_) {
            if (board.get() != from)
                board->to_board.push_back(frame);
        }
    }
    // Direct clients hear their own robot only.
    for (auto &client : clients_) {
        if (client.get() != from && (client->robot == nullptr || client->robot == from))
            client->to_client.append(frame.begin(), frame.end());
    }
}

void Network::close_client(size_t index, const char *reason)
{
    if (reason)
        std::fprintf(stderr, "network: client dropped: %s\n", reason);
    close(clients_[index]->fd);
    clients_.erase(clients_.begin() + long(index));
}

size_t Network::client_count() const
{
    return clients_.size();
}

void Network::deliver_to_boards()
{
    // Feed each link what it can hold, whole frames only.
    for (auto &board : boards_) {
        while (!board->to_board.empty()) {
            const Frame &frame = board->to_board.front();
            if (!host_board_link_deliver(board->board, frame.data(), uint16_t(frame.size())))
                break;
            board->to_board.pop_front();
        }
    }
}

void Network::service(int timeout_ms)
{
    deliver_to_boards();
    // What arrives while waiting reaches the boards before this returns, so
    // that robots answer at their next poll rather than after another wait.
    struct DeliverOnReturn {
        Network *network;
        ~DeliverOnReturn()
        {
            network->deliver_to_boards();
        }
    } deliver_on_return{ this };

    std::vector<pollfd> fds;
    for (const Listener &listener : listeners_)
        fds.push_back({ listener.fd, POLLIN, 0 });
    for (auto &client : clients_)
        fds.push_back({ client->fd, short(POLLIN | (client->to_client.empty() ? 0 : POLLOUT)), 0 });
    if (poll(fds.data(), fds.size(), timeout_ms) <= 0)
        return;

    for (size_t i = 0; i < listeners_.size(); i++) {
        if (!(fds[i].revents & POLLIN))
            continue;
        int fd = accept(listeners_[i].fd, nullptr, nullptr);
        if (fd < 0)
            continue;
        set_non_blocking(fd);
        int yes = 1;
        // Hosts wait for each answer: do not let Nagle hold small frames.
        setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
        auto client = std::make_unique<Member>();
        client->network = this;
        client->fd = fd;
        client->robot = listeners_[i].robot;
        clients_.push_back(std::move(client));
    }

    // Clients that were there when poll was called, in reverse so that
    // closing one does not shift the others' indices.
    size_t polled = fds.size() - listeners_.size();
    for (size_t k = polled; k-- > 0;) {
        Member &client = *clients_[k];
        short events = fds[listeners_.size() + k].revents;
        if (events & POLLIN) {
            uint8_t buffer[4096];
            ssize_t count = read(client.fd, buffer, sizeof buffer);
            if (count <= 0) {
                close_client(k, nullptr);
                continue;
            }
            if (!client.reader.feed(buffer, size_t(count))) {
                close_client(k, "it sent a frame longer than the protocol allows");
                continue;
            }
            while (auto frame = client.reader.next())
                broadcast(&client, *frame);
        }
        if ((events & POLLOUT) && !client.to_client.empty()) {
            ssize_t count = write(client.fd, client.to_client.data(), client.to_client.size());
            if (count > 0)
                client.to_client.erase(0, size_t(count));
        }
        if (events & (POLLERR | POLLHUP)) {
            close_client(k, nullptr);
            continue;
        }
        if (client.to_client.size() > client_backlog_limit)
            close_client(k, "it stopped reading");
    }
}

} // namespace aseba::host
