// The host's Aseba network: a frame bus between boards and TCP clients,
// over standalone asio (accepts, writes) and poll() (the wait for bytes).

#include "network.hpp"

#include <asio.hpp>

#include <poll.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <deque>
#include <map>
#include <memory>
#include <stdexcept>

extern "C" {
#include "vm/node_protocol.h"
}

namespace aseba::host
{

namespace
{

// Where a frame's message type lies (protocol.md §2).
constexpr size_t type_offset = 4;
// Bytes taken from a client at a time: at most this many frames' worth can
// overshoot its share before reading stops.
constexpr size_t read_chunk = 1024;
// Socket events handled in one service() call after the first, so that
// a client that never stops sending cannot keep service() from returning.
constexpr int max_events_per_service = 256;
// Passes of service() at most between two looks at the sockets' events
// while clients that were read again had sent more (accepts and writes
// waiting for room are handled at those looks).
constexpr int passes_between_events = 16;
// How long a wait looks at the sockets without sleeping, after a client
// was heard: a host that answers at once is then read without the system
// waking this process (on another core, that wake-up took longer than the
// whole answer: 280,000 events a second with a sleep at once, 550,000 with
// this look first).
constexpr auto busy_look = std::chrono::microseconds(50);
// The robots' frames, in the queue of each board, as one source.
constexpr uint64_t robots_source = 0;
// Frames kept for reuse once delivered, at most: a frame's buffer and its
// count of owners are then not allocated again for each message.
constexpr size_t spare_frames_kept = 256;

uint16_t read_u16(const uint8_t *bytes)
{
    return uint16_t(bytes[0] | (bytes[1] << 8));
}

} // namespace

bool FrameReader::feed(const uint8_t *bytes, size_t count)
{
    if (broken_)
        return false;
    // Drop what earlier frames used before the buffer grows.
    if (consumed_ > 0) {
        pending_.erase(pending_.begin(), pending_.begin() + long(consumed_));
        consumed_ = 0;
    }
    pending_.insert(pending_.end(), bytes, bytes + count);
    if (pending_.size() >= 2 && read_u16(pending_.data()) > NODE_MAX_PAYLOAD)
        broken_ = true;
    return !broken_;
}

std::optional<FrameView> FrameReader::next()
{
    size_t available = pending_.size() - consumed_;
    if (broken_ || available < NODE_HEADER_SIZE)
        return std::nullopt;
    const uint8_t *start = pending_.data() + consumed_;
    size_t length = NODE_HEADER_SIZE + read_u16(start);
    if (available < length)
        return std::nullopt;
    consumed_ += length;
    if (pending_.size() - consumed_ >= 2 &&
        read_u16(pending_.data() + consumed_) > NODE_MAX_PAYLOAD)
        broken_ = true;
    return FrameView{ start, length };
}

template<class Sink>
bool FrameReader::read(const uint8_t *bytes, size_t count, Sink &&sink)
{
    size_t at = 0;
    if (!broken_ && consumed_ == pending_.size()) {
        while (count - at >= NODE_HEADER_SIZE) {
            uint16_t payload = read_u16(bytes + at);
            size_t length = NODE_HEADER_SIZE + payload;
            if (payload > NODE_MAX_PAYLOAD || count - at < length)
                break;
            sink(FrameView{ bytes + at, length });
            at += length;
        }
        if (at == count)
            return true;
    }
    // The rest begins a frame (or announces one too long): through the
    // buffer, as if fed after the frames before it.
    if (!feed(bytes + at, count - at))
        return at > 0;
    while (auto frame = next())
        sink(*frame);
    return true;
}

namespace
{

// A frame on its way to every board: one copy, shared by their queues.
// Its owners are counted by hand, without a shared_ptr's atomic count and
// control block: one thread moves the frames, and a stream of events pays
// for that on each of them.
struct SharedFrame {
    Frame bytes;
    size_t owners = 0;
};

// Frames waiting for one board from one source.
struct SourceQueue {
    std::deque<SharedFrame *> frames; // each counted in its owners
    size_t bytes = 0;
    bool full = false; // a client's queue at its share: the client is not read
};

struct Board;

// Where a board's frames go.
struct Bus {
    virtual void broadcast_from_board(Board &from, FrameView frame) = 0;

