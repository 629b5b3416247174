/* The harness image: the firmware's VM and node on the emulated STM32F4,
 * driven call by call from the host tests over the serial port
 * (remote_protocol.h). It holds one machine at a time, a bare VM with the
 * test natives or a node with a test preset, its memory between guard
 * words, and a copy of the memory as the host last saw it, so that each
 * answer carries only the words that changed. */

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "ports/stm32f4/stm32f4_chip.h"
#include "ports/stm32f4/stm32f4_registers.h"
#include "node.h"
#include "tests/ports/stm32f4/remote_protocol.h"
#include "remote_events.h"
#include "test_natives.h"

#define AREA_WORDS              2048u /* largest memory area a test asks for (variables: 1060) */
#define GUARD_WORDS             8u
#define GUARD_PATTERN           0xA5C3u
#define REQUEST_BYTES           16384u
#define EVENT_BYTES             16384u
#define ANSWER_BYTES            (EVENT_BYTES + 3u * 2u * AREA_WORDS + 1024u)
#define AREA_COUNT              3u
#define BYTE_BITS               8u
#define MILLISECONDS_PER_SECOND 1000u
#define CALIBRATION_LOOPS       1000000ul

typedef struct area {
    uint16_t words[GUARD_WORDS + AREA_WORDS + GUARD_WORDS];
    uint16_t seen[AREA_WORDS]; /* the words as the host last saw them */
    uint16_t size;
} area;

typedef struct server {
    hal_board board;
    bool is_node;
    vm_state vm;
    node_state node;
    area areas[AREA_COUNT];
    uint16_t words[AREA_WORDS]; /* a call's words, aligned */

    uint8_t request[REQUEST_BYTES];
    uint8_t events[EVENT_BYTES];
    uint16_t event_length;
    bool events_overflowed;
    uint8_t answer[ANSWER_BYTES];
    uint16_t answer_length;
} server;

static server the_server;

/* --- bytes ------------------------------------------------------------------------ */

static uint16_t get16(const uint8_t *bytes)
{
    return (uint16_t)(bytes[0] | (uint16_t)bytes[1] << BYTE_BITS);
}

static uint32_t get32(const uint8_t *bytes)
{
    return (uint32_t)get16(bytes) | (uint32_t)get16(bytes + 2) << 16;
}

static void put16(uint8_t *bytes, uint16_t value)
{
    bytes[0] = (uint8_t)value;
    bytes[1] = (uint8_t)(value >> BYTE_BITS);
}

/* The harness's side of remote_events.h: a call's events, kept whole for its
 * answer, or marked as overflowed. */
void remote_event_bytes(void *context, const void *data, uint16_t count)
{
    server *s = context;
    const uint8_t *bytes = data;
    uint16_t i;
    if (s->event_length + count > EVENT_BYTES) {
        s->events_overflowed = true;
        return;
    }
    for (i = 0; i < count; i++)
        s->events[s->event_length++] = bytes[i];
}

static void answer16(server *s, uint16_t value)
{
    put16(s->answer + s->answer_length, value);
    s->answer_length = (uint16_t)(s->answer_length + 2u);
}

/* --- the machine ---------------------------------------------------------------------- */

static vm_state *machine_vm(server *s)
{
    return s->is_node ? &s->node.vm : &s->vm;
}

static uint16_t *area_memory(area *a)
{
    return a->words + GUARD_WORDS;
}

static bool guards_hold(const server *s)
{
    uint16_t i;
    uint16_t k;
    for (i = 0; i < AREA_COUNT; i++) {
        const area *a = &s->areas[i];
        for (k = 0; k < GUARD_WORDS; k++) {
            if (a->words[k] != GUARD_PATTERN ||
                a->words[GUARD_WORDS + a->size + k] != GUARD_PATTERN)
                return false;
        }
    }
    return true;
}

