// A dsPIC30F UART (UART1 or UART2) on byte streams of the host: what the
// program writes to UxTXREG goes out at once (the transmitter reads empty:
// UTXBF = 0, TRMT = 1), and bytes from the input enter a 4-deep receive
// FIFO at the configured baud rate (fact sheet §2.1).

#pragma once

#include "tools/dspic30_sim/cpu.hpp"
#include "tools/dspic30_sim/peripheral.hpp"

#include <cstdint>
#include <deque>
#include <functional>

namespace aseba::dspic30
{

// Where a UART's registers sit and which interrupts it raises.
struct UartPorts {
    uint16_t base; // UxMODE; UxSTA, UxTXREG, UxRXREG, UxBRG follow
    int rx_irq;
    int tx_irq;
};

inline constexpr UartPorts uart1_ports{ sfr::U1MODE,
                                        9,
                                        10 }; // IRQs (vectors 17, 18; fact sheet §1.7)
inline constexpr UartPorts uart2_ports{ sfr::U2MODE,
                                        24,
                                        25 }; // IRQs (vectors 32, 33; fact sheet §1.7)

class Uart : public Peripheral
{
  public:
    // A transmitted byte goes to `output`; `input` gives the next received
    // byte, or -1 when none is waiting. Either may be empty (no link).
    Uart(Cpu &cpu,
         UartPorts ports,
         std::function<void(uint8_t)> output,
         std::function<int()> input);

    // Attaches the UART's registers to `cpu`.
    void attach();

    uint16_t read(uint16_t address) override;
    void write(uint16_t address, uint16_t value, uint16_t mask) override;
    uint64_t next_event() const override;
    void advance(uint64_t now) override;
    void reset() override;

    // The number of instruction cycles one byte takes on the line (10 bits).
    uint64_t byte_cycles() const;

  private:
    bool enabled() const;
    void update_receive_interrupt();

    Cpu &cpu_;
    UartPorts ports_;
    std::function<void(uint8_t)> output_;
    std::function<int()> input_;
    uint16_t mode_ = 0, status_ = 0, brg_ = 0;
    std::deque<uint8_t> fifo_;
    uint64_t next_receive_ = never;
};

} // namespace aseba::dspic30