  protected:
    ~Bus() = default;
};

// A board on the bus: its output cut into frames, and what waits for it, by
// source (the robots, then each client by number), served in turn.
struct Board {
    Bus *bus = nullptr;
    hal_board *board = nullptr;
    FrameReader reader;
    std::map<uint64_t, SourceQueue> waiting;
    size_t waiting_frames = 0; // in every queue
    uint64_t last_served = robots_source;
    // The queue enqueue found last, looked for again only for another
    // source: a stream comes from one (queues in a map stay where they are).
    uint64_t last_enqueued = robots_source;
    SourceQueue *last_queue = nullptr;
};

// The board's link output, cut into frames for the bus.
void board_output(void *context, const uint8_t *bytes, uint16_t count)
{
    auto *board = static_cast<Board *>(context);
    // The node never announces an oversized frame, so the reader cannot break.
    board->reader.read(
      bytes, count, [board](FrameView frame) { board->bus->broadcast_from_board(*board, frame); });
}

struct Listener;

struct Client : std::enable_shared_from_this<Client> {
    explicit Client(asio::io_context &io)
      : socket(io)
    {
    }
    uint64_t number = 0;
    asio::ip::tcp::socket socket;
    const Listener *listener = nullptr;   // the port it came by
    Board *robot = nullptr;               // a client linked to this board alone
    connections::Clock::time_point heard; // when it last sent something
    FrameReader reader;
    std::array<uint8_t, read_chunk> input{};
    bool read_queued = false; // in reads_queued: read at the next look at the sockets
    bool waiting = false;     // empty at the last read: read when its socket has bytes
    bool read_again = false;  // sent at the last read: read at the next service()
    size_t full_queues = 0;   // boards where this client has its share waiting
    std::string unsent;       // for the client, not yet taken by its socket
    bool writing = false;     // waiting for the socket to take more
    bool closed = false;
};

struct Listener {
    explicit Listener(asio::io_context &io)
      : acceptor(io)
    {
    }
    asio::ip::tcp::acceptor acceptor;
    Board *robot = nullptr;
    connections::PortLimit limit;
    bool accepting = false; // an accept is pending
};

} // namespace

struct Network::State final : Bus {
    // One thread runs it and no other touches it: no locks, not even
    // around each socket (asio's concurrency hint).
    asio::io_context io{ ASIO_CONCURRENCY_HINT_UNSAFE };
    // service() waits for its time even when no socket is open.
    asio::executor_work_guard<asio::io_context::executor_type> work = asio::make_work_guard(io);
    std::vector<std::unique_ptr<Listener>> listeners;
    std::vector<std::unique_ptr<Board>> boards;
    std::vector<std::shared_ptr<Client>> clients;
    uint64_t next_client_number = robots_source + 1;
    uint64_t frames_moved = 0;
    uint64_t frames_dropped = 0;
    bool relay_robot_events = true;
    std::function<void(FrameView)> observer;
    std::vector<SharedFrame *> spare_frames; // owned by none, for make_frame; freed with the state
    int passes_without_events = 0;           // service() calls since the last look
    // Clients to read without waiting, in turn (new ones, ones whose queues
    // emptied, ones whose last read filled the buffer).
    std::vector<std::shared_ptr<Client>> reads_queued;
    // reads_queued as read_queued_clients takes them.
    std::vector<std::shared_ptr<Client>> reading_now;
    // asio may hold a completed accept or write wait, or one it can complete
    // at once: its handlers run at the next look even if no socket is ready.
    bool asio_may_have_work = false;
    bool heard_since_wait = false; // a client's bytes came since the last wait_for_sockets
    std::vector<pollfd> look;      // what wait_for_sockets asks poll() about
    std::vector<std::shared_ptr<Client>> looked; // the client of each entry, none for listeners

    ~State()
    {
        for (auto &board : boards)
            for (auto &[source, queue] : board->waiting)
                for (SharedFrame *frame : queue.frames)
                    release(frame);
        for (SharedFrame *frame : spare_frames)
            delete frame;
        for (auto &client : clients)
            client->socket.close();
        for (auto &listener : listeners)
            listener->acceptor.close();
        clients.clear();
        io.stop();
    }

