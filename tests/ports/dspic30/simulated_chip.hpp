// A simulated dsPIC30F6014A for the ports/dspic30 tests: a register file that
// records every access, plus just enough of the peripherals (UART1, ADC,
// I2C master, NVM controller with its table-write latches, flash and EEPROM)
// to run the HAL's routines end to end. Its rules come from the hardware fact
// sheet, written independently of the HAL's code.

#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace simulated
{

// One register write, in program order.
struct Write {
    uint16_t address;
    uint16_t value;
};

// One NVM operation the controller ran.
struct Operation {
    uint16_t nvmcon;
    uint32_t address;         // NVMADRU:NVMADR for erases, the latch row for writes
    uint16_t status_register; // SR when the key sequence ran
};

class Chip
{
  public:
    static constexpr uint32_t flash_words = 0x18000 / 2;
    static constexpr uint32_t eeprom_words = 2048;

    Chip(); // becomes the chip the HAL's register accesses reach
    ~Chip();

    uint16_t read(uint16_t address);
    void write(uint16_t address, uint16_t value);
    void table_write(uint16_t offset, uint16_t value, bool high);
    uint16_t table_read(uint16_t offset, bool high);
    void special(const std::string &instruction);

    // Direct access without side effects, for checks.
    uint16_t &sfr(uint16_t address)
    {
        return registers[address / 2];
    }

    std::vector<Write> writes;
    std::vector<std::string> specials;
    // Runs when the CPU idles (pwrsav #1), where a test lets time pass.
    std::function<void()> on_idle;
    std::vector<Operation> operations;
    int rejected_unlocks = 0; // WR set without the key sequence just before

    std::deque<uint8_t> uart_receive; // bytes waiting in U1RX's FIFO
    std::deque<uint8_t> uart_fifo;    // bytes written to U1TXREG, not yet on the line
    std::vector<uint8_t> uart_sent;   // bytes that left on the line, in order
    int uart_lost = 0;                // bytes written to U1TXREG while UTXBF was set

    // The line takes the oldest byte of the transmit buffer (false when it
    // is empty); with UTXISEL = 1, the buffer emptying sets U1TXIF.
    bool uart_shift_out();
    uint16_t analog[16] = {};

    // I2C devices by 8-bit write address: 256 registers each.
    std::map<uint8_t, std::vector<uint8_t>> i2c_devices;

    std::vector<uint32_t> flash;
    std::vector<uint16_t> eeprom;
    // Data space as bytes (SFRs aside), for code that writes RAM through
    // dspic30_write_byte; filled with a pattern no start-up would write.
    static constexpr uint8_t ram_fill = 0xA5;
    std::vector<uint8_t> ram = std::vector<uint8_t>(0x2800, ram_fill);

  private:
    uint16_t registers[0x800 / 2] = {};
    std::map<uint32_t, uint32_t> latches; // PC address -> 24-bit value

    // I2C transaction state.
    enum class I2cPhase { idle, address, reg, data } i2c_phase = I2cPhase::idle;
    uint8_t i2c_device = 0;
    bool i2c_reading = false;
    uint8_t i2c_register = 0;

    void on_i2c_control(uint16_t value);
    void on_i2c_transmit(uint8_t byte);
    void on_nvm_control(uint16_t previous, uint16_t value);
    void run_operation(uint16_t nvmcon);
};

// The chip currently under test.
Chip &chip();

} // namespace simulated
