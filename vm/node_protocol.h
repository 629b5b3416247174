// The numbers of Aseba wire protocol 5 (protocol.md §2, §3): frame layout,
// limits and message types. Shared by the node and by tests that decode its
// frames.

#ifndef NODE_PROTOCOL_H
#define NODE_PROTOCOL_H

#define NODE_PROTOCOL_VERSION 5

// Frame: len (payload bytes), source, type, then the payload; all uint16 LE.
#define NODE_HEADER_SIZE         6
#define NODE_MAX_PAYLOAD         516 // 258 words; hosts abort on more
#define NODE_MAX_FRAME           (NODE_HEADER_SIZE + NODE_MAX_PAYLOAD)
#define NODE_MAX_STRING          255 // a string is a length byte and its bytes
#define NODE_MAX_VARIABLES_WORDS 257 // values in one VARIABLES answer (+ start)

// Types below this are user events; their payload is int16 words.
#define NODE_FIRST_SYSTEM_TYPE 0x8000

// From nodes to hosts.
#define NODE_MSG_DESCRIPTION                 0x9000
#define NODE_MSG_NAMED_VARIABLE_DESCRIPTION  0x9001
#define NODE_MSG_LOCAL_EVENT_DESCRIPTION     0x9002
#define NODE_MSG_NATIVE_FUNCTION_DESCRIPTION 0x9003
#define NODE_MSG_DISCONNECTED                0x9004
#define NODE_MSG_VARIABLES                   0x9005
#define NODE_MSG_ARRAY_ACCESS_OUT_OF_BOUNDS  0x9006
#define NODE_MSG_DIVISION_BY_ZERO            0x9007
#define NODE_MSG_EVENT_EXECUTION_KILLED      0x9008
#define NODE_MSG_NODE_SPECIFIC_ERROR         0x9009
#define NODE_MSG_EXECUTION_STATE_CHANGED     0x900A
#define NODE_MSG_BREAKPOINT_SET_RESULT       0x900B
#define NODE_MSG_NODE_PRESENT                0x900C

// From hosts: two broadcasts, the others start with `dest`.
#define NODE_MSG_GET_DESCRIPTION      0xA000
#define NODE_MSG_SET_BYTECODE         0xA001
#define NODE_MSG_RESET                0xA002
#define NODE_MSG_RUN                  0xA003
#define NODE_MSG_PAUSE                0xA004
#define NODE_MSG_STEP                 0xA005
#define NODE_MSG_STOP                 0xA006
#define NODE_MSG_GET_EXECUTION_STATE  0xA007
#define NODE_MSG_BREAKPOINT_SET       0xA008
#define NODE_MSG_BREAKPOINT_CLEAR     0xA009
#define NODE_MSG_BREAKPOINT_CLEAR_ALL 0xA00A
#define NODE_MSG_GET_VARIABLES        0xA00B
#define NODE_MSG_SET_VARIABLES        0xA00C
#define NODE_MSG_WRITE_BYTECODE       0xA00D
#define NODE_MSG_REBOOT               0xA00E
#define NODE_MSG_SUSPEND_TO_RAM       0xA00F
#define NODE_MSG_GET_NODE_DESCRIPTION 0xA010
#define NODE_MSG_LIST_NODES           0xA011

// GET_DESCRIPTION is answered only by hosts of this version or older (§6.1).
#define NODE_OLDEST_DESCRIPTION_VERSION 4

#endif
