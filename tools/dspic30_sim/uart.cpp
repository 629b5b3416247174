// UART registers: UxMODE and UxBRG as written, UxSTA with the hardware's
// status bits, UxTXREG straight to the output, UxRXREG from the FIFO.

#include "tools/dspic30_sim/uart.hpp"

namespace aseba::dspic30
{
namespace
{

constexpr uint16_t mode_offset = 0, status_offset = 2, tx_offset = 4, rx_offset = 6, brg_offset = 8;
constexpr uint16_t mode_uarten = 1u << 15;
constexpr uint16_t status_utxen = 1u << 10;
constexpr uint16_t status_utxbf = 1u << 9;
constexpr uint16_t status_trmt = 1u << 8;
constexpr int status_urxisel_shift = 6;
constexpr uint16_t status_ridle = 1u << 4;
constexpr uint16_t status_oerr = 1u << 1;
constexpr uint16_t status_urxda = 1u << 0;
// What the program may write in UxSTA (the rest is hardware status; OERR
// can be cleared).
constexpr uint16_t status_writable = 0x8000 | 0x0800 | status_utxen | 0x00C0 | 0x0020;
constexpr std::size_t fifo_depth = 4;
constexpr uint64_t bits_per_byte = 10;  // start, 8 data, stop
constexpr uint64_t clocks_per_bit = 16; // UxBRG = FCY / (16 baud) - 1

} // namespace

Uart::Uart(Cpu &cpu,
           UartPorts ports,
           std::function<void(uint8_t)> output,
           std::function<int()> input)
  : cpu_(cpu)
  , ports_(ports)
  , output_(std::move(output))
  , input_(std::move(input))
{
}

void Uart::attach()
{
    cpu_.attach(ports_.base, static_cast<uint16_t>(ports_.base + brg_offset), *this);
}

uint64_t Uart::byte_cycles() const
{
    return bits_per_byte * clocks_per_bit * (static_cast<uint64_t>(brg_) + 1);
}

bool Uart::enabled() const
{
    return mode_ & mode_uarten;
}

uint16_t Uart::read(uint16_t address)
{
    switch (address - ports_.base) {
    case mode_offset: return mode_;
    case status_offset: {
        uint16_t s = static_cast<uint16_t>(status_ & ~(status_utxbf | status_urxda));
        s |= status_trmt | status_ridle;
        if (!fifo_.empty())
            s |= status_urxda;
        return s;
    }
    case rx_offset: {
        if (fifo_.empty())
            return 0;
        const uint8_t byte = fifo_.front();
        fifo_.pop_front();
        update_receive_interrupt();
        return byte;
    }
    case brg_offset: return brg_;
    default: return 0; // UxTXREG reads 0
    }
}

void Uart::write(uint16_t address, uint16_t value, uint16_t mask)
{
    const auto merged = [&](uint16_t old) {
        return static_cast<uint16_t>((old & ~mask) | (value & mask));
    };
    switch (address - ports_.base) {
    case mode_offset: {
        const bool was = enabled();
        mode_ = merged(mode_);
        if (enabled() && !was) {
            next_receive_ = cpu_.cycles() + byte_cycles();
            cpu_.reschedule();
        } else if (!enabled()) {
            fifo_.clear();
            next_receive_ = never;
        }
        break;
    }
    case status_offset: {
        const uint16_t next = merged(status_);
        const bool tx_enabled_now = (next & status_utxen) && !(status_ & status_utxen);
        // OERR can only be cleared by the program.
        const uint16_t oerr = status_ & next & status_oerr;
        status_ = static_cast<uint16_t>((next & status_writable) | oerr);
        if (tx_enabled_now && enabled())
            cpu_.raise_interrupt(ports_.tx_irq); // the empty buffer asks for data
        break;
    }
    case tx_offset:
        if (enabled() && (status_ & status_utxen)) {
            if (output_)
                output_(static_cast<uint8_t>(value & mask));
            cpu_.raise_interrupt(ports_.tx_irq);
        }
        break;
    case brg_offset: brg_ = merged(brg_); break;
    default: break;
    }
}

uint64_t Uart::next_event() const
{
    return input_ ? next_receive_ : never;
}

void Uart::advance(uint64_t now)
{
    while (enabled() && next_receive_ <= now) {
        next_receive_ += byte_cycles();
        const int byte = input_ ? input_() : -1;
        if (byte < 0)
            continue;
        if (fifo_.size() >= fifo_depth) {
            status_ |= status_oerr;
            continue;
        }
        fifo_.push_back(static_cast<uint8_t>(byte));
        update_receive_interrupt();
    }
    if (next_receive_ <= now) // catching up after a long pause
        next_receive_ = now + byte_cycles();
}

void Uart::update_receive_interrupt()
{
    const int mode = (status_ >> status_urxisel_shift) & 3;
    const std::size_t wanted = mode < 2 ? 1 : (mode == 2 ? 3 : fifo_depth);
    if (fifo_.size() >= wanted)
        cpu_.raise_interrupt(ports_.rx_irq);
}

void Uart::reset()
{
    mode_ = status_ = brg_ = 0;
    fifo_.clear();
    next_receive_ = never;
}

} // namespace aseba::dspic30
