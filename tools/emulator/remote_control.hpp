// A TV remote control's RC5 frames as the e-puck's IR receiver shows them
// (hardware §3.9). RC5 (Philips): 14 bits of 64 periods of a 36 kHz carrier
// (1.778 ms), most significant first: two start bits (1, 1), the toggle bit,
// 5 address bits, 6 command bits. Each bit is Manchester coded in two
// halves: a 1 is a half without carrier then a half with it, a 0 the
// reverse. The receiver's output is low while it sees the carrier and idles
// high. A held key repeats its frame every 64 bit times (113.8 ms).

#pragma once

#include <cstdint>
#include <deque>

namespace aseba::arena
{

struct Rc5Frame {
    uint8_t toggle = 0;  // 0/1, flipped by the remote at each key press
    uint8_t address = 0; // 0..31, the device (0: TV)
    uint8_t command = 0; // 0..63
};

// The 14 bits of `frame`, the first start bit in bit 13.
uint16_t rc5_bits(const Rc5Frame &frame);

// Processor cycles (HOST_CYCLES_PER_SECOND a second) from a frame's start to
// the boundary of its half bit `half` (0..28), rounded down: 32 carrier
// periods of 36 kHz a half bit.
uint64_t rc5_half_bit_cycles(unsigned half);

// One robot's IR receiver: the frames it will see, and its output line.
class RemoteReceiver
{
  public:
    // The receiver sees `frame` from `cycle` on, or after the frames it
    // already has, a repetition period after the last one started.
    void send(const Rc5Frame &frame, uint64_t cycle);

    // The output level at `cycle`: low while the carrier is on.
    bool level(uint64_t cycle) const;

    // The first half-bit boundary of a frame after `after`, where the line
    // may change; UINT64_MAX when no frame is to come.
    uint64_t next_change(uint64_t after) const;

    // Forgets the frames that ended before `cycle`.
    void forget_before(uint64_t cycle);

  private:
    struct Scheduled {
        uint64_t start;
        uint16_t bits;
    };
    std::deque<Scheduled> frames_;
};

} // namespace aseba::arena
