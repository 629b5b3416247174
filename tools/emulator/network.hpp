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
// No client can take the network for itself: each robot takes frames from
// its sources in turn (the robots, then each client), a client may have only
// a few frames waiting for any robot (then it is not read until they go, so
// TCP slows it down), and a client that reads nothing while a megabyte waits
// for it is dropped. Each port holds its own number of clients
// (tools/connections/port_limit.hpp): a connection beyond takes the place of
// the client silent the longest if that one has said nothing for the grace,
// else it is closed at once. Memory stays bounded whatever clients send.
//
// A robot may also have ports of its own (listen_robot), as each robot of the
// reference simulator has: a client there is like a tool linked to that robot
// alone by Bluetooth.
//
// Sockets are standalone asio's, kept out of this header.

#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tools/connections/port_limit.hpp"

extern "C" {
#include "boards/epuck_host/host_board.h"
}

namespace aseba::host
{

// Where the network listens unless told otherwise: this computer only.
inline constexpr const char *LOOPBACK_ADDRESS = "127.0.0.1";

// What one client may hold in the network (see the top of this file).
inline constexpr size_t CLIENT_FRAMES_PER_ROBOT = 64;  // waiting for one robot
inline constexpr size_t CLIENT_BYTES_PER_ROBOT = 4096; // the same, in bytes
inline constexpr size_t CLIENT_UNREAD_LIMIT = 1 << 20; // waiting for the client to read
inline constexpr size_t MAX_CLIENTS = 64;              // on the network's port at once
inline constexpr size_t ROBOT_PORT_CLIENTS = 8;        // on one robot's own port at once
inline constexpr size_t ROBOT_FRAMES_PER_ROBOT = 4096; // from the robots, for one robot

using Frame = std::vector<uint8_t>;

// A frame's bytes where they lie, borrowed: valid until its owner changes.
struct FrameView {
    const uint8_t *bytes = nullptr;
    size_t size = 0;
};

// Cuts a byte stream into Aseba frames.
class FrameReader
{
  public:
    // Takes bytes; false once a header announced a payload above the
    // protocol's maximum: the stream can no longer be followed.
    bool feed(const uint8_t *bytes, size_t count);
    // The next complete frame, if any, in the reader's buffer until the next feed.
    std::optional<FrameView> next();
    // feed, then `sink` with each frame next gives; whole frames are passed
    // where they lie in `bytes` when no earlier part waits, which is most
    // of the time. Defined where it is used (network.cpp).
    template<class Sink>
    bool read(const uint8_t *bytes, size_t count, Sink &&sink);

  private:
    std::vector<uint8_t> pending_;
    size_t consumed_ = 0;
    bool broken_ = false;
};

class Network
{
  public:
    Network();
    ~Network();
    Network(const Network &) = delete;
    Network &operator=(const Network &) = delete;

    // Accepts clients on `port` of `address` (0: a port the system chooses),
    // as many at once as `limit` says; returns the port. Throws
    // std::runtime_error with the system's reason when it cannot.
    uint16_t listen(uint16_t port,
                    const std::string &address = LOOPBACK_ADDRESS,
                    const connections::PortLimit &limit = { MAX_CLIENTS, connections::IDLE_GRACE });

    // Joins a board: its link output comes to the bus, the bus feeds its link.
    void attach(hal_board *board);

    // Accepts clients linked directly to `board` (attached before) on `port`,
    // as listen does; returns the port. Such a client hears that board's
    // frames only, and its frames reach that board only, not the bus nor
    // the board's other direct clients; the board's frames still reach the
    // bus. Throws std::invalid_argument for a board not attached.
    uint16_t listen_robot(hal_board *board,
                          uint16_t port,
                          const std::string &address = LOOPBACK_ADDRESS,
                          const connections::PortLimit &limit = { ROBOT_PORT_CLIENTS,
                                                                  connections::IDLE_GRACE });

    // Moves frames: accepts clients, reads and writes sockets (waiting up to
    // `timeout_ms` for one of them), and feeds boards what their links can
    // take. Call it often; it never waits longer than asked.
    void service(int timeout_ms);

    // Clients connected now.
    size_t client_count() const;

    // Frames that crossed the bus since the start.
    uint64_t frames_moved() const;

    // Frames from the robots dropped because a robot's link had
    // ROBOT_FRAMES_PER_ROBOT of them waiting already (a robot flooding the
    // others, as a saturated radio would lose them).
    uint64_t frames_dropped() const;

    // Bytes of frames the network holds now, waiting for boards and for
    // clients: what its memory grows with, bounded by the limits above.
    size_t held_bytes() const;

    // Whether a user event (type below 0x8000) that a board emits reaches the
    // other boards; on by default. Off cuts the robots' radio between
    // themselves, as for the paper's runs without communication: tools still
    // hear such events, and protocol messages and a tool's events still
    // reach every board.
    void relay_robot_events(bool relay);

    // Called with every frame that crosses the bus (for status and logs),
    // borrowed for the call.
    void observe(std::function<void(FrameView)> observer);

  private:
    struct State;
    std::unique_ptr<State> state_;
};

} // namespace aseba::host