/* Reads sizes from `payload` (bytecode, variables, stack, args); false when too large. */
static bool prepare_memory(server *s, const uint8_t *payload, vm_memory *memory)
{
    uint16_t i;
    uint16_t k;

    for (i = 0; i < AREA_COUNT; i++) {
        area *a = &s->areas[i];
        a->size = get16(payload + 2u * i);
        if (a->size > AREA_WORDS)
            return false;
        for (k = 0; k < GUARD_WORDS + AREA_WORDS + GUARD_WORDS; k++)
            a->words[k] = GUARD_PATTERN;
        for (k = 0; k < a->size; k++) {
            area_memory(a)[k] = 0;
            a->seen[k] = 0;
        }
    }
    memory->bytecode = area_memory(&s->areas[REMOTE_AREA_BYTECODE]);
    memory->bytecode_size = s->areas[REMOTE_AREA_BYTECODE].size;
    memory->variables = (int16_t *)area_memory(&s->areas[REMOTE_AREA_VARIABLES]);
    memory->variables_size = s->areas[REMOTE_AREA_VARIABLES].size;
    memory->stack = (int16_t *)area_memory(&s->areas[REMOTE_AREA_STACK]);
    memory->stack_size = s->areas[REMOTE_AREA_STACK].size;
    memory->args_size = get16(payload + 2u * AREA_COUNT);
    return true;
}

/* --- synchronising with the host ------------------------------------------------------- */

static void write_state(server *s)
{
    const vm_state *vm = machine_vm(s);
    uint16_t i;
    answer16(s, vm->pc);
    answer16(s, (uint16_t)vm->sp);
    answer16(s, vm->flags);
    answer16(s, vm->breakpoint_count);
    for (i = 0; i < VM_MAX_BREAKPOINTS; i++)
        answer16(s, vm->breakpoints[i]);
    answer16(s, vm->random_state);
    answer16(s, vm->node_id);
}

static const uint8_t *read_state(server *s, const uint8_t *at)
{
    vm_state *vm = machine_vm(s);
    uint16_t i;
    vm->pc = get16(at);
    vm->sp = (int16_t)get16(at + 2);
    vm->flags = get16(at + 4);
    vm->breakpoint_count = get16(at + 6);
    for (i = 0; i < VM_MAX_BREAKPOINTS; i++)
        vm->breakpoints[i] = get16(at + 8 + 2u * i);
    vm->random_state = get16(at + 8 + 2u * VM_MAX_BREAKPOINTS);
    vm->node_id = get16(at + 10 + 2u * VM_MAX_BREAKPOINTS);
    return at + 2u * REMOTE_STATE_WORDS;
}

/* Applies the host's runs; false when one is out of bounds or truncated. */
static bool read_runs(server *s, const uint8_t *at, const uint8_t *end)
{
    while (at < end && *at != REMOTE_AREA_END) {
        area *a;
        uint16_t start;
        uint16_t count;
        uint16_t i;
        if (*at >= AREA_COUNT || end - at < 5)
            return false;
        a = &s->areas[*at];
        start = get16(at + 1);
        count = get16(at + 3);
        at += 5;
        if ((uint32_t)start + count > a->size || end - at < 2 * (long)count)
            return false;
        for (i = 0; i < count; i++, at += 2) {
            area_memory(a)[start + i] = get16(at);
            a->seen[start + i] = get16(at);
        }
    }
    return at < end;
}

static void write_runs(server *s)
{
    uint16_t i;
    for (i = 0; i < AREA_COUNT; i++) {
        area *a = &s->areas[i];
        uint16_t *words = area_memory(a);
        uint16_t k = 0;
        while (k < a->size) {
            uint16_t start;
            if (words[k] == a->seen[k]) {
                k++;
                continue;
            }
            start = k;
            while (k < a->size && words[k] != a->seen[k]) {
                a->seen[k] = words[k];
                k++;
            }
            s->answer[s->answer_length++] = (uint8_t)i;
            answer16(s, start);
            answer16(s, (uint16_t)(k - start));
            for (; start < k; start++)
                answer16(s, words[start]);
        }
    }
    s->answer[s->answer_length++] = REMOTE_AREA_END;
}

/* --- opening a machine ------------------------------------------------------------------- */

#define OPEN_HEADER_BYTES (3u + 2u * (AREA_COUNT + 1u)) /* node id, kind, four sizes */

/* The host's memory for the machine (after the header and a state block,
 * which an opening ignores); false when malformed. */
static bool read_opening_memory(server *s,
                                const uint8_t *payload,
                                uint16_t length,
                                vm_memory *memory)
{
    if (length < OPEN_HEADER_BYTES + 2u * REMOTE_STATE_WORDS ||
        !prepare_memory(s, payload + 3, memory))
        return false;
    return read_runs(s, payload + OPEN_HEADER_BYTES + 2u * REMOTE_STATE_WORDS, payload + length);
}

