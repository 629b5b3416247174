// One Aseba network on a PC: simulated boards and TCP clients (Studio, the
// console, the Debian tools) on a shared bus, the way a Bluetooth-to-TCP
// switch joins real robots. Every frame from one member goes to all others,
// so robots hear each other's events and every tool hears everything; the
// robots' radio between themselves can be cut (relay_robot_events).
//
// The bus moves whole frames only: bytes from a client or a board are cut
// into frames (protocol.md §2) before they are passed on, so two clients
// writing at once never interleave inside a frame on a robot's link.
//
// A robot may also have ports of its own (listen_robot), as each robot of the
// reference simulator has: a client there is like a tool linked to that robot
// alone by Bluetooth.

#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

extern "C" {
#include "hal/host/host_board.h"
}

namespace aseba::host
{

using Frame = std::vector<uint8_t>;

// Cuts a byte stream into Aseba frames.
class FrameReader
{
  public:
    // Takes bytes; false once a header announced a payload above the
    // protocol's maximum: the stream can no longer be followed.
    bool feed(const uint8_t *bytes, size_t count);
    // The next complete frame, if any.
    std::optional<Frame> next();

  private:
    std::vector<uint8_t> pending_;
    bool broken_ = false;
};

class Network
{
  public:
    Network();
    ~Network();
    Network(const Network &) = delete;
    Network &operator=(const Network &) = delete;

    // Accepts clients on `port` of the loopback and other interfaces (0: a
    // port the system chooses); returns the port. Throws std::runtime_error
    // with the system's reason when it cannot.
    uint16_t listen(uint16_t port);

    // Joins a board: its link output comes to the bus, the bus feeds its link.
    void attach(hal_board *board);

    // Accepts clients linked directly to `board` (attached before) on `port`,
    // as listen does; returns the port. Such a client hears that board's
    // frames only, and its frames reach that board only, not the bus nor
    // the board's other direct clients; the board's frames still reach the
    // bus. Throws std::invalid_argument for a board not attached.
    uint16_t listen_robot(hal_board *board, uint16_t port);

    // Moves frames: accepts clients, reads and writes sockets (waiting up to
    // `timeout_ms` for one of them), and feeds boards what their links can
    // take. Call it often; it never waits longer than asked.
    void service(int timeout_ms);

    // Clients connected now.
    size_t client_count() const;

    // Frames that crossed the bus since the start.
    uint64_t frames_moved() const
    {
        return frames_moved_;
    }

    // Whether a user event (type below 0x8000) that a board emits reaches the
    // other boards; on by default. Off cuts the robots' radio between
    // themselves, as for the paper's runs without communication: tools still
    // hear such events, and protocol messages and a tool's events still
    // reach every board.
    void relay_robot_events(bool relay)
    {
        relay_robot_events_ = relay;
    }

    // Called with every frame that crosses the bus (for status and logs).
    void observe(std::function<void(const Frame &)> observer)
    {
        observer_ = std::move(observer);
    }

  private:
    struct Member;
    // A listening socket; its clients join the bus, or link to `robot` alone.
    struct Listener {
        int fd;
        Member *robot;
    };
    // A listening socket on `port`, which it sets to the port chosen for 0.
    static int open_listener(uint16_t &port);
    void broadcast(const Member *from, const Frame &frame);
    void deliver_to_boards();
    void close_client(size_t index, const char *reason);
    static void board_output(void *context, const uint8_t *bytes, uint16_t count);

    std::vector<Listener> listeners_;
    std::vector<std::unique_ptr<Member>> boards_;
    std::vector<std::unique_ptr<Member>> clients_;
    uint64_t frames_moved_ = 0;
    bool relay_robot_events_ = true;
    std::function<void(const Frame &)> observer_;
};

} // namespace aseba::host
