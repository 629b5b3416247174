// The modelled world's answers (see modelled_world.hpp).

#include "modelled_world.hpp"

namespace drivers_test
{
namespace
{

ModelledWorld &world_of(void *context)
{
    return *static_cast<ModelledWorld *>(context);
}

uint16_t adc_read(void *context, uint8_t channel, uint64_t cycle)
{
    ModelledWorld &world = world_of(context);
    world.conversions.push_back({ channel, cycle });
    if (channel >= EPUCK_ADC_PROXIMITY_0) {
        unsigned sensor = channel - EPUCK_ADC_PROXIMITY_0;
        epuck_pin pulse = epuck_pin(EPUCK_PIN_IR_PULSE_0_4 + sensor % 4);
        uint16_t value = world.ambient[sensor];
        if (world.output[pulse])
            value = uint16_t(value - world.reflection[sensor]);
        return value;
    }
    if (world.signal)
        return world.signal(channel, cycle);
    return world.channel[channel];
}

bool pin_read(void *context, epuck_pin pin, uint64_t cycle)
{
    ModelledWorld &world = world_of(context);
    if (world.input_signal)
        return world.input_signal(pin, cycle);
    return world.input[pin];
}

void pin_written(void *context, epuck_pin pin, bool high, uint64_t cycle)
{
    ModelledWorld &world = world_of(context);
    world.output[pin] = high;
    world.changes.push_back({ pin, high, cycle });
}

bool i2c_write(void *context, uint8_t device, uint8_t reg, const uint8_t *bytes, uint16_t count)
{
    ModelledWorld &world = world_of(context);
    if (!world.camera_present || device != EPUCK_I2C_CAMERA_ADDRESS)
        return false;
    for (uint16_t i = 0; i < count; i++) {
        uint8_t at = uint8_t(reg + i);
        world.camera_registers[at] = bytes[i];
        world.camera_writes.push_back({ at, bytes[i] });
    }
    return true;
}

bool i2c_read(void *context, uint8_t device, uint8_t reg, uint8_t *bytes, uint16_t count)
{
    ModelledWorld &world = world_of(context);
    if (!world.camera_present || device != EPUCK_I2C_CAMERA_ADDRESS)
        return false;
    for (uint16_t i = 0; i < count; i++)
        bytes[i] = world.camera_registers[uint8_t(reg + i)];
    return true;
}

uint64_t input_change_after(void *context, uint64_t after_cycle)
{
    ModelledWorld &world = world_of(context);
    return world.next_input_change ? world.next_input_change(after_cycle) : HOST_NO_INPUT_CHANGE;
}

bool channels_steady(void *context, uint16_t channel_mask)
{
    ModelledWorld &world = world_of(context);
    // The values of `channel` hold still (those of `signal` do not); only
    // the microphones are offered: the proximity channels follow the
    // emitters.
    return world.steady_microphones && !world.signal && channel_mask == EPUCK_MICROPHONE_CHANNELS;
}

uint8_t camera_byte(void *context, uint16_t row, uint16_t index, uint64_t)
{
    ModelledWorld &world = world_of(context);
    if (index == 0)
        world.camera_rows_read.push_back(row);
    return world.camera_pixels ? world.camera_pixels(row, index) : 0;
}

} // namespace

ModelledWorld::ModelledWorld()
{
    table = { this,        adc_read,           pin_read, pin_written,     i2c_write, i2c_read,
              camera_byte, input_change_after, nullptr,  channels_steady, nullptr,   nullptr,
              false };
    input[EPUCK_PIN_REMOTE] = true; // idles high
    input[EPUCK_PIN_BATTERY_LOW] = true;
}

void ModelledWorld::attach(hal_board *board)
{
    host_board_set_world(board, &table);
}

std::vector<PinChange> ModelledWorld::changes_of(epuck_pin pin) const
{
    std::vector<PinChange> result;
    for (const PinChange &change : changes)
        if (change.pin == pin)
            result.push_back(change);
    return result;
}

} // namespace drivers_test
