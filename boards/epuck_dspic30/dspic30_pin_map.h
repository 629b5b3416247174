// Where each pin of the e-puck is on the dsPIC30F6014A (§3.1): its port,
// its bit, and whether the firmware drives it. One list for the board's
// GPIO code (dspic30_gpio.c) and for the tools that put a simulated chip
// on an e-puck (tools/emulator/dspic30_robot.cpp), so that the two cannot
// disagree. Plain C: no register of the chip is named here.
//
// DSPIC30_EPUCK_PINS(X) calls X(pin, port letter, bit, OUT or IN) for every
// epuck_pin (robots/epuck/epuck_board.h).

#ifndef DSPIC30_PIN_MAP_H
#define DSPIC30_PIN_MAP_H

// HREF's bit of port C, which the camera's timed row read tests directly
// (dspic30_camera_row.c).
#define DSPIC30_CAMERA_HREF_BIT 3

#define DSPIC30_EPUCK_PINS(X)                                                                      \
    X(EPUCK_PIN_LED_0, A, 6, OUT)                                                                  \
    X(EPUCK_PIN_LED_1, A, 7, OUT)                                                                  \
    X(EPUCK_PIN_LED_2, A, 9, OUT)                                                                  \
    X(EPUCK_PIN_LED_3, A, 12, OUT)                                                                 \
    X(EPUCK_PIN_LED_4, A, 10, OUT)                                                                 \
    X(EPUCK_PIN_LED_5, A, 13, OUT)                                                                 \
    X(EPUCK_PIN_LED_6, A, 14, OUT)                                                                 \
    X(EPUCK_PIN_LED_7, A, 15, OUT)                                                                 \
    X(EPUCK_PIN_FRONT_LED, C, 1, OUT)                                                              \
    /* ⚠ The library also names RC2 CAM_PWDN but never drives it so (§3.1). */                  \
    X(EPUCK_PIN_BODY_LED, C, 2, OUT)                                                               \
    X(EPUCK_PIN_MOTOR_LEFT_A, D, 0, OUT)                                                           \
    X(EPUCK_PIN_MOTOR_LEFT_B, D, 1, OUT)                                                           \
    X(EPUCK_PIN_MOTOR_LEFT_C, D, 2, OUT)                                                           \
    X(EPUCK_PIN_MOTOR_LEFT_D, D, 3, OUT)                                                           \
    X(EPUCK_PIN_MOTOR_RIGHT_A, D, 4, OUT)                                                          \
    X(EPUCK_PIN_MOTOR_RIGHT_B, D, 5, OUT)                                                          \
    X(EPUCK_PIN_MOTOR_RIGHT_C, D, 6, OUT)                                                          \
    X(EPUCK_PIN_MOTOR_RIGHT_D, D, 7, OUT)                                                          \
    X(EPUCK_PIN_IR_PULSE_0_4, F, 7, OUT)                                                           \
    X(EPUCK_PIN_IR_PULSE_1_5, F, 8, OUT)                                                           \
    X(EPUCK_PIN_IR_PULSE_2_6, G, 0, OUT)                                                           \
    X(EPUCK_PIN_IR_PULSE_3_7, G, 1, OUT)                                                           \
    X(EPUCK_PIN_CAMERA_RESET, C, 13, OUT)                                                          \
    X(EPUCK_PIN_AUDIO_ON, F, 0, OUT)                                                               \
    /* ⚠ Selector pull-ups and polarity are undocumented; read raw as the */                     \
    /* library does (§3.8). */                                                                    \
    X(EPUCK_PIN_SELECTOR_0, G, 6, IN)                                                              \
    X(EPUCK_PIN_SELECTOR_1, G, 7, IN)                                                              \
    X(EPUCK_PIN_SELECTOR_2, G, 8, IN)                                                              \
    X(EPUCK_PIN_SELECTOR_3, G, 9, IN)                                                              \
    X(EPUCK_PIN_BATTERY_LOW, F, 1, IN)                                                             \
    X(EPUCK_PIN_REMOTE, F, 6, IN)                                                                  \
    X(EPUCK_PIN_CAMERA_HREF, C, DSPIC30_CAMERA_HREF_BIT, IN)                                       \
    X(EPUCK_PIN_CAMERA_VSYNC, C, 4, IN)                                                            \
    X(EPUCK_PIN_CAMERA_PCLK, C, 14, IN)

#endif
