// The I2C master's steps, each timed on the instruction clock, and the
// bytes exchanged with the host's devices.

#include "tools/dspic30_sim/i2c.hpp"

namespace aseba::dspic30
{
namespace
{

constexpr uint16_t i2crcv = 0x0200, i2ctrn = 0x0202, i2cbrg = 0x0204, i2ccon = 0x0206,
                   i2cstat = 0x0208, i2cadd = 0x020A;
constexpr uint16_t con_i2cen = 1u << 15;
constexpr uint16_t con_acken = 1u << 4;
constexpr uint16_t con_rcen = 1u << 3;
constexpr uint16_t con_pen = 1u << 2;
constexpr uint16_t con_rsen = 1u << 1;
constexpr uint16_t con_sen = 1u << 0;
constexpr uint16_t con_steps = con_acken | con_rcen | con_pen | con_rsen | con_sen;
constexpr uint16_t stat_ackstat = 1u << 15;
constexpr uint16_t stat_trstat = 1u << 14;
constexpr uint16_t stat_iwcol = 1u << 7;
constexpr uint16_t stat_i2cov = 1u << 6;
constexpr uint16_t stat_p = 1u << 4;
constexpr uint16_t stat_s = 1u << 3;
constexpr uint16_t stat_rbf = 1u << 1;
constexpr uint16_t stat_tbf = 1u << 0;
// What the program may clear or set in I2CSTAT (the rest is the module's).
constexpr uint16_t stat_writable = stat_iwcol | stat_i2cov | (1u << 10); // BCL
constexpr uint16_t brg_bits = 0x01FF;
constexpr int master_irq = 14; // IFS0 bit 14, MI2C (fact sheet §1.7)
constexpr uint64_t byte_and_acknowledge_bits = 9, byte_bits = 8;

} // namespace

I2cMaster::I2cMaster(Cpu &cpu)
  : cpu_(cpu)
{
}

void I2cMaster::attach()
{
    cpu_.attach(i2crcv, i2cadd, *this);
}

void I2cMaster::connect(uint8_t address, I2cDevice &device)
{
    devices_[static_cast<uint8_t>(address & 0x7F)] = &device;
}

uint16_t I2cMaster::read(uint16_t address)
{
    switch (address) {
    case i2crcv: status_ = static_cast<uint16_t>(status_ & ~stat_rbf); return received_;
    case i2ctrn: return transmit_;
    case i2cbrg: return baud_;
    case i2ccon: return control_;
    case i2cstat: return status_;
    case i2cadd: return own_address_;
    default: return 0;
    }
}

void I2cMaster::write(uint16_t address, uint16_t value, uint16_t mask)
{
    const auto merged = [&](uint16_t old) {
        return static_cast<uint16_t>((old & ~mask) | (value & mask));
    };
    switch (address) {
    case i2ctrn:
        if (!(control_ & con_i2cen))
            break;
        if (step_ != Step::none || (status_ & stat_tbf)) {
            status_ |= stat_iwcol; // the bus is busy: the byte is not sent
            break;
        }
        transmit_ = static_cast<uint8_t>(value & mask);
        status_ |= stat_tbf | stat_trstat;
        begin(Step::transmit, byte_and_acknowledge_bits);
        break;
    case i2cbrg: baud_ = merged(baud_) & brg_bits; break;
    case i2ccon: {
        const uint16_t started = static_cast<uint16_t>(merged(control_) & ~control_ & con_steps);
        control_ = merged(control_);
        if (!(control_ & con_i2cen)) {
            control_ = static_cast<uint16_t>(control_ & ~con_steps);
            step_ = Step::none;
            step_end_ = never;
            break;
        }
        if (step_ != Step::none || started == 0)
            break; // ⚠ a step started while another runs is ignored
        if (started & con_sen)
            begin(Step::start, 1);
        else if (started & con_rsen)
            begin(Step::restart, 1);
        else if (started & con_pen)
            begin(Step::stop, 1);
        else if (started & con_rcen)
            begin(Step::receive, byte_bits);
        else if (started & con_acken)
            begin(Step::acknowledge, 1);
        break;
    }
    case i2cstat:
        status_ =
          static_cast<uint16_t>((status_ & ~stat_writable) | (merged(status_) & stat_writable));
        break;
    case i2cadd: own_address_ = merged(own_address_); break;
    default: break;
    }
}

void I2cMaster::begin(Step step, uint64_t bits)
{
    step_ = step;
    step_end_ = cpu_.cycles() + bits * (static_cast<uint64_t>(baud_) + 1);
    cpu_.reschedule();
}

void I2cMaster::complete()
{
    switch (step_) {
    case Step::start:
    case Step::restart:
        control_ = static_cast<uint16_t>(control_ & ~(con_sen | con_rsen));
        status_ = static_cast<uint16_t>((status_ | stat_s) & ~stat_p);
        expecting_address_ = true;
        current_ = nullptr;
        break;
    case Step::stop:
        control_ = static_cast<uint16_t>(control_ & ~con_pen);
        status_ = static_cast<uint16_t>((status_ | stat_p) & ~stat_s);
        if (current_ != nullptr)
            current_->stop();
        current_ = nullptr;
        break;
    case Step::transmit: {
        bool acknowledged = false;
        if (expecting_address_) {
            expecting_address_ = false;
            const auto found = devices_.find(static_cast<uint8_t>(transmit_ >> 1));
            current_ = found == devices_.end() ? nullptr : found->second;
            if (current_ != nullptr) {
                current_->start(transmit_ & 1);
                acknowledged = true;
            }
        } else if (current_ != nullptr) {
            acknowledged = current_->receive(transmit_);
        }
        status_ = static_cast<uint16_t>(status_ & ~(stat_tbf | stat_trstat));
        if (acknowledged)
            status_ = static_cast<uint16_t>(status_ & ~stat_ackstat);
        else
            status_ |= stat_ackstat;
        break;
    }
    case Step::receive:
        control_ = static_cast<uint16_t>(control_ & ~con_rcen);
        if (status_ & stat_rbf)
            status_ |= stat_i2cov;                                 // the last byte was not read
        received_ = current_ != nullptr ? current_->send() : 0xFF; // an idle bus reads ones
        status_ |= stat_rbf;
        break;
    case Step::acknowledge:
        // ACKDT goes out on the bus; a device here learns the end of a
        // read from the stop that follows.
        control_ = static_cast<uint16_t>(control_ & ~con_acken);
        break;
    case Step::none: break;
    }
    step_ = Step::none;
    step_end_ = never;
    cpu_.raise_interrupt(master_irq);
}

uint64_t I2cMaster::next_event() const
{
    return step_end_;
}

void I2cMaster::advance(uint64_t now)
{
    if (step_end_ <= now)
        complete();
}

void I2cMaster::reset()
{
    control_ = status_ = baud_ = own_address_ = 0;
    transmit_ = received_ = 0;
    step_ = Step::none;
    step_end_ = never;
    expecting_address_ = false;
    current_ = nullptr;
}

} // namespace aseba::dspic30
