// The e-puck's named variables, those of its description as a struct, so
// that the firmware and the robot's devices write them by name. The
// firmware's variable memory holds them, then the words left for user
// variables (FIRMWARE_FREE_VARIABLE_WORDS of the target's configuration).

#ifndef EPUCK_VARIABLES_H
#define EPUCK_VARIABLES_H

#include <stdint.h>

#include "epuck_description.h"

typedef struct epuck_named_variables {
#define EPUCK_VARIABLE_MEMBER(identifier, name, size) int16_t identifier[size];
    EPUCK_VARIABLE_LIST(EPUCK_VARIABLE_MEMBER)
#undef EPUCK_VARIABLE_MEMBER
} epuck_named_variables;

#define EPUCK_VARIABLE_WORDS(identifier, name, size) +(size)
#define EPUCK_NAMED_WORDS                            (0 EPUCK_VARIABLE_LIST(EPUCK_VARIABLE_WORDS))

// The struct must lay the variables out exactly as the description counts them.
typedef char epuck_named_variables_have_no_padding
  [sizeof(epuck_named_variables) == EPUCK_NAMED_WORDS * sizeof(int16_t) ? 1 : -1];

// The local events, by index (the i-th has event id 0xFFFE - i).
enum epuck_local_event {
#define EPUCK_LOCAL_EVENT_INDEX(identifier, name, description) EPUCK_EVENT_##identifier,
    EPUCK_LOCAL_EVENT_LIST(EPUCK_LOCAL_EVENT_INDEX)
#undef EPUCK_LOCAL_EVENT_INDEX
      EPUCK_LOCAL_EVENT_COUNT
};

#endif