    uint16_t open_listener(Listener &listener,
                           uint16_t port,
                           const std::string &address,
                           const connections::PortLimit &limit)
    {
        listener.limit = limit;
        std::string where = address + " port " + std::to_string(port);
        try {
            asio::ip::tcp::endpoint endpoint(asio::ip::make_address(address), port);
            listener.acceptor.open(endpoint.protocol());
            listener.acceptor.set_option(asio::ip::tcp::acceptor::reuse_address(true));
            listener.acceptor.bind(endpoint);
            // The system's longest backlog: bursts of connections wait there
            // to be accepted, none is refused or delayed by a retry.
            listener.acceptor.listen(asio::socket_base::max_listen_connections);
        } catch (const std::system_error &error) {
            throw std::runtime_error("cannot listen on " + where + ": " + error.code().message());
        }
        accept(listener);
        return listener.acceptor.local_endpoint().port();
    }

    // Accepts connections as they come; after a failure (no descriptor
    // left, say), again at the next service() rather than at once.
    void accept(Listener &listener)
    {
        listener.accepting = true;
        asio_may_have_work = true; // a connection waiting already is accepted at once
        listener.acceptor.async_accept(
          [this, &listener](std::error_code error, asio::ip::tcp::socket socket) {
              listener.accepting = false;
              if (error == asio::error::operation_aborted)
                  return;
              if (error)
                  return;
              admit(std::move(socket), listener);
              accept(listener);
          });
    }

    // A connection to a full port takes the place of the client that has
    // been silent the longest, if silent for the grace; else it is closed.
    void admit(asio::ip::tcp::socket socket, const Listener &listener)
    {
        bool room = connections::make_room(
          clients,
          [&](const std::shared_ptr<Client> &client) {
              return !client->closed && client->listener == &listener;
          },
          [](const std::shared_ptr<Client> &client) { return client->heard; },
          [this](std::shared_ptr<Client> &client) {
              close(*client, "silent while its port was full");
          },
          listener.limit);
        if (room) {
            add_client(std::move(socket), listener);
            return;
        }
        std::fprintf(stderr,
                     "network: connection closed: its port holds %zu clients already\n",
                     listener.limit.capacity);
        std::error_code ignored;
        socket.close(ignored);
    }

    void add_client(asio::ip::tcp::socket socket, const Listener &listener)
    {
        std::error_code ignored;
        // Hosts wait for each answer: do not let Nagle hold small frames.
        socket.set_option(asio::ip::tcp::no_delay(true), ignored);
        // read_from reads what has come without waiting.
        socket.non_blocking(true, ignored);
        auto client = std::make_shared<Client>(io);
        client->socket = std::move(socket);
        client->number = next_client_number++;
        client->listener = &listener;
        client->robot = listener.robot;
        client->heard = connections::Clock::now();
        clients.push_back(client);
        start_read(client);
    }

    // Reads the client again (a new one, or one whose queues had filled):
    // bytes may have come meanwhile, so read before waiting, at the next
    // look at the sockets (the other clients get their turn first).
    void start_read(const std::shared_ptr<Client> &client)
    {
        if (client->closed || client->read_queued || client->full_queues > 0)
            return;
        client->read_queued = true;
        reads_queued.push_back(client);
    }

    // The reads queued by start_read; those they queue again (a read that
    // filled the buffer) wait for the next look.
    void read_queued_clients()
    {
        reading_now.swap(reads_queued);
        for (const auto &client : reading_now) {
            client->read_queued = false;
            read_from(client);
        }
        reading_now.clear();
    }

    // One read of what the client sent, passed on frame by frame; returns
    // whether bytes came. A read that fills the buffer may have left more:
    // the next one is posted, so that other sockets get their turn in
    // between. After a shorter one the client is read again at the next
    // service(), before any wait: a client that streams has sent more by
    // then, and that read saves a wait and a system call to start it.
    bool read_from(const std::shared_ptr<Client> &client)
    {
        if (client->closed || client->full_queues > 0)
            return false;
        std::error_code error;
        size_t count = client->socket.read_some(asio::buffer(client->input), error);
        // An empty socket: wait_for_sockets watches it until bytes come.
        client->waiting = error == asio::error::would_block || error == asio::error::try_again;
        if (client->waiting)
            return false;
        if (error) {
            close(*client, nullptr); // closed by the peer, or failed
            return false;
        }
        client->heard = connections::Clock::now();
        heard_since_wait = true;
        if (!client->reader.read(client->input.data(), count, [this, &client](FrameView frame) {
                broadcast_from_client(*client, frame);
            })) {
            close(*client, "it sent a frame longer than the protocol allows");
            return true;
        }
        if (client->closed || client->full_queues > 0)
            return true; // deliver_to_boards reads it again once there is room
        if (count == client->input.size())
            start_read(client);
        else
            client->read_again = true;
        return true;
    }

