// The harness image's link on the simulated dsPIC30F6014A (remote_link.hpp):
// the image (tests/ports/dspic30/target, pic30-elf-gcc's machine code) runs
// in this process on the simulator library (tools/dspic30_sim), requests go
// into its UART1 and answers come out of it. The chip runs only while the
// host waits for bytes, so a test costs the cycles the image spends.

#include <chrono>
#include <cstdio>
#include <deque>

#include "tests/ports/dspic30/simulated_link.hpp"
#include "tests/ports/stm32f4/remote_link.hpp"
#include "tools/dspic30_sim/intel_hex.hpp"
#include "tools/dspic30_sim/simulator.hpp"

namespace qemu_test
{

namespace
{

using aseba::dspic30::StopReason;
using aseba::dspic30::TrapRecord;

// As QEMU's link: an answer that takes longer is a hung image.
constexpr double answer_timeout_seconds = 20;
// Cycles between two looks at the clock.
constexpr uint64_t slice_cycles = 1'000'000;

class SimulatedLink : public HarnessLink
{
  public:
    SimulatedLink()
      : simulator_([this](uint8_t byte) { on_transmit(byte); },
                   [this]() -> int {
                       if (to_chip_.empty())
                           return -1;
                       uint8_t byte = to_chip_.front();
                       to_chip_.pop_front();
                       return byte;
                   })
    {
        simulator_.load(aseba::dspic30::read_intel_hex_file(DSPIC30_HARNESS_IMAGE));
        // A trap in the firmware is a finding, not a test result: stop there.
        simulator_.cpu().set_trap_observer([this](const TrapRecord &record) {
            if (trap_.empty())
                trap_ = record.cause + " at pc 0x" + hex(record.pc) + "\n" + record.registers;
            simulator_.cpu().request_stop();
        });
        uint8_t ready[REMOTE_HEADER_BYTES];
        receive(ready, sizeof ready);
        if (ready[0] != REMOTE_ANSWER_MAGIC || ready[1] != REMOTE_OK || ready[2] || ready[3])
            fail("the image did not announce itself");
    }

    void send(const uint8_t *bytes, size_t count) override
    {
        to_chip_.insert(to_chip_.end(), bytes, bytes + count);
    }

    void receive(uint8_t *bytes, size_t count) override
    {
        wanted_ = count;
        const auto start = std::chrono::steady_clock::now();
        aseba::dspic30::Cpu &cpu = simulator_.cpu();
        while (from_chip_.size() < count) {
            StopReason reason = cpu.run(cpu.cycles() + slice_cycles);
            if (!trap_.empty())
                fail("a trap on the chip: " + trap_);
            if (reason == StopReason::trap_reset_storm || reason == StopReason::illegal_instruction)
                fail("the chip stopped: " + std::string(reason == StopReason::trap_reset_storm
                                                          ? "trap-reset storm"
                                                          : "illegal instruction"));
            std::chrono::duration<double> waited = std::chrono::steady_clock::now() - start;
            if (waited.count() > answer_timeout_seconds)
                fail("no answer within " + std::to_string(int(answer_timeout_seconds)) + " s");
        }
        for (size_t i = 0; i < count; i++) {
            bytes[i] = from_chip_.front();
            from_chip_.pop_front();
        }
    }

    ~SimulatedLink() override
    {
        std::fprintf(stderr,
                     "harness image: %llu instruction cycles on the simulated dsPIC30F\n",
                     static_cast<unsigned long long>(cycles()));
    }

    uint64_t cycles()
    {
        return simulator_.cpu().cycles();
    }

  private:
    static std::string hex(uint32_t value)
    {
        char text[16];
        std::snprintf(text, sizeof text, "%06X", unsigned(value));
        return text;
    }

    // Stops the chip as soon as the bytes waited for are there.
    void on_transmit(uint8_t byte)
    {
        from_chip_.push_back(byte);
        if (from_chip_.size() >= wanted_)
            simulator_.cpu().request_stop();
    }

    aseba::dspic30::Simulator simulator_;
    std::deque<uint8_t> to_chip_;
    std::deque<uint8_t> from_chip_;
    size_t wanted_ = 0;
    std::string trap_;
};

SimulatedLink *the_link = nullptr;

} // namespace

std::unique_ptr<HarnessLink> open_harness_link(bool)
{
    auto link = std::make_unique<SimulatedLink>();
    the_link = link.get();
    return link;
}

uint64_t simulated_chip_cycles()
{
    return the_link ? the_link->cycles() : 0;
}

} // namespace qemu_test
