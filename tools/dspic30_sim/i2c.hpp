// The dsPIC30F6014A's I2C module as a bus master (hardware fact sheet §2.4,
// the family reference manual's I2C section), with the bus's slaves given
// by the simulator's host. Each step the program starts by an I2CCON bit
// (SEN start, RSEN repeated start, PEN stop, RCEN receive, ACKEN
// acknowledge) or by writing I2CTRN takes its time on the bus, then the
// module clears the bit (or TBF and TRSTAT) and raises the master interrupt
// (MI2C, IRQ 14): a start, stop or acknowledge one bit time, a byte sent
// with its acknowledge 9, a byte received 8; a bit time is taken as
// I2CBRG + 1 instruction cycles (⚠ the data sheets' baud formula also has
// a small fixed delay term). I2CSTAT gives S and P, TBF and TRSTAT, RBF,
// ACKSTAT (1: the addressed slave, or none, did not acknowledge) and IWCOL
// (I2CTRN written while the bus is busy). Not modelled: slave mode, 10-bit
// addresses, clock stretching, bus collisions (BCL) and arbitration.

#pragma once

#include "tools/dspic30_sim/cpu.hpp"
#include "tools/dspic30_sim/peripheral.hpp"

#include <cstdint>
#include <map>

namespace aseba::dspic30
{

// A slave on the bus, at one 7-bit address.
class I2cDevice
{
  public:
    virtual ~I2cDevice() = default;
    // A start (or repeated start) then its address byte: `reading` when
    // the master reads.
    virtual void start(bool reading) = 0;
    // A byte from the master; whether the device acknowledges it.
    virtual bool receive(uint8_t byte) = 0;
    // The next byte the master reads.
    virtual uint8_t send() = 0;
    // A stop condition.
    virtual void stop() {}
};

class I2cMaster : public Peripheral
{
  public:
    explicit I2cMaster(Cpu &cpu);

    // Attaches I2CRCV..I2CADD to `cpu`.
    void attach();
    // Puts `device` on the bus at 7-bit address `address`.
    void connect(uint8_t address, I2cDevice &device);

    uint16_t read(uint16_t address) override;
    void write(uint16_t address, uint16_t value, uint16_t mask) override;
    uint64_t next_event() const override;
    void advance(uint64_t now) override;
    void reset() override;

  private:
    enum class Step : uint8_t { none, start, restart, stop, transmit, receive, acknowledge };

    void begin(Step step, uint64_t bits);
    void complete();

    Cpu &cpu_;
    std::map<uint8_t, I2cDevice *> devices_;
    uint16_t control_ = 0, status_ = 0, baud_ = 0, own_address_ = 0;
    uint8_t transmit_ = 0, received_ = 0;
    Step step_ = Step::none;
    uint64_t step_end_ = never;
    bool expecting_address_ = false; // the next byte sent follows a start
    I2cDevice *current_ = nullptr;   // the slave addressed, if it answered
};

} // namespace aseba::dspic30