    // Reads the clients marked by read_from; returns whether any had sent
    // more.
    bool read_clients_again()
    {
        bool heard = false;
        for (const auto &client : clients) {
            if (!client->read_again)
                continue;
            client->read_again = false;
            heard |= read_from(client);
        }
        return heard;
    }

    // Waits up to `timeout_ms` for a socket to be ready, then handles what
    // is: the clients with bytes are read, once each; accepts and the ends
    // of write waits are asio's. The wait for bytes is a poll() of its own
    // rather than one of asio's: a read that finds its socket empty, the
    // common end of a stream of events, then costs no operation to start,
    // queue and complete (some 1,300 host instructions each).
    void wait_for_sockets(int timeout_ms)
    {
        look.clear();
        looked.clear();
        for (const auto &client : clients) {
            short events = short((client->waiting ? POLLIN : 0) | (client->writing ? POLLOUT : 0));
            if (client->closed || events == 0)
                continue;
            look.push_back(pollfd{ client->socket.native_handle(), events, 0 });
            looked.push_back(client);
        }
        for (const auto &listener : listeners)
            if (listener->accepting)
                look.push_back(pollfd{ listener->acceptor.native_handle(), POLLIN, 0 });
        if (timeout_ms < 0 || asio_may_have_work || !reads_queued.empty())
            timeout_ms = 0;
        int ready = 0;
        if (timeout_ms > 0 && heard_since_wait) {
            const auto until = std::chrono::steady_clock::now() + busy_look;
            do
                ready = ::poll(look.data(), nfds_t(look.size()), 0);
            while (ready == 0 && std::chrono::steady_clock::now() < until);
        }
        heard_since_wait = false;
        if (ready == 0)
            ready = ::poll(look.data(), nfds_t(look.size()), timeout_ms);
        bool asio_ready = asio_may_have_work;
        for (size_t i = 0; ready > 0 && i < look.size(); i++) {
            if (look[i].revents == 0)
                continue;
            ready--;
            // Bytes, an end or an error: the read tells which.
            if (i < looked.size() && looked[i]->waiting && (look[i].revents & ~POLLOUT) != 0)
                read_from(looked[i]);
            if (i >= looked.size() || (look[i].revents & POLLOUT) != 0)
                asio_ready = true;
        }
        if (asio_ready) {
            asio_may_have_work = false;
            int handled = 0;
            while (handled < max_events_per_service && io.poll_one() > 0)
                handled++;
            if (handled == max_events_per_service)
                asio_may_have_work = true;
        }
        read_queued_clients();
    }

    // Sends what waits for the client, as much as its socket takes now, in
    // one system call for every frame gathered since the last time; the
    // rest once the socket can take more.
    void flush(const std::shared_ptr<Client> &client)
    {
        if (client->closed || client->writing || client->unsent.empty())
            return;
        std::error_code error;
        size_t sent = client->socket.write_some(asio::buffer(client->unsent), error);
        if (error && error != asio::error::would_block && error != asio::error::try_again) {
            close(*client, nullptr);
            return;
        }
        client->unsent.erase(0, sent);
        if (client->unsent.empty())
            return;
        client->writing = true;
        asio_may_have_work = true;
        client->socket.async_wait(asio::ip::tcp::socket::wait_write,
                                  [this, client](std::error_code wait_error) {
                                      client->writing = false;
                                      if (client->closed)
                                          return;
                                      if (wait_error) {
                                          close(*client, nullptr);
                                          return;
                                      }
                                      flush(client);
                                  });
    }

    void flush_clients()
    {
        for (auto &client : clients)
            flush(client);
    }

    // Closes the client's socket; it leaves `clients` at the next sweep.
    // The frames it sent stay queued for the boards (a tool may send a
    // command and hang up at once, as asebacmd does).
    void close(Client &client, const char *reason)
    {
        if (client.closed)
            return;
        if (reason)
            std::fprintf(stderr, "network: client dropped: %s\n", reason);
        client.closed = true;
        std::error_code ignored;
        client.socket.close(ignored);
    }

    void sweep()
    {
        clients.erase(std::remove_if(clients.begin(),
                                     clients.end(),
                                     [](const auto &client) { return client->closed; }),
                      clients.end());
        for (auto &listener : listeners)
            if (!listener->accepting)
                accept(*listener);
    }

    Client *client_numbered(uint64_t number) const
    {
        for (const auto &client : clients)
            if (client->number == number)
                return client.get();
        return nullptr;
    }