static bool open_vm(server *s, const uint8_t *payload, uint16_t length)
{
    vm_memory memory;

    if (length < OPEN_HEADER_BYTES || payload[2] != REMOTE_NATIVES_HARNESS ||
        !read_opening_memory(s, payload, length, &memory))
        return false;
    s->is_node = false;
    vm_init(&s->vm, &memory, get16(payload), &harness_natives, &remote_vm_callbacks, s);
    return true;
}

static bool open_node(server *s, const uint8_t *payload, uint16_t length)
{
    static const node_transport transport = { remote_on_send, &the_server };
    static const node_hooks hooks = {
        remote_on_write_bytecode, remote_on_reboot, remote_on_suspend, &the_server
    };
    const node_description *description;
    vm_memory memory;

    if (length < OPEN_HEADER_BYTES)
        return false;
    if (payload[2] == REMOTE_PRESET_TINY)
        description = &tiny_description;
    else if (payload[2] == REMOTE_PRESET_REFNODE)
        description = &refnode_description;
    else
        return false;
    if (!read_opening_memory(s, payload, length, &memory))
        return false;
    s->is_node = true;
    node_init(&s->node, get16(payload), description, &memory, &transport, &hooks);
    return true;
}

/* After an opening or a call: the state block, the memory runs that
 * changed, and a node's error counters. */
static void write_machine(server *s)
{
    write_state(s);
    write_runs(s);
    if (s->is_node) {
        const node_error_counters *errors = &s->node.errors;
        answer16(s, errors->oversize);
        answer16(s, errors->truncated);
        answer16(s, errors->malformed);
        answer16(s, errors->wrong_destination);
        answer16(s, errors->ignored);
    }
}

/* --- calls ------------------------------------------------------------------------------ */

/* The bytes of the call at `payload` and its arguments; 0 for an unknown
 * call or when they do not fit in `length`. */
static uint16_t call_length(const uint8_t *payload, uint16_t length)
{
    uint16_t needed;

    switch (payload[0]) {
    case REMOTE_VM_STEP:
    case REMOTE_VM_RESET:
    case REMOTE_VM_COMMAND_RUN:
    case REMOTE_VM_COMMAND_PAUSE:
    case REMOTE_VM_COMMAND_STEP:
    case REMOTE_VM_COMMAND_STOP:
    case REMOTE_VM_REPORT_STATE:
    case REMOTE_VM_BREAKPOINT_CLEAR_ALL: needed = 1; break;
    case REMOTE_VM_SETUP_EVENT:
    case REMOTE_VM_EVENT_ADDRESS:
    case REMOTE_VM_RUN:
    case REMOTE_VM_BREAKPOINT_SET:
    case REMOTE_VM_BREAKPOINT_CLEAR:
    case REMOTE_NODE_RAISE_LOCAL: needed = 3; break;
    case REMOTE_NODE_POLL: needed = 5; break;
    case REMOTE_NODE_RECEIVE_BYTE: needed = 6; break;
    case REMOTE_VM_RECEIVE_EVENT:
        needed = length >= 7 ? (uint16_t)(7u + 2u * get16(payload + 5)) : 0xFFFFu;
        break;
    case REMOTE_VM_SET_BYTECODE:
        needed = length >= 5 ? (uint16_t)(5u + 2u * get16(payload + 3)) : 0xFFFFu;
        break;
    case REMOTE_NODE_RECEIVE:
        needed = length >= 7 ? (uint16_t)(7u + get16(payload + 5)) : 0xFFFFu;
        break;
    default: return 0;
    }
    return needed <= length ? needed : 0;
}

/* `count` words from `bytes`, into an aligned buffer. */
static const uint16_t *words_of(server *s, const uint8_t *bytes, uint16_t count)
{
    uint16_t i;
    for (i = 0; i < count && i < AREA_WORDS; i++)
        s->words[i] = get16(bytes + 2u * i);
    return s->words;
}

