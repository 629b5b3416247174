// RC5 frames on the receiver's line (see remote_control.hpp).

#include "remote_control.hpp"

#include <algorithm>

extern "C" {
#include "boards/epuck_host/epuck_host_config.h"
}

namespace aseba::arena
{
namespace
{

constexpr unsigned frame_bits = 14;
constexpr unsigned frame_halves = 2 * frame_bits;
constexpr unsigned address_shift = 6;
constexpr unsigned toggle_shift = 11;
constexpr uint16_t start_bits = 0x3 << 12;
// 32 periods of the 36 kHz carrier per half bit.
constexpr uint64_t carrier_hz = 36000;
constexpr uint64_t carrier_periods_per_half = 32;
// A held key repeats its frame every 64 bit times.
constexpr unsigned repetition_halves = 2 * 64;

} // namespace

uint16_t rc5_bits(const Rc5Frame &frame)
{
    return uint16_t(start_bits | (frame.toggle & 1u) << toggle_shift |
                    (frame.address & 0x1Fu) << address_shift | (frame.command & 0x3Fu));
}

uint64_t rc5_half_bit_cycles(unsigned half)
{
    return uint64_t(half) * carrier_periods_per_half * HOST_CYCLES_PER_SECOND / carrier_hz;
}

void RemoteReceiver::send(const Rc5Frame &frame, uint64_t cycle)
{
    if (!frames_.empty())
        cycle = std::max(cycle, frames_.back().start + rc5_half_bit_cycles(repetition_halves));
    frames_.push_back({ cycle, rc5_bits(frame) });
}

bool RemoteReceiver::level(uint64_t cycle) const
{
    for (const Scheduled &frame : frames_) {
        if (cycle < frame.start || cycle >= frame.start + rc5_half_bit_cycles(frame_halves))
            continue;
        // The half bit `cycle` falls in: the last boundary at or before it.
        // The division's quotient is that one, or one short where a boundary
        // rounded down to the cycle itself.
        uint64_t into = cycle - frame.start;
        unsigned half =
          unsigned(into * carrier_hz / (carrier_periods_per_half * HOST_CYCLES_PER_SECOND));
        if (half + 1 < frame_halves && rc5_half_bit_cycles(half + 1) <= into)
            half++;
        bool one = (frame.bits >> (frame_bits - 1 - half / 2)) & 1u;
        bool second_half = half % 2 == 1;
        bool carrier = second_half == one;
        return !carrier;
    }
    return true;
}

uint64_t RemoteReceiver::next_change(uint64_t after) const
{
    for (const Scheduled &frame : frames_) {
        if (after >= frame.start + rc5_half_bit_cycles(frame_halves))
            continue;
        for (unsigned half = 0; half <= frame_halves; half++) {
            uint64_t boundary = frame.start + rc5_half_bit_cycles(half);
            if (boundary > after)
                return boundary;
        }
    }
    return UINT64_MAX;
}

void RemoteReceiver::forget_before(uint64_t cycle)
{
    while (!frames_.empty() && frames_.front().start + rc5_half_bit_cycles(frame_halves) < cycle)
        frames_.pop_front();
}

} // namespace aseba::arena