    // A frame holding `frame`'s bytes, from the spares when one is left,
    // owned by the caller until it calls release.
    SharedFrame *make_frame(FrameView frame)
    {
        SharedFrame *made;
        if (spare_frames.empty()) {
            made = new SharedFrame;
        } else {
            made = spare_frames.back();
            spare_frames.pop_back();
        }
        made->bytes.assign(frame.bytes, frame.bytes + frame.size);
        made->owners = 1;
        return made;
    }

    // Drops one owner of `frame`; without owners it is kept for reuse, or
    // freed when enough are kept.
    void release(SharedFrame *frame)
    {
        if (--frame->owners > 0)
            return;
        if (spare_frames.size() < spare_frames_kept)
            spare_frames.push_back(frame);
        else
            delete frame;
    }

    void enqueue(Board &board, uint64_t source, SharedFrame *frame)
    {
        if (board.last_queue == nullptr || board.last_enqueued != source) {
            board.last_queue = &board.waiting[source];
            board.last_enqueued = source;
        }
        SourceQueue &queue = *board.last_queue;
        if (source == robots_source && queue.frames.size() >= ROBOT_FRAMES_PER_ROBOT) {
            frames_dropped++;
            return;
        }
        queue.frames.push_back(frame);
        frame->owners++;
        queue.bytes += frame->bytes.size();
        board.waiting_frames++;
        if (source != robots_source && !queue.full &&
            (queue.frames.size() >= CLIENT_FRAMES_PER_ROBOT ||
             queue.bytes >= CLIENT_BYTES_PER_ROBOT)) {
            queue.full = true;
            if (auto client = client_numbered(source))
                client->full_queues++;
        }
    }

    void count(FrameView frame)
    {
        frames_moved++;
        if (observer)
            observer(frame);
    }

    void send_to_clients(const Board *from_board, const Client *from_client, FrameView frame)
    {
        // Direct clients hear their own robot only.
        for (auto &client : clients) {
            if (client->closed || client.get() == from_client ||
                (client->robot != nullptr && client->robot != from_board))
                continue;
            client->unsent.append(reinterpret_cast<const char *>(frame.bytes), frame.size);
            if (client->unsent.size() > CLIENT_UNREAD_LIMIT)
                close(*client, "it stopped reading");
        }
    }

    void broadcast_from_board(Board &from, FrameView frame) override
    {
        const bool user_event = read_u16(frame.bytes + type_offset) < NODE_FIRST_SYSTEM_TYPE;
        count(frame);
        if ((!user_event || relay_robot_events) && boards.size() > 1) {
            SharedFrame *shared = make_frame(frame);
            for (auto &board : boards)
                if (board.get() != &from)
                    enqueue(*board, robots_source, shared);
            release(shared);
        }
        send_to_clients(&from, nullptr, frame);
    }

    // A client's frame goes straight into a board's link when nothing waits
    // for that board (the order and the turns of the sources are then those
    // of the queues, which would hand it over at once): a stream of events
    // from a tool is not copied into a frame of the queues for each of them.
    // Else it waits in `shared`, made at the first board that needs it.
    void deliver_from_client(Board &board, uint64_t source, FrameView frame, SharedFrame *&shared)
    {
        if (board.waiting_frames == 0 &&
            host_board_link_deliver(board.board, frame.bytes, uint16_t(frame.size)))
            return;
        if (shared == nullptr)
            shared = make_frame(frame);
        enqueue(board, source, shared);
    }

    void broadcast_from_client(const Client &from, FrameView frame)
    {
        SharedFrame *shared = nullptr;
        count(frame);
        if (from.robot != nullptr) {
            // A client linked directly to one robot talks to it alone.
            deliver_from_client(*from.robot, from.number, frame, shared);
        } else {
            for (auto &board : boards)
                deliver_from_client(*board, from.number, frame, shared);
            send_to_clients(nullptr, &from, frame);
        }
        if (shared != nullptr)
            release(shared);
    }

    // The next source with frames for `board`, after the last one served;
    // end() when none has any.
    std::map<uint64_t, SourceQueue>::iterator next_source(Board &board)
    {
        auto found = board.waiting.upper_bound(board.last_served);
        for (size_t tried = 0; tried < board.waiting.size(); tried++, ++found) {
            if (found == board.waiting.end())
                found = board.waiting.begin();
            if (!found->second.frames.empty())
                return found;
        }
        return board.waiting.end();
    }