/* Runs the call at `payload`, whose length call_length checked; returns its result. */
static uint16_t run_call(server *s, const uint8_t *payload)
{
    vm_state *vm = machine_vm(s);
    const uint8_t *arguments = payload + 1;
    uint16_t count;

    switch (payload[0]) {
    case REMOTE_VM_SETUP_EVENT: return vm_setup_event(vm, get16(arguments));
    case REMOTE_VM_EVENT_ADDRESS: return vm_event_address(vm, get16(arguments));
    case REMOTE_VM_RECEIVE_EVENT:
        count = get16(arguments + 4);
        vm_receive_event(vm,
                         get16(arguments),
                         get16(arguments + 2),
                         (const int16_t *)words_of(s, arguments + 6, count),
                         count);
        return 0;
    case REMOTE_VM_RUN: return vm_run(vm, get16(arguments));
    case REMOTE_VM_STEP: return vm_step(vm);
    case REMOTE_VM_SET_BYTECODE:
        count = get16(arguments + 2);
        vm_set_bytecode(vm, get16(arguments), words_of(s, arguments + 4, count), count);
        return 0;
    case REMOTE_VM_RESET: vm_reset(vm); return 0;
    case REMOTE_VM_COMMAND_RUN: vm_command_run(vm); return 0;
    case REMOTE_VM_COMMAND_PAUSE: vm_command_pause(vm); return 0;
    case REMOTE_VM_COMMAND_STEP: vm_command_step(vm); return 0;
    case REMOTE_VM_COMMAND_STOP: vm_command_stop(vm); return 0;
    case REMOTE_VM_REPORT_STATE: vm_report_state(vm); return 0;
    case REMOTE_VM_BREAKPOINT_SET: return vm_breakpoint_set(vm, get16(arguments));
    case REMOTE_VM_BREAKPOINT_CLEAR: vm_breakpoint_clear(vm, get16(arguments)); return 0;
    case REMOTE_VM_BREAKPOINT_CLEAR_ALL: vm_breakpoint_clear_all(vm); return 0;
    case REMOTE_NODE_RECEIVE:
        return node_receive(&s->node, arguments + 6, get16(arguments + 4), get32(arguments));
    case REMOTE_NODE_RECEIVE_BYTE:
        return node_receive_byte(&s->node, arguments[4], get32(arguments));
    case REMOTE_NODE_POLL: return node_poll(&s->node, get32(arguments));
    default: /* REMOTE_NODE_RAISE_LOCAL */
        return node_raise_local_event(&s->node, get16(arguments));
    }
}

/* A call: the host's changes (after the call's arguments) first, then the
 * call, then the answer. */
static uint8_t call(server *s, const uint8_t *payload, uint16_t length)
{
    const uint8_t *end = payload + length;
    uint16_t arguments = length >= 1 ? call_length(payload, length) : 0;
    const uint8_t *changes = payload + arguments;
    uint16_t result;
    uint16_t i;

    if (arguments == 0 || end - changes < 2 * REMOTE_STATE_WORDS)
        return REMOTE_BAD_REQUEST;
    changes = read_state(s, changes);
    if (!read_runs(s, changes, end))
        return REMOTE_BAD_REQUEST;

    s->event_length = 0;
    s->events_overflowed = false;
    result = run_call(s, payload);
    if (s->events_overflowed)
        return REMOTE_EVENTS_OVERFLOW;
    if (!guards_hold(s))
        return REMOTE_GUARDS_BROKEN;

    s->answer_length = 0;
    answer16(s, result);
    for (i = 0; i < s->event_length; i++)
        s->answer[s->answer_length++] = s->events[i];
    s->answer[s->answer_length++] = REMOTE_EVENT_END;
    write_machine(s);
    return REMOTE_OK;
}

/* --- measuring ----------------------------------------------------------------------------- */

/* Core clock cycles since start-up, from SysTick. */
static uint32_t cycles_now(server *s)
{
    uint32_t milliseconds;
    uint32_t count;
    uint32_t reload = stm32f4_read(STM32F4_SYST_RVR);
    do {
        milliseconds = hal_milliseconds(&s->board);
        count = stm32f4_read(STM32F4_SYST_CVR);
    } while (milliseconds != hal_milliseconds(&s->board));
    return milliseconds * (reload + 1u) + (reload - count);
}

/* Runs the handler of an event of the loaded program once a step at a time
 * (its steps: the firmware's own count), then to its end `runs` times, and a
 * loop of two instructions per turn, both timed by SysTick: the host turns
 * the cycles into instructions with the loop's. */
