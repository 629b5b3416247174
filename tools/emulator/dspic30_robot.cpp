// The e-puck's board around the simulated chip (see dspic30_robot.hpp).

#include "dspic30_robot.hpp"

#include <algorithm>

#include <array>

extern "C" {
#include "boards/epuck_dspic30/dspic30_pin_map.h"
}

namespace aseba::arena
{
namespace
{

struct PinPlace {
    char port;
    uint8_t bit;
};

// Where each pin of the e-puck is on the chip, from the board's own list.
#define PIN_PLACE(pin, port, bit, direction) places[pin] = { (#port)[0], bit };
constexpr std::array<PinPlace, EPUCK_PIN_COUNT> pin_places = [] {
    std::array<PinPlace, EPUCK_PIN_COUNT> places{};
    DSPIC30_EPUCK_PINS(PIN_PLACE)
    return places;
}();
#undef PIN_PLACE

// The camera's data lines: the upper byte of port D (§3.5).
constexpr unsigned camera_data_shift = 8;
// The timers whose external clock pins HREF and VSYNC are wired to (§2.2).
constexpr int camera_href_timer = 4;
constexpr int camera_vsync_timer = 5;

uint16_t bit_of(epuck_pin pin)
{
    return uint16_t(1u << pin_places[pin].bit);
}

} // namespace

// The camera on the I2C bus: register writes and reads as the firmware
// makes them (a register address after a start for writing, then data
// bytes, or a repeated start for reading), answered by the world's
// i2c_write and i2c_read one register at a time.
class Dspic30Robot::CameraBus : public dspic30::I2cDevice
{
  public:
    explicit CameraBus(const host_world &world)
      : world_(world)
    {
    }

    void start(bool reading) override
    {
        reading_ = reading;
        have_register_ = reading_ ? have_register_ : false;
    }

    bool receive(uint8_t byte) override
    {
        if (!have_register_) {
            register_ = byte;
            have_register_ = true;
            return true;
        }
        return world_.i2c_write(world_.context, EPUCK_I2C_CAMERA_ADDRESS, register_++, &byte, 1);
    }

    uint8_t send() override
    {
        uint8_t byte = 0;
        if (!world_.i2c_read(world_.context, EPUCK_I2C_CAMERA_ADDRESS, register_++, &byte, 1))
            return 0xFF; // nothing drives the bus: it reads high
        return byte;
    }

  private:
    const host_world &world_;
    bool reading_ = false;
    bool have_register_ = false;
    uint8_t register_ = 0;
};

Dspic30Robot::Dspic30Robot(const std::map<uint32_t, uint32_t> &image, const host_world &world)
  : world_(world)
  , pixel_port_(world)
  , camera_bus_(std::make_unique<CameraBus>(world))
{
    chip_ =
      std::make_unique<dspic30::Simulator>([this](uint8_t byte) { from_chip_.push_back(byte); },
                                           [this]() {
                                               if (to_chip_.empty())
                                                   return -1;
                                               int byte = to_chip_.front();
                                               to_chip_.pop_front();
                                               return byte;
                                           });
    chip_->load(image);
    chip_->gpio().set_input_sampler([this](char letter) { sample_inputs(letter); });
    chip_->gpio().set_pins_changed([this](char letter, uint16_t before, uint16_t after) {
        pins_changed(letter, before, after);
    });
    chip_->adc().set_input_source([this](int channel, uint64_t cycle) {
        return world_.adc_read(world_.context, uint8_t(channel), cycle);
    });
    chip_->i2c().connect(EPUCK_I2C_CAMERA_ADDRESS >> 1, *camera_bus_);
    // HREF and VSYNC also reach the external clock inputs of Timers 4 and 5
    // (T4CK RC3, T5CK RC4, §2.2), which the firmware may count them with.
    // PCLK on T1CK (RC14) is not given to Timer1: no firmware counts it.
    chip_->timers().connect_clock(camera_href_timer, &pixel_port_.href_clock());
    chip_->timers().connect_clock(camera_vsync_timer, &pixel_port_.vsync_clock());
    for (char letter : { 'A', 'B', 'C', 'D', 'F', 'G' })
        sample_inputs(letter);
}

Dspic30Robot::~Dspic30Robot() = default;

void Dspic30Robot::sample_inputs(char letter)
{
    const uint64_t cycle = chip_->cpu().cycles();
    uint16_t levels = 0;
    for (int pin = EPUCK_PIN_FIRST_INPUT; pin < EPUCK_PIN_COUNT; pin++) {
        if (pin_places[pin].port != letter || pin == EPUCK_PIN_CAMERA_HREF ||
            pin == EPUCK_PIN_CAMERA_VSYNC || pin == EPUCK_PIN_CAMERA_PCLK)
            continue;
        if (world_.pin_read(world_.context, epuck_pin(pin), cycle))
            levels |= bit_of(epuck_pin(pin));
    }
    if (letter == 'C' || letter == 'D') {
        const PixelPortLevels camera = pixel_port_.at(cycle);
        if (letter == 'C') {
            levels |= camera.href ? bit_of(EPUCK_PIN_CAMERA_HREF) : 0;
            levels |= camera.vsync ? bit_of(EPUCK_PIN_CAMERA_VSYNC) : 0;
            levels |= camera.pclk ? bit_of(EPUCK_PIN_CAMERA_PCLK) : 0;
        } else {
            levels |= uint16_t(camera.data << camera_data_shift);
        }
    }
    chip_->gpio().set_input_levels(letter, levels);
}

void Dspic30Robot::pins_changed(char letter, uint16_t before, uint16_t after)
{
    const uint64_t cycle = chip_->cpu().cycles();
    for (int pin = 0; pin < EPUCK_PIN_FIRST_INPUT; pin++) {
        if (pin_places[pin].port != letter || !((before ^ after) & bit_of(epuck_pin(pin))))
            continue;
        world_.pin_written(
          world_.context, epuck_pin(pin), (after & bit_of(epuck_pin(pin))) != 0, cycle);
    }
}

dspic30::Outcome Dspic30Robot::run_until(uint64_t cycle)
{
    // The chip stops at each change of the world's inputs, which then reach
    // its pins at their own cycle: an edge on RF6 is INT0, the remote's.
    while (chip_->cpu().cycles() < cycle) {
        dspic30::RunLimits limits;
        limits.cycles = cycle;
        if (world_.next_input_change) {
            const uint64_t change = world_.next_input_change(world_.context, chip_->cpu().cycles());
            limits.cycles = std::min(cycle, std::max(change, chip_->cpu().cycles() + 1));
        }
        const dspic30::Outcome outcome = chip_->run(limits).outcome;
        if (outcome != dspic30::Outcome::cycle_limit)
            return outcome;
        for (char letter : { 'F', 'G' })
            sample_inputs(letter);
    }
    return dspic30::Outcome::cycle_limit;
}

void Dspic30Robot::receive(const uint8_t *bytes, size_t count)
{
    to_chip_.insert(to_chip_.end(), bytes, bytes + count);
}

std::vector<uint8_t> Dspic30Robot::take_output()
{
    std::vector<uint8_t> bytes;
    bytes.swap(from_chip_);
    return bytes;
}

bool Dspic30Robot::output(epuck_pin pin) const
{
    const PinPlace &place = pin_places.at(pin);
    return (chip_->gpio().pins(place.port) >> place.bit) & 1u;
}

} // namespace aseba::arena
