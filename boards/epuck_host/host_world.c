// The flat world: a still, upright robot on an empty floor in even light.

#include "host_world.h"

static uint16_t flat_adc_read(void *context, uint8_t channel, uint64_t cycle)
{
    (void)context;
    (void)cycle;
    if (channel >= EPUCK_ADC_MICROPHONE_0 && channel < EPUCK_ADC_ACCELEROMETER_X)
        return HOST_FLAT_MICROPHONE;
    if (channel == EPUCK_ADC_ACCELEROMETER_X || channel == EPUCK_ADC_ACCELEROMETER_Y)
        return HOST_FLAT_ACCELERATION_XY;
    if (channel == EPUCK_ADC_ACCELEROMETER_Z)
        return HOST_FLAT_ACCELERATION_Z;
    if (channel >= EPUCK_ADC_PROXIMITY_0 && channel < EPUCK_ADC_CHANNEL_COUNT)
        return HOST_FLAT_PROXIMITY;
    return HOST_FLAT_OTHER_INPUT;
}

static bool flat_pin_read(void *context, epuck_pin pin, uint64_t cycle)
{
    (void)context;
    (void)cycle;
    // The battery-low line and the remote receiver idle high; the selector
    // reads 0 and the camera is silent.
    return pin == EPUCK_PIN_BATTERY_LOW || pin == EPUCK_PIN_REMOTE;
}

static void flat_pin_written(void *context, epuck_pin pin, bool high, uint64_t cycle)
{
    (void)context;
    (void)pin;
    (void)high;
    (void)cycle;
}

static bool flat_i2c_write(void *context,
                           uint8_t device,
                           uint8_t reg,
                           const uint8_t *bytes,
                           uint16_t count)
{
    (void)context;
    (void)device;
    (void)reg;
    (void)bytes;
    (void)count;
    return false;
}

static bool flat_i2c_read(void *context,
                          uint8_t device,
                          uint8_t reg,
                          uint8_t *bytes,
                          uint16_t count)
{
    (void)context;
    (void)device;
    (void)reg;
    (void)bytes;
    (void)count;
    return false;
}

static uint8_t flat_camera_byte(void *context, uint16_t row, uint16_t index, uint64_t cycle)
{
    (void)context;
    (void)row;
    (void)index;
    (void)cycle;
    return 0;
}

static bool flat_adc_channels_steady(void *context, uint16_t channel_mask)
{
    (void)context;
    (void)channel_mask;
    return true; // every input always reads the same
}

static const host_world flat_world = {
    0,
    flat_adc_read,
    flat_pin_read,
    flat_pin_written,
    flat_i2c_write,
    flat_i2c_read,
    flat_camera_byte,
    0,
    0,
    flat_adc_channels_steady,
    0,
    0,
    false,
};

const host_world *host_world_flat(void)
{
    return &flat_world;
}
