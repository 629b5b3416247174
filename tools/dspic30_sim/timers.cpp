// The timers, kept lazily: a counter is brought up to date (sync) when it is
// read or written or when its next match is due, from the cycles elapsed.

#include "tools/dspic30_sim/timers.hpp"

namespace aseba::dspic30
{
namespace
{

// Register addresses (fact sheet §2.2).
constexpr uint16_t tmr1 = 0x0100, pr1 = 0x0102, t1con = 0x0104;
constexpr uint16_t tmr2 = 0x0106, tmr3hld = 0x0108, tmr3 = 0x010A, pr2 = 0x010C, pr3 = 0x010E;
constexpr uint16_t t2con = 0x0110, t3con = 0x0112;
constexpr uint16_t tmr4 = 0x0114, tmr5hld = 0x0116, tmr5 = 0x0118, pr4 = 0x011A, pr5 = 0x011C;
constexpr uint16_t t4con = 0x011E, t5con = 0x0120;
constexpr uint16_t first_register = tmr1, last_register = t5con;

constexpr uint16_t con_ton = 1u << 15;
constexpr uint16_t con_tcs = 1u << 1;
constexpr uint16_t con_t32 = 1u << 3;
constexpr int con_tckps_shift = 4;
constexpr uint64_t prescalers[4] = { 1, 8, 64, 256 };
// IRQ numbers (vector - 8): T1 3, T2 6, T3 7, T4 21, T5 22 (fact sheet §1.7).
constexpr int timer_irq[6] = { -1, 3, 6, 7, 21, 22 };
constexpr uint32_t word_range = 0x10000;

uint16_t merge(uint16_t old, uint16_t value, uint16_t mask)
{
    return static_cast<uint16_t>((old & ~mask) | (value & mask));
}

} // namespace

Timers::Timers(Cpu &cpu)
  : cpu_(cpu)
{
    reset();
}

void Timers::attach()
{
    cpu_.attach(first_register, last_register, *this);
}

void Timers::reset()
{
    counters_.fill(Counter{});
    control_.fill(0);
    period_.fill(0xFFFF); // PRx reset to all ones
    high_latch_.fill(0);
}

// Timer 2 (4) when it runs as the low half of a 32-bit pair; timer 3 (5)
// then does not count on its own.
bool Timers::paired(int timer) const
{
    return (timer == 2 || timer == 4) && (control_[timer] & con_t32);
}

void Timers::connect_clock(int timer, const ClockInput *input)
{
    const uint64_t now = cpu_.cycles();
    sync(timer, now);
    clock_inputs_[timer] = input;
    counters_[timer].synced_at = now;
    schedule(timer, now);
}

// The edges timer `timer` counts when its TCS is set, else nullptr (it
// counts the instruction clock).
const ClockInput *Timers::external_clock(int timer) const
{
    return (control_[timer] & con_tcs) ? clock_inputs_[timer] : nullptr;
}

bool Timers::counting(int timer) const
{
    if ((timer == 3 || timer == 5) && paired(timer - 1))
        return false;
    if (!(control_[timer] & con_ton))
        return false;
    return !(control_[timer] & con_tcs) || clock_inputs_[timer] != nullptr;
}

uint64_t Timers::prescale(int timer) const
{
    return prescalers[(control_[timer] >> con_tckps_shift) & 3];
}

uint32_t Timers::period(int timer) const
{
    if (paired(timer))
        return (static_cast<uint32_t>(period_[timer + 1]) << 16) | period_[timer];
    return period_[timer];
}

void Timers::sync(int timer, uint64_t now)
{
    Counter &c = counters_[timer];
    if (!counting(timer) || now <= c.synced_at) {
        c.synced_at = std::max(c.synced_at, now);
        return;
    }
    const ClockInput *input = external_clock(timer);
    const uint64_t counted = input ? input->rising_edges(c.synced_at, now) : now - c.synced_at;
    const uint64_t total = c.phase + counted;
    uint64_t ticks = total / prescale(timer);
    c.phase = total % prescale(timer);
    c.synced_at = now;
    const uint64_t range = paired(timer) ? uint64_t{ 1 } << 32 : word_range;
    const uint64_t p = period(timer);
    while (ticks > 0) {
        // Counts to the match (count == period, then 0 on the next count),
        // or past the top of the range back to 0 when above the period.
        const uint64_t to_match = c.count <= p ? p - c.count + 1 : range - c.count + p + 1;
        if (ticks < to_match) {
            c.count = static_cast<uint32_t>((c.count + ticks) % range);
            break;
        }
        ticks -= to_match;
        c.count = 0;
        const int flag_timer = paired(timer) ? timer + 1 : timer;
        cpu_.raise_interrupt(timer_irq[flag_timer]);
    }
}

void Timers::schedule(int timer, uint64_t now)
{
    Counter &c = counters_[timer];
    if (!counting(timer)) {
        c.match_at = never;
        return;
    }
    const uint64_t range = paired(timer) ? uint64_t{ 1 } << 32 : word_range;
    const uint64_t p = period(timer);
    const uint64_t to_match = c.count <= p ? p - c.count + 1 : range - c.count + p + 1;
    const uint64_t counts = to_match * prescale(timer) - c.phase;
    const ClockInput *input = external_clock(timer);
    c.match_at = input ? input->rising_edge(now, counts) : now + counts;
    cpu_.reschedule();
}

uint64_t Timers::next_event() const
{
    uint64_t next = never;
    for (int t = 1; t <= 5; ++t)
        next = std::min(next, counters_[t].match_at);
    return next;
}

void Timers::advance(uint64_t now)
{
    for (int t = 1; t <= 5; ++t)
        if (counters_[t].match_at <= now) {
            sync(t, now);
            schedule(t, now);
        }
}

uint16_t Timers::read(uint16_t address)
{
    const uint64_t now = cpu_.cycles();
    const auto count_of = [&](int t) {
        sync(t, now);
        return counters_[t].count;
    };
    switch (address) {
    case tmr1: return static_cast<uint16_t>(count_of(1));
    case tmr2:
    case tmr4: {
        const int t = address == tmr2 ? 2 : 4;
        const uint32_t count = count_of(t);
        if (paired(t))
            high_latch_[t + 1] = static_cast<uint16_t>(count >> 16);
        return static_cast<uint16_t>(count);
    }
    case tmr3:
        return paired(2) ? static_cast<uint16_t>(count_of(2) >> 16)
                         : static_cast<uint16_t>(count_of(3));
    case tmr5:
        return paired(4) ? static_cast<uint16_t>(count_of(4) >> 16)
                         : static_cast<uint16_t>(count_of(5));
    case tmr3hld: return high_latch_[3];
    case tmr5hld: return high_latch_[5];
    case pr1: return period_[1];
    case pr2: return period_[2];
    case pr3: return period_[3];
    case pr4: return period_[4];
    case pr5: return period_[5];
    case t1con: return control_[1];
    case t2con: return control_[2];
    case t3con: return control_[3];
    case t4con: return control_[4];
    case t5con: return control_[5];
    default: return 0;
    }
}

void Timers::write(uint16_t address, uint16_t value, uint16_t mask)
{
    const uint64_t now = cpu_.cycles();
    for (int t = 1; t <= 5; ++t)
        sync(t, now);
    const auto set_count = [&](int t, uint32_t count) {
        counters_[t].count = count;
        counters_[t].phase = 0;
    };
    switch (address) {
    case tmr1: set_count(1, merge(static_cast<uint16_t>(counters_[1].count), value, mask)); break;
    case tmr2:
    case tmr4: {
        const int t = address == tmr2 ? 2 : 4;
        const uint16_t low = merge(static_cast<uint16_t>(counters_[t].count), value, mask);
        if (paired(t))
            set_count(t, (static_cast<uint32_t>(high_latch_[t + 1]) << 16) | low);
        else
            set_count(t, low);
        break;
    }
    case tmr3:
    case tmr5: {
        const int t = address == tmr3 ? 3 : 5;
        if (paired(t - 1))
            set_count(t - 1,
                      (static_cast<uint32_t>(
                         merge(static_cast<uint16_t>(counters_[t - 1].count >> 16), value, mask))
                       << 16) |
                        (counters_[t - 1].count & 0xFFFF));
        else
            set_count(t, merge(static_cast<uint16_t>(counters_[t].count), value, mask));
        break;
    }
    case tmr3hld: high_latch_[3] = merge(high_latch_[3], value, mask); break;
    case tmr5hld: high_latch_[5] = merge(high_latch_[5], value, mask); break;
    case pr1: period_[1] = merge(period_[1], value, mask); break;
    case pr2: period_[2] = merge(period_[2], value, mask); break;
    case pr3: period_[3] = merge(period_[3], value, mask); break;
    case pr4: period_[4] = merge(period_[4], value, mask); break;
    case pr5: period_[5] = merge(period_[5], value, mask); break;
    case t1con: control_[1] = merge(control_[1], value, mask); break;
    case t2con: control_[2] = merge(control_[2], value, mask); break;
    case t3con: control_[3] = merge(control_[3], value, mask); break;
    case t4con: control_[4] = merge(control_[4], value, mask); break;
    case t5con: control_[5] = merge(control_[5], value, mask); break;
    default: break;
    }
    for (int t = 1; t <= 5; ++t)
        schedule(t, now);
}

} // namespace aseba::dspic30
