// What our e-puck tells hosts about itself: its name, named variables and
// local events (its memory sizes are each target's: FIRMWARE_* in its
// configuration). One list serves the firmware (which sends it in
// DESCRIPTION messages and lays out its variables by it) and the host tools
// (the compiler's built-in e-puck target), so the two cannot disagree.
//
// Variable names follow the upstream e-puck firmware that the 2007 paper used
// (hardware/epuck1.md §6.1), so that the paper's controller runs unchanged.
// The first three variables are fixed by the VM (bytecode.md §7). The later
// additions of the GCtronic firmware (§6.1: step counters, microphones,
// selector, RC5, timer period, battery) come after the paper's thirteen, so
// that the paper's names keep their addresses. Ours come last: the
// microphones' recordings (robots/epuck/devices/epuck_microphones.h), for sound
// localisation with the dsp.* natives.

#ifndef EPUCK_DESCRIPTION_H
#define EPUCK_DESCRIPTION_H

#define EPUCK_NAME "e-puck"

// camLine at boot: where in the image the camera's line is, in percent of
// its height (the GCtronic firmware's cam.line, §6.1).
#define EPUCK_CAM_LINE_AT_BOOT 50

// Readings of a microphone in one recording (EPUCK_MICROPHONE_RECORD_SAMPLES
// of robots/epuck/devices/epuck_microphones.h, which checks that they agree).
#define EPUCK_MIC_RECORD_WORDS 32

// EPUCK_VARIABLE(identifier, "name", size in words), in memory order.
#define EPUCK_VARIABLE_LIST(X)                                                                     \
    X(id, "id", 1)                                                                                 \
    X(source, "source", 1)                                                                         \
    X(args, "args", 32)                                                                            \
    X(left_speed, "leftSpeed", 1)                                                                  \
    X(right_speed, "rightSpeed", 1)                                                                \
    X(leds, "leds", 8)                                                                             \
    X(prox, "prox", 8)                                                                             \
    X(ambient, "ambiant", 8)                                                                       \
    X(acc, "acc", 3)                                                                               \
    X(cam_line, "camLine", 1)                                                                      \
    X(cam_red, "camR", 60)                                                                         \
    X(cam_green, "camG", 60)                                                                       \
    X(cam_blue, "camB", 60)                                                                        \
    X(steps_left, "steps.left", 1)                                                                 \
    X(steps_right, "steps.right", 1)                                                               \
    X(mic, "mic", 3)                                                                               \
    X(selector, "sel", 1)                                                                          \
    X(rc5, "rc5", 1)                                                                               \
    X(timer_period, "timer.period", 1)                                                             \
    X(battery, "battery", 1)                                                                       \
    X(mic_samples0, "mic.samples0", EPUCK_MIC_RECORD_WORDS)                                        \
    X(mic_samples1, "mic.samples1", EPUCK_MIC_RECORD_WORDS)                                        \
    X(mic_samples2, "mic.samples2", EPUCK_MIC_RECORD_WORDS)

// EPUCK_LOCAL_EVENT(identifier, "name", "description"), in id order: the i-th
// has event id 0xFFFE - i.
#define EPUCK_LOCAL_EVENT_LIST(X)                                                                  \
    X(ir_sensors, "ir_sensors", "new proximity and ambient values")                                \
    X(camera, "camera", "new camera line")                                                         \
    X(timer, "timer", "timer.period milliseconds elapsed")                                         \
    X(microphones, "microphones", "new recordings in mic.samples0..2")

#endif
