// The simulated dsPIC30F6014A: register file, peripheral models and the
// functions that ports/dspic30/dspic30_registers.h calls in a test build.

#include "simulated_chip.hpp"

#include <stdexcept>

namespace simulated
{

namespace
{

Chip *current = nullptr;

// SFR addresses and bits, from the fact sheet (§1.8, §2).
constexpr uint16_t TBLPAG = 0x0032, SR = 0x0042, IFS0 = 0x0084;
constexpr uint16_t OSCCON = 0x0742, NVMCON = 0x0760, NVMADR = 0x0762, NVMADRU = 0x0764,
                   NVMKEY = 0x0766;
constexpr uint16_t U1STA = 0x020E, U1TXREG = 0x0210, U1RXREG = 0x0212;
constexpr uint16_t I2CRCV = 0x0200, I2CTRN = 0x0202, I2CCON = 0x0206, I2CSTAT = 0x0208;
constexpr uint16_t ADCBUF0 = 0x0280, ADCON1 = 0x02A0, ADCHS = 0x02A6;

constexpr uint16_t WR = 0x8000;
constexpr uint16_t URXDA = 0x0001, TRMT = 0x0100, UTXBF = 0x0200;
constexpr uint16_t U1TXIF = 0x0400;
constexpr size_t UART_FIFO_BYTES = 4; // §2.1: a 4-deep transmit buffer
constexpr uint16_t SEN = 0x0001, RSEN = 0x0002, PEN = 0x0004, RCEN = 0x0008, ACKEN = 0x0010;
constexpr uint16_t ACKSTAT = 0x8000, RBF = 0x0002;
constexpr uint16_t ADON = 0x8000, SSRC = 0x00E0, SAMP = 0x0002, DONE = 0x0001;
constexpr uint16_t ADIF = 0x0800;

constexpr uint32_t ROW_SPAN = 0x40;
constexpr uint32_t EEPROM_BASE = 0x7FF000;
constexpr uint32_t ERASED_INSTRUCTION = 0xFFFFFF;

} // namespace

Chip::Chip()
  : flash(flash_words, ERASED_INSTRUCTION)
  , eeprom(eeprom_words, 0xFFFF)
{
    if (current)
        throw std::logic_error("one simulated chip at a time");
    current = this;
    sfr(OSCCON) = 0x0020; // the PLL is locked (LOCK, bit 5)
    sfr(U1STA) = TRMT;
}

Chip::~Chip()
{
    current = nullptr;
}

bool Chip::uart_shift_out()
{
    if (uart_fifo.empty())
        return false;
    uart_sent.push_back(uart_fifo.front());
    uart_fifo.pop_front();
    // UTXISEL = 1: the transmit interrupt when the buffer has emptied.
    if (uart_fifo.empty() && (sfr(U1STA) & 0x8000))
        sfr(IFS0) |= U1TXIF;
    return true;
}

Chip &chip()
{
    if (!current)
        throw std::logic_error("no simulated chip");
    return *current;
}

uint16_t Chip::read(uint16_t address)
{
    if (address >= 0x800 || address % 2)
        throw std::out_of_range("SFR address " + std::to_string(address));
    if (address == U1STA) {
        uint16_t status = sfr(U1STA) & ~(URXDA | UTXBF | TRMT);
        if (!uart_receive.empty())
            status |= URXDA;
        if (uart_fifo.size() == UART_FIFO_BYTES)
            status |= UTXBF;
        if (uart_fifo.empty())
            status |= TRMT; // nothing left to shift out
        return status;
    }
    if (address == U1RXREG) {
        if (uart_receive.empty())
            return 0;
        uint8_t byte = uart_receive.front();
        uart_receive.pop_front();
        return byte;
    }
    if (address == I2CRCV)
        sfr(I2CSTAT) &= ~RBF;
    return sfr(address);
}

void Chip::write(uint16_t address, uint16_t value)
{
    if (address >= 0x800 || address % 2)
        throw std::out_of_range("SFR address " + std::to_string(address));
    writes.push_back({ address, value });
    uint16_t previous = sfr(address);
    sfr(address) = value;
    switch (address) {
    case U1TXREG:
        if (uart_fifo.size() == UART_FIFO_BYTES)
            uart_lost++;
        else
            uart_fifo.push_back(uint8_t(value));
        break;
    case U1STA: // URXDA is read-only
        break;
    case I2CCON: on_i2c_control(value); break;
    case I2CTRN: on_i2c_transmit(uint8_t(value)); break;
    case NVMCON: on_nvm_control(previous, value); break;
    case ADCON1:
        // Manual mode: clearing SAMP converts the channel of ADCHS<3:0>.
        if ((value & ADON) && (value & SSRC) == 0 && (previous & SAMP) && !(value & SAMP)) {
            sfr(ADCBUF0) = analog[sfr(ADCHS) & 0xF];
            sfr(ADCON1) |= DONE;
            sfr(IFS0) |= ADIF;
        } else if (value & SAMP) {
            sfr(ADCON1) &= ~DONE;
        }
        break;
    default: break;
    }
}

void Chip::on_i2c_control(uint16_t value)
{
    // Every step completes at once; the module clears its bit.
    if (value & SEN) {
        i2c_phase = I2cPhase::address;
        sfr(I2CCON) &= ~SEN;
    }
    if (value & RSEN) {
        i2c_phase = I2cPhase::address;
        sfr(I2CCON) &= ~RSEN;
    }
    if (value & RCEN) {
        auto device = i2c_devices.find(i2c_device);
        uint8_t byte = 0xFF;
        if (i2c_reading && device != i2c_devices.end())
            byte = device->second[i2c_register++];
        sfr(I2CRCV) = byte;
        sfr(I2CSTAT) |= RBF;
        sfr(I2CCON) &= ~RCEN;
    }
    if (value & ACKEN)
        sfr(I2CCON) &= ~ACKEN;
    if (value & PEN) {
        i2c_phase = I2cPhase::idle;
        sfr(I2CCON) &= ~PEN;
    }
}

void Chip::on_i2c_transmit(uint8_t byte)
{
    bool acknowledged = false;
    switch (i2c_phase) {
    case I2cPhase::idle: break; // no start condition: nobody listens
    case I2cPhase::address:
        i2c_device = uint8_t(byte & 0xFE);
        i2c_reading = byte & 1;
        acknowledged = i2c_devices.count(i2c_device) != 0;
        i2c_phase = i2c_reading ? I2cPhase::data : I2cPhase::reg;
        break;
    case I2cPhase::reg:
        acknowledged = true;
        i2c_register = byte;
        i2c_phase = I2cPhase::data;
        break;
    case I2cPhase::data:
        acknowledged = !i2c_reading;
        if (acknowledged)
            i2c_devices[i2c_device][i2c_register++] = byte;
        break;
    }
    if (acknowledged)
        sfr(I2CSTAT) &= ~ACKSTAT;
    else
        sfr(I2CSTAT) |= ACKSTAT;
}

void Chip::on_nvm_control(uint16_t previous, uint16_t value)
{
    if (!(value & WR) || (previous & WR))
        return;
    // WR starts an operation only right after 0x55 then 0xAA into NVMKEY.
    size_t n = writes.size();
    bool unlocked = n >= 3 && writes[n - 3].address == NVMKEY && writes[n - 3].value == 0x55 &&
                    writes[n - 2].address == NVMKEY && writes[n - 2].value == 0xAA;
    if (!unlocked) {
        rejected_unlocks++;
        sfr(NVMCON) &= ~WR;
        return;
    }
    run_operation(value);
    sfr(NVMCON) &= ~WR; // done at once
}

void Chip::run_operation(uint16_t nvmcon)
{
    uint32_t target = (uint32_t(sfr(NVMADRU) & 0xFF) << 16) | sfr(NVMADR);
    uint16_t code = nvmcon & 0x7FFF;
    Operation operation{ code, target, sfr(SR) };
    if (code == 0x4041) { // erase one program row
        if (target % ROW_SPAN || target / 2 >= flash_words)
            throw std::out_of_range("row erase address");
        for (uint32_t i = 0; i < ROW_SPAN / 2; i++)
            flash[target / 2 + i] = ERASED_INSTRUCTION;
    } else if (code == 0x4001) { // program the row of the latches
        if (latches.empty())
            throw std::logic_error("row write without latches");
        uint32_t row = latches.begin()->first / ROW_SPAN * ROW_SPAN;
        for (auto [address, latch] : latches) {
            if (address / ROW_SPAN * ROW_SPAN != row)
                throw std::logic_error("latches of two rows");
            flash[address / 2] &= latch; // programming only clears bits
        }
        operation.address = row;
    } else if (code == 0x4044) { // erase one EEPROM word
        if (target < EEPROM_BASE || target % 2)
            throw std::out_of_range("EEPROM erase address");
        eeprom[(target - EEPROM_BASE) / 2] = 0xFFFF;
    } else if (code == 0x4004) { // write one EEPROM word from its latch
        if (latches.size() != 1 || latches.begin()->first < EEPROM_BASE)
            throw std::logic_error("EEPROM word write needs one EEPROM latch");
        auto [address, latch] = *latches.begin();
        eeprom[(address - EEPROM_BASE) / 2] &= uint16_t(latch);
        operation.address = address;
    } else {
        throw std::logic_error("NVMCON code not modelled: " + std::to_string(code));
    }
    latches.clear();
    operations.push_back(operation);
}

void Chip::table_write(uint16_t offset, uint16_t value, bool high)
{
    uint32_t address = (uint32_t(sfr(TBLPAG) & 0xFF) << 16) | (offset & 0xFFFE);
    auto [entry, added] = latches.try_emplace(address, ERASED_INSTRUCTION);
    (void)added;
    if (high)
        entry->second = (entry->second & 0x00FFFF) | (uint32_t(value & 0xFF) << 16);
    else
        entry->second = (entry->second & 0xFF0000) | value;
}

uint16_t Chip::table_read(uint16_t offset, bool high)
{
    uint32_t address = (uint32_t(sfr(TBLPAG) & 0xFF) << 16) | (offset & 0xFFFE);
    if (address >= EEPROM_BASE && address < EEPROM_BASE + 2 * eeprom_words)
        return high ? 0 : eeprom[(address - EEPROM_BASE) / 2];
    if (address / 2 >= flash_words)
        throw std::out_of_range("table read address");
    uint32_t word = flash[address / 2];
    // TBLRDH: bits 23:16 in 7:0, phantom byte 0 (§1.2).
    return high ? uint16_t(word >> 16) : uint16_t(word & 0xFFFF);
}

void Chip::special(const std::string &instruction)
{
    specials.push_back(instruction);
    if (instruction == "pwrsav #1" && on_idle)
        on_idle();
}

} // namespace simulated

