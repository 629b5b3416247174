// The run loop around the CPU: slices of cycles between wall-clock checks,
// and the UART1 line watcher.

#include "tools/dspic30_sim/simulator.hpp"

#include <chrono>
#include <cstdio>
#include <stdexcept>

namespace aseba::dspic30
{
namespace
{
constexpr std::size_t longest_line = 256;
} // namespace

std::string outcome_name(Outcome outcome)
{
    switch (outcome) {
    case Outcome::cycle_limit: return "cycle limit";
    case Outcome::exit_line: return "EXIT line";
    case Outcome::abort_line: return "ABORT line";
    case Outcome::trap_reset_storm: return "trap-reset storm";
    case Outcome::illegal_instruction: return "illegal instruction";
    case Outcome::wall_clock: return "wall-clock watchdog";
    case Outcome::power_cut: return "power cut";
    case Outcome::interrupted: return "signal";
    }
    return "?";
}

Simulator::Simulator(std::function<void(uint8_t)> output, std::function<int()> input)
  : uart1_(
      cpu_,
      uart1_ports,
      [this](uint8_t b) { uart_byte(b); },
      std::move(input))
  , uart2_(
      cpu_,
      uart2_ports,
      [this](uint8_t b) {
          if (uart2_output_)
              uart2_output_(b);
      },
      [this]() { return uart2_input_ ? uart2_input_() : -1; })
  , timers_(cpu_)
  , gpio_(cpu_)
  , adc_(cpu_)
  , i2c_(cpu_)
  , output_(std::move(output))
{
    uart1_.attach();
    uart2_.attach();
    timers_.attach();
    gpio_.attach();
    adc_.attach();
    i2c_.attach();
    cpu_.set_trap_observer([this](const TrapRecord &record) {
        if (!current_)
            return;
        ++current_->trap_count;
        if (current_->traps.size() < trap_log_length)
            current_->traps.push_back(record);
    });
}

void Simulator::load(const std::map<uint32_t, uint32_t> &words)
{
    for (const auto &[address, word] : words)
        if (!cpu_.program(address, word)) {
            char text[96];
            std::snprintf(text,
                          sizeof text,
                          "nothing is implemented at PC address 0x%06X of the image",
                          static_cast<unsigned>(address));
            throw std::invalid_argument(text);
        }
    cpu_.power_on_reset();
}

void Simulator::uart_byte(uint8_t byte)
{
    if (output_)
        output_(byte);
    if (!watching_exit_)
        return;
    if (byte != '\n') {
        if (line_.size() < longest_line)
            line_ += static_cast<char>(byte);
        return;
    }
    int n = 0;
    char extra = 0;
    if (line_ == "ABORT") {
        line_outcome_ = Outcome::abort_line;
        cpu_.request_stop();
    } else if (std::sscanf(line_.c_str(), "EXIT %d%c", &n, &extra) == 1) {
        line_outcome_ = Outcome::exit_line;
        exit_status_ = n;
        cpu_.request_stop();
    }
    line_.clear();
}

RunResult Simulator::run(const RunLimits &limits)
{
    RunResult result;
    current_ = &result;
    watching_exit_ = limits.stop_at_exit_line;
    line_outcome_.reset();
    const auto start = std::chrono::steady_clock::now();
    const auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    for (;;) {
        const uint64_t target = limits.cycles - cpu_.cycles() > slice_cycles_
                                  ? cpu_.cycles() + slice_cycles_
                                  : limits.cycles;
        const StopReason reason = cpu_.run(target);
        if (line_outcome_) {
            result.outcome = *line_outcome_;
            result.exit_status = exit_status_;
            break;
        }
        if (reason == StopReason::trap_reset_storm) {
            result.outcome = Outcome::trap_reset_storm;
            break;
        }
        if (reason == StopReason::illegal_instruction) {
            result.outcome = Outcome::illegal_instruction;
            break;
        }
        if (cpu_.power_cut()) {
            result.outcome = Outcome::power_cut;
            break;
        }
        if (cpu_.cycles() >= limits.cycles) {
            result.outcome = Outcome::cycle_limit;
            break;
        }
        if (limits.seconds > 0 && elapsed() > limits.seconds) {
            result.outcome = Outcome::wall_clock;
            break;
        }
        if (between_slices_ && !between_slices_()) {
            result.outcome = Outcome::interrupted;
            break;
        }
    }
    result.cycles = cpu_.cycles();
    result.seconds = elapsed();
    current_ = nullptr;
    return result;
}

} // namespace aseba::dspic30