    // Feeds each link what it can hold, whole frames only, a frame from each
    // source in turn. Queues stay for the next frames (the robots' one
    // always), but a departed client's goes once empty.
    void deliver_to_boards()
    {
        for (auto &board : boards) {
            while (board->waiting_frames > 0) {
                auto source = next_source(*board);
                SourceQueue &queue = source->second;
                SharedFrame *frame = queue.frames.front();
                if (!host_board_link_deliver(
                      board->board, frame->bytes.data(), uint16_t(frame->bytes.size())))
                    break;
                queue.bytes -= frame->bytes.size();
                queue.frames.pop_front();
                release(frame);
                board->waiting_frames--;
                board->last_served = source->first;
                if (source->first == robots_source)
                    continue;
                // The client is looked for only when its queue stops being
                // full or empties, not at every frame.
                if (queue.full && queue.frames.size() < CLIENT_FRAMES_PER_ROBOT &&
                    queue.bytes < CLIENT_BYTES_PER_ROBOT) {
                    queue.full = false;
                    if (Client *client = client_numbered(source->first)) {
                        client->full_queues--;
                        start_read(client->shared_from_this());
                    }
                }
                if (queue.frames.empty() && !client_numbered(source->first)) {
                    if (board->last_queue == &queue)
                        board->last_queue = nullptr;
                    board->waiting.erase(source);
                }
            }
        }
    }
};

Network::Network()
  : state_(std::make_unique<State>())
{
}

Network::~Network() = default;

uint16_t Network::listen(uint16_t port,
                         const std::string &address,
                         const connections::PortLimit &limit)
{
    auto listener = std::make_unique<Listener>(state_->io);
    uint16_t chosen = state_->open_listener(*listener, port, address, limit);
    state_->listeners.push_back(std::move(listener));
    return chosen;
}

uint16_t Network::listen_robot(hal_board *board,
                               uint16_t port,
                               const std::string &address,
                               const connections::PortLimit &limit)
{
    auto attached = std::find_if(state_->boards.begin(),
                                 state_->boards.end(),
                                 [board](const auto &member) { return member->board == board; });
    if (attached == state_->boards.end())
        throw std::invalid_argument("listen_robot: the board is not on the network");
    auto listener = std::make_unique<Listener>(state_->io);
    listener->robot = attached->get();
    uint16_t chosen = state_->open_listener(*listener, port, address, limit);
    state_->listeners.push_back(std::move(listener));
    return chosen;
}

void Network::attach(hal_board *board)
{
    auto member = std::make_unique<Board>();
    member->bus = state_.get();
    member->board = board;
    board->link_output = board_output;
    board->link_context = member.get();
    state_->boards.push_back(std::move(member));
}

void Network::service(int timeout_ms)
{
    State &state = *state_;
    // What the boards said since the last call leaves before any wait.
    state.flush_clients();
    state.deliver_to_boards();
    bool heard = state.read_clients_again();
    // Waits if asked to, unless a client has just been heard; a client that
    // streams is read again at each call, and the other sockets are looked
    // at every passes_between_events calls meanwhile.
    if (!heard || ++state.passes_without_events >= passes_between_events) {
        state.passes_without_events = 0;
        if (state.io.stopped())
            state.io.restart();
        state.wait_for_sockets(heard ? 0 : timeout_ms);
    }
    state.sweep();
    // What arrived while waiting reaches the boards before this returns, so
    // that robots answer at their next poll rather than after another wait.
    state.deliver_to_boards();
    state.flush_clients();
}

size_t Network::client_count() const
{
    size_t open = 0;
    for (const auto &client : state_->clients)
        open += client->closed ? 0 : 1;
    return open;
}

uint64_t Network::frames_moved() const
{
    return state_->frames_moved;
}

size_t Network::held_bytes() const
{
    size_t bytes = 0;
    for (const auto &board : state_->boards)
        for (const auto &[source, queue] : board->waiting)
            bytes += queue.bytes;
    for (const auto &client : state_->clients)
        bytes += client->unsent.size();
    return bytes;
}

uint64_t Network::frames_dropped() const
{
    return state_->frames_dropped;
}

void Network::relay_robot_events(bool relay)
{
    state_->relay_robot_events = relay;
}

void Network::observe(std::function<void(FrameView)> observer)
{
    state_->observer = std::move(observer);
}

} // namespace aseba::host
