// Keeps simulated time in step with the host's clock for a simulator that
// talks to host programs (--uart1 tcp:PORT): the chip runs no further ahead
// of the wall clock than one slice, so that its timeouts (a bootloader's
// one-second wait, a frame's half-second of silence) last as long for the
// host as on a robot. A simulator that falls behind (a loaded machine) runs
// flat out and does not try to make up more than a tenth of a second: a
// burst of simulated time would squeeze timeouts as much as running ahead.

#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>

namespace aseba::dspic30
{

class WallClockPace
{
  public:
    using Clock = std::chrono::steady_clock;

    // `cycles_per_second` of simulated time per second of the host's; 0:
    // no pacing (as fast as the host can).
    explicit WallClockPace(double cycles_per_second)
      : rate_(cycles_per_second)
    {
    }

    // How long to wait, at cycle `cycles`, for the wall clock to catch up.
    Clock::duration wait_at(uint64_t cycles)
    {
        if (rate_ <= 0)
            return Clock::duration::zero();
        const Clock::time_point now = Clock::now();
        if (!started_) {
            started_ = true;
            rebase(now, cycles);
        }
        const std::chrono::duration<double> simulated((cycles - start_cycles_) / rate_);
        const auto ahead = std::chrono::duration_cast<Clock::duration>(simulated) - (now - start_);
        if (ahead < -max_debt) // too far behind: start again from here
            rebase(now - max_debt, cycles);
        return std::max(ahead, Clock::duration::zero());
    }

  private:
    static constexpr Clock::duration max_debt = std::chrono::milliseconds(100);

    void rebase(Clock::time_point now, uint64_t cycles)
    {
        start_ = now;
        start_cycles_ = cycles;
    }

    double rate_;
    bool started_ = false;
    Clock::time_point start_;
    uint64_t start_cycles_ = 0;
};

} // namespace aseba::dspic30
