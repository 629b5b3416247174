// A dsPIC30F6014A with UART1 and UART2 on host byte streams, timers 1-5, the I/O
// ports, the ADC and the I2C master, as dspic30-sim and the tests run it: load an image, run it
// from reset under a cycle limit and a wall-clock watchdog, and stop at the line a test program
// prints at its end ("EXIT n" or "ABORT", the convention of
// ../shared/vectors/gcc-torture).

#pragma once

#include "tools/dspic30_sim/adc.hpp"
#include "tools/dspic30_sim/cpu.hpp"
#include "tools/dspic30_sim/gpio.hpp"
#include "tools/dspic30_sim/i2c.hpp"
#include "tools/dspic30_sim/timers.hpp"
#include "tools/dspic30_sim/uart.hpp"

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace aseba::dspic30
{

// How a run ended.
enum class Outcome : uint8_t {
    cycle_limit,         // ran the cycles asked for
    exit_line,           // UART1 printed "EXIT n" (exit_status holds n)
    abort_line,          // UART1 printed "ABORT"
    trap_reset_storm,    // the chip kept resetting on traps
    illegal_instruction, // the PC reached a word that is no instruction
    wall_clock,          // the wall-clock watchdog fired
    power_cut,           // the NVM operation chosen for a power cut began
    interrupted,         // the caller's between-slices hook asked to stop (a signal)
};

// The words of `outcome` ("cycle limit", "EXIT line", ...).
std::string outcome_name(Outcome outcome);

struct RunLimits {
    uint64_t cycles = never;        // instruction cycles
    double seconds = 0;             // wall-clock limit; 0 = none
    bool stop_at_exit_line = false; // stop at "EXIT n" / "ABORT" on UART1
};

struct RunResult {
    Outcome outcome = Outcome::cycle_limit;
    int exit_status = 0;           // the n of "EXIT n"
    uint64_t cycles = 0;           // at the end
    double seconds = 0;            // wall-clock time of run()
    std::vector<TrapRecord> traps; // the first ones (up to trap_log_length)
    uint64_t trap_count = 0;
};

class Simulator
{
  public:
    static constexpr std::size_t trap_log_length = 16;

    // UART1's transmitted bytes go to `output`, its input comes from
    // `input` (-1: no byte waiting); either may be empty.
    Simulator(std::function<void(uint8_t)> output = {}, std::function<int()> input = {});

    // Programs `words` (PC address -> word) and resets the chip. Throws
    // std::invalid_argument naming the first address nothing is
    // implemented at.
    void load(const std::map<uint32_t, uint32_t> &words);

    // UART2's transmitted bytes go to `output`, its input comes from `input`
    // (-1: no byte waiting); until then UART2 is unconnected.
    void connect_uart2(std::function<void(uint8_t)> output, std::function<int()> input)
    {
        uart2_output_ = std::move(output);
        uart2_input_ = std::move(input);
    }

    RunResult run(const RunLimits &limits);

    // Calls `hook` after each slice of `slice_cycles` of a run (the TCP
    // link, pacing to the wall clock); the hook returning false stops the
    // run (Outcome::interrupted). Without one, a run looks at the wall
    // clock every 2^22 cycles.
    void set_between_slices(uint64_t slice_cycles, std::function<bool()> hook)
    {
        slice_cycles_ = slice_cycles;
        between_slices_ = std::move(hook);
    }

    Cpu &cpu()
    {
        return cpu_;
    }
    GpioPorts &gpio()
    {
        return gpio_;
    }
    Adc &adc()
    {
        return adc_;
    }
    Timers &timers()
    {
        return timers_;
    }
    I2cMaster &i2c()
    {
        return i2c_;
    }

  private:
    void uart_byte(uint8_t byte);

    Cpu cpu_;
    Uart uart1_;
    Uart uart2_;
    Timers timers_;
    GpioPorts gpio_;
    Adc adc_;
    I2cMaster i2c_;
    std::function<void(uint8_t)> output_;
    std::function<void(uint8_t)> uart2_output_;
    std::function<int()> uart2_input_;
    std::string line_;
    bool watching_exit_ = false;
    std::optional<Outcome> line_outcome_;
    int exit_status_ = 0;
    RunResult *current_ = nullptr;
    uint64_t slice_cycles_ = uint64_t{ 1 } << 22;
    std::function<bool()> between_slices_;
};

} // namespace aseba::dspic30