// The hooks of dspic30_registers.h.
extern "C" {
uint16_t dspic30_simulated_read(uint16_t address)
{
    return simulated::chip().read(address);
}
void dspic30_simulated_write(uint16_t address, uint16_t value)
{
    simulated::chip().write(address, value);
}
void dspic30_simulated_write_byte(uint16_t address, uint8_t value)
{
    simulated::chip().ram.at(address) = value;
}
void dspic30_simulated_table_write_low(uint16_t offset, uint16_t value)
{
    simulated::chip().table_write(offset, value, false);
}
void dspic30_simulated_table_write_high(uint16_t offset, uint16_t value)
{
    simulated::chip().table_write(offset, value, true);
}
uint16_t dspic30_simulated_table_read_low(uint16_t offset)
{
    return simulated::chip().table_read(offset, false);
}
uint16_t dspic30_simulated_table_read_high(uint16_t offset)
{
    return simulated::chip().table_read(offset, true);
}
// What __builtin_write_NVM does on the chip: the two keys, then WR (the DISI
// it starts with is logged as a special).
void dspic30_simulated_nvm_unlock_and_start(void)
{
    auto &chip = simulated::chip();
    chip.special("disi #5");
    chip.write(0x0766, 0x55);
    chip.write(0x0766, 0xAA);
    chip.write(0x0760, uint16_t(chip.read(0x0760) | 0x8000));
}
void dspic30_simulated_special(const char *instruction)
{
    simulated::chip().special(instruction);
}
}
