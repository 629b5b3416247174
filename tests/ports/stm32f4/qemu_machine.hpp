// An STM32F4 image running in QEMU for a test: scripts/qemu-node.sh started
// on a free loopback port (tests/interop's child process: stopped by its PID,
// SIGTERM then SIGKILL, when the object goes, and by the kernel when the
// test program dies), reachable over TCP once QEMU listens.

#pragma once

#include <memory>
#include <string>

#include "tests/interop/child_process.hpp"
#include "tests/interop/interop_support.hpp"

namespace qemu_test
{

// When the board starts: at once (clients come and go; bytes sent before
// the image has turned its USART on are lost), or when the first client
// connects (that client then sees everything the image sends).
enum class Start { at_once, on_first_connection };

class QemuMachine
{
  public:
    // Starts `image`; with `icount`, the guest's clock counts instructions.
    // Throws std::runtime_error when QEMU does not start or the port does not
    // accept a connection within a few seconds.
    explicit QemuMachine(const std::string &image,
                         bool icount = false,
                         Start start = Start::at_once);
    ~QemuMachine();
    QemuMachine(const QemuMachine &) = delete;
    QemuMachine &operator=(const QemuMachine &) = delete;

    int port() const
    {
        return port_;
    }
    // The Dashel target of the node: tcp:127.0.0.1;PORT.
    std::string target() const;
    // A new TCP connection to the machine's serial port; throws on failure.
    int connect() const;
    // With Start::on_first_connection: the connection that started the
    // board (the caller closes it).
    int first_connection() const
    {
        return first_connection_;
    }

  private:
    interop::ScratchFolder scratch_; // QEMU's messages
    std::unique_ptr<interop::ChildProcess> process_;
    int port_ = 0;
    int first_connection_ = -1;
};

// Writes all of `bytes`; throws on failure.
void write_all(int socket, const void *bytes, size_t count);

// Reads exactly `count` bytes within `timeout_ms`; throws on failure or time-out.
void read_exactly(int socket, void *bytes, size_t count, int timeout_ms);

} // namespace qemu_test
