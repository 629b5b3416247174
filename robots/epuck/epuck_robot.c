// The e-puck's description and its variables at boot (epuck_robot.h): what
// every device set of the e-puck shares.

#include "epuck_robot.h"

#include "epuck_natives.h"

static const node_named_variable epuck_variables[] = {
#define EPUCK_VARIABLE_DESCRIPTION(identifier, name, size) { name, size },
    EPUCK_VARIABLE_LIST(EPUCK_VARIABLE_DESCRIPTION)
#undef EPUCK_VARIABLE_DESCRIPTION
};

static const node_local_event epuck_local_events[] = {
#define EPUCK_LOCAL_EVENT_DESCRIPTION(identifier, name, description) { name, description },
    EPUCK_LOCAL_EVENT_LIST(EPUCK_LOCAL_EVENT_DESCRIPTION)
#undef EPUCK_LOCAL_EVENT_DESCRIPTION
};

const node_description robot_description = {
    EPUCK_NAME,          NODE_PROTOCOL_VERSION,
    epuck_variables,     sizeof(epuck_variables) / sizeof(epuck_variables[0]),
    epuck_local_events,  EPUCK_LOCAL_EVENT_COUNT,
    &epuck_native_table,
};

void robot_variables_at_boot(robot_variables *named)
{
    named->cam_line[0] = EPUCK_CAM_LINE_AT_BOOT;
}
