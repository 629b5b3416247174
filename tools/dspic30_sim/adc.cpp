// The ADC's sequencer: idle, sampling (until SAMP is cleared, or SAMC Tad
// with SSRC = 111), converting (14 Tad), then the result and perhaps the
// interrupt; with ASAM, sampling again.

#include "tools/dspic30_sim/adc.hpp"

namespace aseba::dspic30
{
namespace
{

constexpr uint16_t buffer_first = 0x0280, adcon1 = 0x02A0, adcon2 = 0x02A2, adcon3 = 0x02A4,
                   adchs = 0x02A6, adpcfg = 0x02A8, adcssl = 0x02AA;
constexpr uint16_t adcon1_adon = 1u << 15;
constexpr uint16_t adcon1_ssrc = 7u << 5;
constexpr uint16_t ssrc_manual = 0, ssrc_auto = 7u << 5;
constexpr uint16_t adcon1_asam = 1u << 2;
constexpr uint16_t adcon1_samp = 1u << 1;
constexpr uint16_t adcon1_done = 1u << 0;
constexpr uint16_t adcon2_cscna = 1u << 10;
constexpr int adcon2_smpi_shift = 2;
constexpr uint16_t adcon2_smpi = 0xFu << adcon2_smpi_shift;
constexpr int adcon3_samc_shift = 8;
constexpr uint16_t adcon3_samc = 0x1Fu << adcon3_samc_shift;
constexpr uint16_t adcon3_adcs = 0x3F;
constexpr uint16_t adchs_ch0sa = 0xF;
constexpr uint64_t conversion_tads = 14; // fact sheet §2.3
constexpr uint16_t full_scale = 0x0FFF;
constexpr int adc_irq = 11; // IFS0 bit 11 (fact sheet §1.7)

} // namespace

Adc::Adc(Cpu &cpu)
  : cpu_(cpu)
{
}

void Adc::attach()
{
    cpu_.attach(buffer_first, adcssl, *this);
}

void Adc::set_input(int channel, uint16_t value)
{
    inputs_.at(static_cast<std::size_t>(channel)) = value & full_scale;
}

uint64_t Adc::tad_cycles(uint64_t tads) const
{
    // Tad = Tcy x (ADCS + 1) / 2: count in half cycles, round up.
    const uint64_t half_cycles = tads * ((adcon3_ & adcon3_adcs) + 1u);
    return (half_cycles + 1) / 2;
}

uint16_t Adc::read(uint16_t address)
{
    switch (address) {
    case adcon1: {
        uint16_t value = static_cast<uint16_t>(adcon1_ & ~(adcon1_samp | adcon1_done));
        if (phase_ == Phase::sampling)
            value |= adcon1_samp;
        if (done_)
            value |= adcon1_done;
        return value;
    }
    case adcon2: return adcon2_;
    case adcon3: return adcon3_;
    case adchs: return adchs_;
    case adpcfg: return adpcfg_;
    case adcssl: return adcssl_;
    default:
        if (address >= buffer_first && address < buffer_first + 2 * channels)
            return buffer_[(address - buffer_first) / 2];
        return 0;
    }
}

void Adc::write(uint16_t address, uint16_t value, uint16_t mask)
{
    const auto merged = [&](uint16_t old) {
        return static_cast<uint16_t>((old & ~mask) | (value & mask));
    };
    const uint64_t now = cpu_.cycles();
    switch (address) {
    case adcon1: {
        const bool was_on = adcon1_ & adcon1_adon;
        const bool was_sampling = phase_ == Phase::sampling;
        const uint16_t next = merged(read(adcon1));
        adcon1_ = static_cast<uint16_t>(next & ~(adcon1_samp | adcon1_done));
        done_ = next & adcon1_done;
        if (!(adcon1_ & adcon1_adon)) { // off: the sequence stops
            phase_ = Phase::idle;
            phase_end_ = never;
            break;
        }
        if (!was_on) {
            scan_last_ = -1;
            filled_ = 0;
        }
        const bool samp = next & adcon1_samp;
        if (samp && phase_ == Phase::idle)
            start_sampling(now);
        else if (!samp && was_sampling && (adcon1_ & adcon1_ssrc) == ssrc_manual)
            start_conversion(now); // ending the sampling starts the conversion
        else if (!was_on && (adcon1_ & adcon1_asam) && phase_ == Phase::idle)
            start_sampling(now);
        break;
    }
    case adcon2: adcon2_ = merged(adcon2_); break;
    case adcon3: adcon3_ = merged(adcon3_); break;
    case adchs: adchs_ = merged(adchs_); break;
    case adpcfg: adpcfg_ = merged(adpcfg_); break;
    case adcssl: adcssl_ = merged(adcssl_); break;
    default: break; // ADCBUFn are read-only
    }
    cpu_.reschedule();
}

int Adc::next_channel()
{
    if (!(adcon2_ & adcon2_cscna) || adcssl_ == 0)
        return adchs_ & adchs_ch0sa;
    for (int step = 1; step <= channels; ++step) {
        const int candidate = (scan_last_ + step) % channels;
        if (adcssl_ & (1u << candidate)) {
            scan_last_ = candidate;
            return candidate;
        }
    }
    return 0;
}

void Adc::start_sampling(uint64_t now)
{
    phase_ = Phase::sampling;
    channel_ = next_channel();
    if ((adcon1_ & adcon1_ssrc) == ssrc_auto) {
        const uint64_t samc = (adcon3_ & adcon3_samc) >> adcon3_samc_shift;
        phase_end_ = now + tad_cycles(samc > 0 ? samc : 1);
    } else {
        phase_end_ = never; // until the program clears SAMP
    }
}

void Adc::start_conversion(uint64_t now)
{
    phase_ = Phase::converting;
    done_ = false;
    // The sample-and-hold keeps the input's level at the end of sampling.
    held_ = input_source_ ? static_cast<uint16_t>(input_source_(channel_, now) & full_scale)
                          : inputs_[channel_];
    phase_end_ = now + tad_cycles(conversion_tads);
}

void Adc::finish_conversion(uint64_t now)
{
    // An input left digital (its ADPCFG bit set) converts as 0.
    const bool analog = !(adpcfg_ & (1u << channel_));
    buffer_[static_cast<std::size_t>(filled_ % channels)] = analog ? held_ : 0;
    done_ = true;
    const int wanted = ((adcon2_ & adcon2_smpi) >> adcon2_smpi_shift) + 1;
    if (++filled_ >= wanted) {
        filled_ = 0;
        scan_last_ = -1;
        cpu_.raise_interrupt(adc_irq);
    }
    phase_ = Phase::idle;
    phase_end_ = never;
    if (adcon1_ & adcon1_asam)
        start_sampling(now);
}

uint64_t Adc::next_event() const
{
    return phase_end_;
}

void Adc::advance(uint64_t now)
{
    while (phase_end_ <= now) {
        const uint64_t at = phase_end_;
        if (phase_ == Phase::sampling)
            start_conversion(at);
        else
            finish_conversion(at);
    }
}

void Adc::reset()
{
    adcon1_ = adcon2_ = adcon3_ = adchs_ = adpcfg_ = adcssl_ = 0;
    buffer_.fill(0);
    phase_ = Phase::idle;
    done_ = false;
    phase_end_ = never;
    scan_last_ = -1;
    filled_ = 0;
}

} // namespace aseba::dspic30
