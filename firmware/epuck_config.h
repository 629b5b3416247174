// Sizes and switches of the e-puck firmware, in one place. The dsPIC build
// names this file as VM_TARGET_CONFIG, so the VM and node defaults can be
// overridden here too. Memory sizes and variables are in epuck_description.h.

#ifndef EPUCK_CONFIG_H
#define EPUCK_CONFIG_H

// Bytes taken from the link per main-loop pass.
#define EPUCK_LINK_CHUNK 32

// Local events. Until the sensor drivers raise them, the firmware raises them
// on the clock at the hardware's rates.
// A full 8-sensor IR update every 16 ms (about 63 Hz, hardware §3.2, derived).
#define EPUCK_IR_SENSORS_PERIOD_MS 16
// ⚠ The camera line rate depends on the frame rate, which was never measured;
// 10 Hz is a placeholder until the camera driver raises the event itself.
#define EPUCK_CAMERA_PERIOD_MS 100

#endif