static uint8_t bench(server *s, const uint8_t *payload, uint16_t length)
{
    vm_state *vm = machine_vm(s);
    uint32_t turns = CALIBRATION_LOOPS;
    uint32_t start;
    uint32_t vm_cycles;
    uint32_t loop_cycles;
    uint32_t steps = 0;
    uint16_t runs;
    uint16_t event;
    uint16_t r;

    if (length < 4)
        return REMOTE_BAD_REQUEST;
    event = get16(payload);
    runs = get16(payload + 2);
    if (vm_setup_event(vm, event) == 0)
        return REMOTE_BAD_REQUEST;
    while (vm_is_event_active(vm) && vm_step(vm))
        steps++;
    start = cycles_now(s);
    for (r = 0; r < runs; r++) {
        if (vm_setup_event(vm, event) == 0)
            return REMOTE_BAD_REQUEST;
        vm_run(vm, 0);
    }
    vm_cycles = cycles_now(s) - start;
    start = cycles_now(s);
    __asm__ volatile("1: subs %0, %0, #1\n bne 1b" : "+r"(turns)::"cc");
    loop_cycles = cycles_now(s) - start;

    s->answer_length = 0;
    answer16(s, (uint16_t)steps);
    answer16(s, (uint16_t)(steps >> 16));
    answer16(s, (uint16_t)vm_cycles);
    answer16(s, (uint16_t)(vm_cycles >> 16));
    answer16(s, (uint16_t)loop_cycles);
    answer16(s, (uint16_t)(loop_cycles >> 16));
    answer16(s, (uint16_t)(2ul * CALIBRATION_LOOPS));
    answer16(s, (uint16_t)((2ul * CALIBRATION_LOOPS) >> 16));
    return REMOTE_OK;
}

/* --- the serial port ------------------------------------------------------------------------- */

static void receive_exactly(server *s, uint8_t *bytes, uint16_t count)
{
    uint16_t got = 0;
    while (got < count) {
        uint16_t taken = hal_link_receive(&s->board, bytes + got, (uint16_t)(count - got));
        got = (uint16_t)(got + taken);
        if (taken == 0)
            hal_idle(&s->board);
    }
}

static void send_all(server *s, const uint8_t *bytes, uint16_t count)
{
    while (count > 0) {
        uint16_t taken = hal_link_send(&s->board, bytes, count);
        bytes += taken;
        count = (uint16_t)(count - taken);
        if (count > 0)
            hal_idle(&s->board);
    }
}

static void serve(server *s)
{
    uint8_t header[REMOTE_HEADER_BYTES];
    uint16_t length;
    uint8_t status;

    receive_exactly(s, header, 1);
    if (header[0] != REMOTE_REQUEST_MAGIC)
        return; /* resynchronise on the next magic byte */
    receive_exactly(s, header + 1, REMOTE_HEADER_BYTES - 1);
    length = get16(header + 2);
    if (length > REQUEST_BYTES) {
        status = REMOTE_BAD_REQUEST;
        s->answer_length = 0;
    } else {
        receive_exactly(s, s->request, length);
        s->answer_length = 0;
        switch (header[1]) {
        case REMOTE_OPEN_VM:
        case REMOTE_OPEN_NODE:
            status = (header[1] == REMOTE_OPEN_VM ? open_vm(s, s->request, length)
                                                  : open_node(s, s->request, length))
                       ? REMOTE_OK
                       : REMOTE_BAD_REQUEST;
            if (status == REMOTE_OK) {
                if (s->is_node)
                    answer16(s, node_fingerprint(&s->node));
                write_machine(s);
            }
            break;
        case REMOTE_CALL: status = call(s, s->request, length); break;
        case REMOTE_BENCH: status = bench(s, s->request, length); break;
        default: status = REMOTE_BAD_REQUEST; break;
        }
        if (status != REMOTE_OK)
            s->answer_length = 0;
    }
    header[0] = REMOTE_ANSWER_MAGIC;
    header[1] = status;
    put16(header + 2, s->answer_length);
    send_all(s, header, REMOTE_HEADER_BYTES);
    send_all(s, s->answer, s->answer_length);
}

int main(void)
{
    static const uint8_t ready[REMOTE_HEADER_BYTES] = { REMOTE_ANSWER_MAGIC, REMOTE_OK, 0, 0 };

    stm32f4_board_init(&the_server.board);
    send_all(&the_server, ready, sizeof ready);
    for (;;)
        serve(&the_server);
    return 0;
}

void stm32f4_systick_vector(void)
{
    stm32f4_on_systick(&the_server.board);
}

void stm32f4_usart1_vector(void)
{
    stm32f4_on_usart1(&the_server.board);
}
