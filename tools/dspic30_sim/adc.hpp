// The dsPIC30F6014A's 12-bit ADC (hardware fact sheet §2.3; the family
// reference manual's 12-bit A/D section): ADCON1-3, ADCHS, ADPCFG, ADCSSL
// and the 16 result words ADCBUF0-F. Modelled: ADON; manual sampling
// (SAMP; with SSRC = 000 clearing SAMP starts the conversion) and
// automatic conversion (SSRC = 111: the internal counter ends sampling
// after SAMC Tad); ASAM (sampling starts again after each conversion);
// channel 0's positive input from CH0SA, or with CSCNA the inputs of ADCSSL
// in ascending order; a conversion of 14 Tad, Tad = Tcy x (ADCS + 1) / 2;
// results filling ADCBUF0 upward, DONE, and the interrupt (IRQ 11) after
// SMPI + 1 conversions, when the buffer and the scan start again from the
// first. Results are unsigned integers (FORM = 00, the e-puck's); the other
// formats, the alternating MUX (ALTS), the split buffer (BUFM), the other
// conversion triggers and the internal RC clock (ADRC) are not modelled.
// The analog inputs' values (0-4095) are set by the simulator's host
// (set_input: 0 until then), or asked of it when the sample is held, at the
// start of each conversion (set_input_source).

#pragma once

#include "tools/dspic30_sim/cpu.hpp"
#include "tools/dspic30_sim/peripheral.hpp"

#include <array>
#include <cstdint>
#include <functional>

namespace aseba::dspic30
{

class Adc : public Peripheral
{
  public:
    static constexpr int channels = 16;

    explicit Adc(Cpu &cpu);

    // Attaches ADCBUF0..ADCSSL to `cpu`.
    void attach();

    // The value (0-4095) input ANn gives from now on.
    void set_input(int channel, uint16_t value);
    // From now on input ANn gives `source(n, cycle)` (0-4095), asked at the
    // cycle its sample is held; empty: the values of set_input.
    void set_input_source(std::function<uint16_t(int channel, uint64_t cycle)> source)
    {
        input_source_ = std::move(source);
    }

    uint16_t read(uint16_t address) override;
    void write(uint16_t address, uint16_t value, uint16_t mask) override;
    uint64_t next_event() const override;
    void advance(uint64_t now) override;
    void reset() override;

  private:
    enum class Phase : uint8_t { idle, sampling, converting };

    // Cycles of `tads` Tad at the configured ADCS.
    uint64_t tad_cycles(uint64_t tads) const;
    void start_sampling(uint64_t now);
    void start_conversion(uint64_t now);
    void finish_conversion(uint64_t now);
    int next_channel();

    Cpu &cpu_;
    uint16_t adcon1_ = 0, adcon2_ = 0, adcon3_ = 0, adchs_ = 0, adpcfg_ = 0, adcssl_ = 0;
    std::array<uint16_t, channels> buffer_{};
    std::array<uint16_t, channels> inputs_{};
    Phase phase_ = Phase::idle;
    bool done_ = false;
    uint64_t phase_end_ = never; // the end of automatic sampling or of a conversion
    int channel_ = 0;            // the input being sampled or converted
    int scan_last_ = -1;         // the last input of ADCSSL taken (-1: none yet)
    int filled_ = 0;             // results since the last interrupt
    uint16_t held_ = 0;          // the sample being converted
    std::function<uint16_t(int, uint64_t)> input_source_;
};

} // namespace aseba::dspic30
