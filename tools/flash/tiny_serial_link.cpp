// A TinyLink over the console's serial transport.

#include "tools/flash/tiny_serial_link.hpp"

#include <poll.h>
#include <termios.h>

#include <deque>

#include "tools/client/transport.hpp"

namespace aseba::flash
{
namespace
{

constexpr int open_timeout_ms = 1000;  // unused by serial devices, which open at once
constexpr int write_timeout_ms = 2000; // a packet is 101 bytes, about 9 ms at 115200 baud
constexpr std::size_t read_chunk = 256;

class SerialTinyLink : public TinyLink
{
  public:
    explicit SerialTinyLink(std::unique_ptr<client::Transport> transport)
      : transport_(std::move(transport))
    {
    }

    void send(std::span<const uint8_t> bytes) override
    {
        transport_->write(bytes.data(), bytes.size(), write_timeout_ms);
    }

    std::optional<uint8_t> receive(std::chrono::milliseconds timeout) override
    {
        auto deadline = std::chrono::steady_clock::now() + timeout;
        while (received_.empty()) {
            auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
              deadline - std::chrono::steady_clock::now());
            pollfd waiting{ transport_->fd(), POLLIN, 0 };
            int ready = poll(&waiting, 1, left.count() > 0 ? static_cast<int>(left.count()) : 0);
            if (ready > 0)
                take_available();
            else if (left.count() <= 0)
                return std::nullopt;
        }
        uint8_t byte = received_.front();
        received_.pop_front();
        return byte;
    }

    void discard_input() override
    {
        tcflush(transport_->fd(), TCIFLUSH);
        received_.clear();
    }

    void finish_sending() override
    {
        tcdrain(transport_->fd());
    }

  private:
    // Reads what poll() said is there: on a tty in raw mode (VMIN = VTIME =
    // 0) a read finding nothing returns 0, which the transport takes for a
    // closed link.
    void take_available()
    {
        uint8_t buffer[read_chunk];
        std::size_t count = transport_->read(buffer, sizeof buffer);
        received_.insert(received_.end(), buffer, buffer + count);
    }

    std::unique_ptr<client::Transport> transport_;
    std::deque<uint8_t> received_;
};

} // namespace

std::unique_ptr<TinyLink> open_tiny_serial_link(const std::string &device)
{
    client::TargetAddress address;
    if (device.rfind("ser:", 0) == 0) {
        address = client::parse_target(device);
    } else {
        address.kind = client::TargetAddress::Kind::serial;
        address.device = device;
    }
    address.baud = client::DEFAULT_SERIAL_BAUD; // the Tiny Bootloader's 115200 (U1BRG = 7)
    return std::make_unique<SerialTinyLink>(client::open_transport(address, open_timeout_ms));
}

} // namespace aseba::flash
