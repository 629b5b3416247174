/* The protocol between the host tests and the harness image running on the
 * emulated STM32F4 (tests/ports/stm32f4/target/harness_server.c): the host's shims of
 * vm.h and node.h (remote_vm.cpp, remote_node.cpp) turn each call into a
 * request over the image's serial port, and the answer brings back what the
 * call did. Shared by both sides; all numbers little-endian.
 *
 * Request:  REMOTE_REQUEST_MAGIC, command (u8), length (u16), payload.
 * Answer:   REMOTE_ANSWER_MAGIC, status (u8), length (u16), payload.
 * At start-up the image sends an empty REMOTE_OK answer: it listens (QEMU
 * starts it when the host connects, so nothing is lost).
 *
 * REMOTE_OPEN_VM / REMOTE_OPEN_NODE payload: node id, natives or preset
 * (u8), sizes of bytecode, variables, stack, args (u16 each), then the
 * host's memory as in a call (a state block, ignored, then memory runs over
 * zeroed memory); the machine is initialised over it. The answer: for a
 * node its description's fingerprint (u16), then the state block, the
 * memory runs that changed and a node's error counters. REMOTE_CALL payload: the call (u8) and its
 * arguments, then the host's changes to the VM since the last answer (a
 * state block, then memory runs). The answer: the call's result (u16), the
 * events the call caused in order (REMOTE_EVENT_*, ended by
 * REMOTE_EVENT_END), the state block, the memory runs that changed, and for
 * a node its five error counters.
 *
 * State block: pc, sp, flags, breakpoint count, the 16 breakpoints, random
 * state (u16 each). Memory run: area (u8: REMOTE_AREA_*), start, count
 * (u16), the words; REMOTE_AREA_END ends the runs. */

#ifndef REMOTE_PROTOCOL_H
#define REMOTE_PROTOCOL_H

#define REMOTE_REQUEST_MAGIC 0xA5
#define REMOTE_ANSWER_MAGIC  0x5A
#define REMOTE_HEADER_BYTES  4
#define REMOTE_MAX_PAYLOAD   0xFFFF

enum remote_command {
    REMOTE_OPEN_VM = 1,
    REMOTE_OPEN_NODE = 2,
    REMOTE_CALL = 3,
    REMOTE_BENCH = 4, /* event (u16), runs (u16): the open VM runs the event's handler once a
                         step at a time, then to its end `runs` times; answer (u32 each): the
                         handler's steps, the runs' SysTick cycles, then those of a loop of
                         known instructions and their count */
};

enum remote_status {
    REMOTE_OK = 0,
    REMOTE_BAD_REQUEST = 1,
    REMOTE_EVENTS_OVERFLOW = 2,  /* the call caused more than the image can report */
    REMOTE_GUARDS_BROKEN = 3,    /* the VM wrote outside its arrays on the target */
    REMOTE_ANSWER_CONTINUES = 4, /* a call's events so far, sent ahead by an image with
                                    little RAM (the dsPIC30F's); the answer follows, these
                                    events before its own */
};

/* REMOTE_OPEN_VM: the native table. */
enum remote_natives {
    REMOTE_NATIVES_HARNESS = 0, /* tests/support/vm_harness.hpp's twelve */
    REMOTE_NATIVES_EPUCK = 1,   /* the standard natives then the DSP ones (the dsPIC30F's image) */
};

/* REMOTE_OPEN_NODE: the description, as tests/node/node_harness.cpp's presets. */
enum remote_preset {
    REMOTE_PRESET_TINY = 0,
    REMOTE_PRESET_REFNODE = 1,
};

enum remote_call {
    /* vm.h */
    REMOTE_VM_SETUP_EVENT = 1,   /* event -> address */
    REMOTE_VM_RECEIVE_EVENT = 2, /* event, source, count, words */
    REMOTE_VM_RUN = 3,           /* budget -> ran */
    REMOTE_VM_STEP = 4,          /* -> stepped */
    REMOTE_VM_SET_BYTECODE = 5,  /* start, count, words */
    REMOTE_VM_RESET = 6,
    REMOTE_VM_COMMAND_RUN = 7,
    REMOTE_VM_COMMAND_PAUSE = 8,
    REMOTE_VM_COMMAND_STEP = 9,
    REMOTE_VM_COMMAND_STOP = 10,
    REMOTE_VM_REPORT_STATE = 11,
    REMOTE_VM_BREAKPOINT_SET = 12,   /* pc -> stored */
    REMOTE_VM_BREAKPOINT_CLEAR = 13, /* pc */
    REMOTE_VM_BREAKPOINT_CLEAR_ALL = 14,
    REMOTE_VM_EVENT_ADDRESS = 16, /* event -> address */
    REMOTE_VM_CALL_NATIVE = 17,   /* native, pc, count, words: the native called directly
                                     inside a running event -> 1 (the dsPIC30F's image) */
    /* node.h */
    REMOTE_NODE_RECEIVE = 32,      /* now (u32), count, bytes -> taken */
    REMOTE_NODE_RECEIVE_BYTE = 33, /* now (u32), byte -> taken */
    REMOTE_NODE_POLL = 34,         /* now (u32) -> busy */
    REMOTE_NODE_RAISE_LOCAL = 35,  /* index -> raised */
};

enum remote_event {
    REMOTE_EVENT_END = 0,
    REMOTE_EVENT_EMIT = 1,       /* event, count, words */
    REMOTE_EVENT_STATE = 2,      /* pc, flags */
    REMOTE_EVENT_KILLED = 3,     /* pc */
    REMOTE_EVENT_ARRAY = 4,      /* pc, size, index */
    REMOTE_EVENT_DIVISION = 5,   /* pc */
    REMOTE_EVENT_NODE_ERROR = 6, /* pc, length (u8), text */
    REMOTE_EVENT_SEND = 7,       /* count, complete (u8), bytes */
    REMOTE_EVENT_HOOK = 8,       /* which (u8): REMOTE_HOOK_* */
};

enum remote_hook {
    REMOTE_HOOK_WRITE_BYTECODE = 0,
    REMOTE_HOOK_REBOOT = 1,
    REMOTE_HOOK_SUSPEND = 2,
};

enum remote_area {
    REMOTE_AREA_BYTECODE = 0,
    REMOTE_AREA_VARIABLES = 1,
    REMOTE_AREA_STACK = 2,
    REMOTE_AREA_END = 0xFF,
};

#define REMOTE_STATE_WORDS 22 /* pc, sp, flags, count, 16 breakpoints, random state, node id */

#endif
