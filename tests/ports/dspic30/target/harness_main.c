/* The harness image on the dsPIC30F6014A: the firmware's VM, node and
 * natives, compiled as `make dspic30` compiles the application, driven call
 * by call from the host tests over UART1 (tests/ports/stm32f4/remote_protocol.h,
 * the protocol of the STM32F4's harness image).
 *
 * The chip has 8 KB of RAM, so unlike the STM32F4's image this one keeps no
 * copy of what the host last saw and buffers no whole answer: a request's
 * memory runs go straight into the VM's memory as they arrive, an answer
 * carries every word of the memory (the host applies them as runs), and when the events a call
 * causes outgrow their buffer it goes out ahead as a REMOTE_ANSWER_CONTINUES frame. UART1 receives
 * through the port's driver (dspic30_uart.c), on a faster line; answers go out polled.
 *
 * Beyond the STM32F4 image's requests: a bare VM may have the e-puck's
 * natives (standard, then DSP: REMOTE_NATIVES_EPUCK), and REMOTE_VM_CALL_NATIVE
 * calls one of them directly, as the DSP natives' tests do; REMOTE_BENCH
 * times with Timer2/3 as one 32-bit counter of instruction cycles. */

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "nat_dsp.h"
#include "nat_standard.h"
#include "nat_words.h"
#include "node.h"
#include "ports/dspic30/dspic30_chip.h"
#include "ports/dspic30/dspic30_registers.h"
#include "tests/ports/stm32f4/remote_protocol.h"
#include "tests/ports/stm32f4/target/remote_events.h"
#include "tests/ports/stm32f4/target/test_natives.h"

/* The largest memory each area gets from a test (tests/node's refnode
 * preset: bytecode 512, stack 64, variables 1060), between guard words. */
#define BYTECODE_WORDS_MAX  512u
#define VARIABLES_WORDS_MAX 1060u
#define STACK_WORDS_MAX     64u
#define GUARD_WORDS         4u
#define GUARD_PATTERN       0xA5C3u
#define AREA_COUNT          3u
/* A call's bulk arguments: SET_BYTECODE's words or a frame's bytes. */
#define ARGUMENT_WORDS 560u
/* UxBRG = 1: FCY / 32, 460800 baud at the e-puck's clock. At BRG = 0 (a
 * byte every 160 cycles) the receive interrupt falls behind and bytes are
 * lost. */
#define HARNESS_UART_BRG 1u
#define EVENT_BYTES      256u
#define BYTE_BITS        8u

/* Timer2/3 as one 32-bit counter: reading TMR2 latches TMR3 here
 * (dsPIC30F Family Reference Manual, 32-bit timer mode). */
#define HARNESS_TMR3HLD 0x0108u
/* The calibration: REPEAT's count (its target runs count + 1 times), in
 * the instruction's text too. */
#define CALIBRATION_REPEAT      9999u
#define CALIBRATION_REPEAT_TEXT "9999"

typedef struct area {
    uint16_t *words; /* after the leading guard words */
    uint16_t capacity;
    uint16_t size;
} area;

static uint16_t bytecode_store[GUARD_WORDS + BYTECODE_WORDS_MAX + GUARD_WORDS];
static uint16_t variables_store[GUARD_WORDS + VARIABLES_WORDS_MAX + GUARD_WORDS];
static uint16_t stack_store[GUARD_WORDS + STACK_WORDS_MAX + GUARD_WORDS];

typedef struct server {
    bool is_node;
    bool bad;        /* the request being read is malformed */
    uint16_t unread; /* bytes of the request not yet read */
    vm_state vm;
    node_state node;
    area areas[AREA_COUNT];

    /* the call being served */
    uint8_t call;
    uint16_t first;  /* its first u16 argument */
    uint16_t second; /* its second */
    uint16_t count;  /* words or bytes of `bulk` */
    uint32_t now;    /* a node call's time */
    union {
        uint16_t words[ARGUMENT_WORDS];
        uint8_t bytes[2u * ARGUMENT_WORDS];
    } bulk;

    uint8_t events[EVENT_BYTES];
    uint16_t event_length;
} server;

static server the_server;

/* The e-puck's order, as tests/native_functions_dsp/dsp_node.cpp's table. */
static const vm_native_module *const epuck_modules[] = { NAT_STANDARD_MODULES NAT_DSP_MODULES };
static const vm_native_table epuck_natives = { epuck_modules,
                                               sizeof epuck_modules / sizeof epuck_modules[0],
                                               nat_words };

/* The DSP tests' deliberately faulty FFT (tests/native_functions_dsp/
 * dsp_fft_truncating_mutant.c), which they must catch on this chip too:
 * REMOTE_VM_CALL_NATIVE's index just after the e-puck's table. */
extern const vm_native_module nat_dsp_fft_truncating_mutant_module;

/* --- UART1: the port's driver receives, answers go out polled ------------------------------ */

static hal_board board;

/* The port's UART1 (its receive interrupt fills the board's ring), then a
 * faster line than the robot's 115200 baud: on the simulator the line's
 * speed is only a cost in cycles. */
static void link_init(void)
{
    dspic30_clock_init(&board);
    dspic30_uart_init(&board);
    dspic30_write(DSPIC30_U1BRG, HARNESS_UART_BRG);
}

static uint8_t uart_receive(void)
{
    uint8_t byte;
    while (hal_link_receive(&board, &byte, 1) == 0)
        hal_idle(&board);
    return byte;
}

/* Straight into the transmit buffer, not through the driver's ring and
 * interrupt: an answer carries kilobytes of memory, and the ring's 32 bytes
 * at a time (a critical section each) cost the chip twice the cycles of
 * the whole test. The driver's transmit interrupt stays disabled (its ring
 * stays empty). */
static void uart_send(uint8_t byte)
{
    while (dspic30_read(DSPIC30_U1STA) & DSPIC30_USTA_UTXBF)
        ;
    dspic30_write(DSPIC30_U1TXREG, byte);
}

static void send16(uint16_t value)
{
    uart_send((uint8_t)value);
    uart_send((uint8_t)(value >> BYTE_BITS));
}

static void send_header(uint8_t status, uint16_t length)
{
    uart_send(REMOTE_ANSWER_MAGIC);
    uart_send(status);
    send16(length);
}

/* --- the request, read as it arrives ----------------------------------------------------- */

static uint8_t take8(server *s)
{
    if (s->unread == 0) {
        s->bad = true;
        return 0;
    }
    s->unread--;
    return uart_receive();
}

static uint16_t take16(server *s)
{
    uint16_t low = take8(s);
    return (uint16_t)(low | (uint16_t)take8(s) << BYTE_BITS);
}

static uint32_t take32(server *s)
{
    uint32_t low = take16(s);
    return low | (uint32_t)take16(s) << 16;
}

/* Reads what is left of a request (after a fault), to stay in step. */
static void drain(server *s)
{
    while (s->unread > 0)
        (void)take8(s);
}

/* --- what the machine reports ----------------------------------------------------------- */

/* Sends the events so far ahead of the answer (REMOTE_ANSWER_CONTINUES). */
static void flush_events(server *s)
{
    uint16_t i;
    send_header(REMOTE_ANSWER_CONTINUES, s->event_length);
    for (i = 0; i < s->event_length; i++)
        uart_send(s->events[i]);
    s->event_length = 0;
}

/* The harness's side of remote_events.h: a call's events, sent ahead when
 * they outgrow their buffer. */
void remote_event_bytes(void *context, const void *data, uint16_t count)
{
    server *s = context;
    const uint8_t *bytes = data;
    uint16_t i;
    for (i = 0; i < count; i++) {
        if (s->event_length == EVENT_BYTES)
            flush_events(s);
        s->events[s->event_length++] = bytes[i];
    }
}

/* --- the machine's memory ---------------------------------------------------------------- */

static vm_state *machine_vm(server *s)
{
    return s->is_node ? &s->node.vm : &s->vm;
}

static void bind_areas(server *s)
{
    s->areas[REMOTE_AREA_BYTECODE].words = bytecode_store + GUARD_WORDS;
    s->areas[REMOTE_AREA_BYTECODE].capacity = BYTECODE_WORDS_MAX;
    s->areas[REMOTE_AREA_VARIABLES].words = variables_store + GUARD_WORDS;
    s->areas[REMOTE_AREA_VARIABLES].capacity = VARIABLES_WORDS_MAX;
    s->areas[REMOTE_AREA_STACK].words = stack_store + GUARD_WORDS;
    s->areas[REMOTE_AREA_STACK].capacity = STACK_WORDS_MAX;
}

static bool guards_hold(const server *s)
{
    uint16_t i;
    uint16_t k;
    for (i = 0; i < AREA_COUNT; i++) {
        const area *a = &s->areas[i];
        for (k = 1; k <= GUARD_WORDS; k++) {
            if (a->words[-(int16_t)k] != GUARD_PATTERN ||
                a->words[a->size + k - 1u] != GUARD_PATTERN)
                return false;
        }
    }
    return true;
}

/* Reads the four sizes (bytecode, variables, stack, args), zeroes the
 * memory and sets the guards; false when an area does not fit. */
static bool prepare_memory(server *s, vm_memory *memory)
{
    uint16_t i;
    uint16_t k;
    bool fits = true;

    for (i = 0; i < AREA_COUNT; i++) {
        area *a = &s->areas[i];
        a->size = take16(s);
        if (a->size > a->capacity) {
            fits = false;
            a->size = 0;
        }
        for (k = 1; k <= GUARD_WORDS; k++) {
            a->words[-(int16_t)k] = GUARD_PATTERN;
            a->words[a->size + k - 1u] = GUARD_PATTERN;
        }
        for (k = 0; k < a->size; k++)
            a->words[k] = 0;
    }
    memory->bytecode = s->areas[REMOTE_AREA_BYTECODE].words;
    memory->bytecode_size = s->areas[REMOTE_AREA_BYTECODE].size;
    memory->variables = (int16_t *)s->areas[REMOTE_AREA_VARIABLES].words;
    memory->variables_size = s->areas[REMOTE_AREA_VARIABLES].size;
    memory->stack = (int16_t *)s->areas[REMOTE_AREA_STACK].words;
    memory->stack_size = s->areas[REMOTE_AREA_STACK].size;
    memory->args_size = take16(s);
    return fits;
}

/* The host's state block into `vm` (NULL: read and ignored). */
static void read_state(server *s, vm_state *vm)
{
    uint16_t words[REMOTE_STATE_WORDS];
    uint16_t i;
    for (i = 0; i < REMOTE_STATE_WORDS; i++)
        words[i] = take16(s);
    if (vm == NULL || s->bad)
        return;
    vm->pc = words[0];
    vm->sp = (int16_t)words[1];
    vm->flags = words[2];
    vm->breakpoint_count = words[3];
    for (i = 0; i < VM_MAX_BREAKPOINTS; i++)
        vm->breakpoints[i] = words[4 + i];
    vm->random_state = words[4 + VM_MAX_BREAKPOINTS];
    vm->node_id = words[5 + VM_MAX_BREAKPOINTS];
}

/* The host's memory runs, written into the areas as they arrive. */
static void read_runs(server *s)
{
    for (;;) {
        uint8_t which = take8(s);
        uint16_t start;
        uint16_t count;
        uint16_t i;
        if (s->bad || which == REMOTE_AREA_END)
            return;
        if (which >= AREA_COUNT) {
            s->bad = true;
            return;
        }
        start = take16(s);
        count = take16(s);
        if ((uint32_t)start + count > s->areas[which].size) {
            s->bad = true;
            return;
        }
        for (i = 0; i < count; i++)
            s->areas[which].words[start + i] = take16(s);
    }
}

/* The bytes the state block, every area as one run, and a node's error
 * counters take in an answer. */
static uint16_t machine_length(const server *s)
{
    uint16_t length = 2u * REMOTE_STATE_WORDS + 1u;
    uint16_t i;
    for (i = 0; i < AREA_COUNT; i++)
        if (s->areas[i].size > 0)
            length = (uint16_t)(length + 5u + 2u * s->areas[i].size);
    return s->is_node ? (uint16_t)(length + 10u) : length;
}

static void send_machine(server *s)
{
    const vm_state *vm = machine_vm(s);
    uint16_t i;
    uint16_t k;

    send16(vm->pc);
    send16((uint16_t)vm->sp);
    send16(vm->flags);
    send16(vm->breakpoint_count);
    for (i = 0; i < VM_MAX_BREAKPOINTS; i++)
        send16(vm->breakpoints[i]);
    send16(vm->random_state);
    send16(vm->node_id);
    for (i = 0; i < AREA_COUNT; i++) {
        const area *a = &s->areas[i];
        if (a->size == 0)
            continue;
        uart_send((uint8_t)i);
        send16(0);
        send16(a->size);
        for (k = 0; k < a->size; k++)
            send16(a->words[k]);
    }
    uart_send(REMOTE_AREA_END);
    if (s->is_node) {
        const node_error_counters *errors = &s->node.errors;
        send16(errors->oversize);
        send16(errors->truncated);
        send16(errors->malformed);
        send16(errors->wrong_destination);
        send16(errors->ignored);
    }
}

/* --- opening a machine ------------------------------------------------------------------- */

static uint8_t open_machine(server *s, uint8_t command)
{
    static const node_transport transport = { remote_on_send, &the_server };
    static const node_hooks hooks = {
        remote_on_write_bytecode, remote_on_reboot, remote_on_suspend, &the_server
    };
    uint16_t node_id = take16(s);
    uint8_t kind = take8(s);
    const vm_native_table *natives = NULL;
    const node_description *description = NULL;
    vm_memory memory;
    bool fits = prepare_memory(s, &memory);

    read_state(s, NULL);
    read_runs(s);
    if (command == REMOTE_OPEN_VM && kind == REMOTE_NATIVES_HARNESS)
        natives = &harness_natives;
    else if (command == REMOTE_OPEN_VM && kind == REMOTE_NATIVES_EPUCK)
        natives = &epuck_natives;
    else if (command == REMOTE_OPEN_NODE && kind == REMOTE_PRESET_TINY)
        description = &tiny_description;
    else if (command == REMOTE_OPEN_NODE && kind == REMOTE_PRESET_REFNODE)
        description = &refnode_description;
    if (!fits || s->bad || s->unread != 0 || (natives == NULL && description == NULL))
        return REMOTE_BAD_REQUEST;

    s->is_node = description != NULL;
    if (s->is_node)
        node_init(&s->node, node_id, description, &memory, &transport, &hooks);
    else
        vm_init(&s->vm, &memory, node_id, natives, &remote_vm_callbacks, s);
    send_header(REMOTE_OK, (uint16_t)(machine_length(s) + (s->is_node ? 2u : 0u)));
    if (s->is_node)
        send16(node_fingerprint(&s->node));
    send_machine(s);
    return REMOTE_OK;
}

/* --- calls ------------------------------------------------------------------------------ */

/* Reads the call's arguments (the call byte first); false for an unknown
 * call or one whose bulk does not fit. */
static bool read_call(server *s)
{
    uint16_t i;

    s->call = take8(s);
    switch (s->call) {
    case REMOTE_VM_STEP:
    case REMOTE_VM_RESET:
    case REMOTE_VM_COMMAND_RUN:
    case REMOTE_VM_COMMAND_PAUSE:
    case REMOTE_VM_COMMAND_STEP:
    case REMOTE_VM_COMMAND_STOP:
    case REMOTE_VM_REPORT_STATE:
    case REMOTE_VM_BREAKPOINT_CLEAR_ALL: return true;
    case REMOTE_VM_SETUP_EVENT:
    case REMOTE_VM_EVENT_ADDRESS:
    case REMOTE_VM_RUN:
    case REMOTE_VM_BREAKPOINT_SET:
    case REMOTE_VM_BREAKPOINT_CLEAR:
    case REMOTE_NODE_RAISE_LOCAL: s->first = take16(s); return true;
    case REMOTE_NODE_POLL: s->now = take32(s); return true;
    case REMOTE_NODE_RECEIVE_BYTE:
        s->now = take32(s);
        s->bulk.bytes[0] = take8(s);
        return true;
    case REMOTE_NODE_RECEIVE:
        s->now = take32(s);
        s->count = take16(s);
        if (s->count > sizeof s->bulk.bytes)
            return false;
        for (i = 0; i < s->count; i++)
            s->bulk.bytes[i] = take8(s);
        return true;
    case REMOTE_VM_RECEIVE_EVENT:
    case REMOTE_VM_SET_BYTECODE:
    case REMOTE_VM_CALL_NATIVE:
        s->first = take16(s);
        if (s->call == REMOTE_VM_RECEIVE_EVENT || s->call == REMOTE_VM_CALL_NATIVE)
            s->second = take16(s);
        s->count = take16(s);
        if (s->count > ARGUMENT_WORDS)
            return false;
        for (i = 0; i < s->count; i++)
            s->bulk.words[i] = take16(s);
        return true;
    default: return false;
    }
}

/* REMOTE_VM_CALL_NATIVE: native `first` of the table (or, just after the
 * e-puck's, the faulty FFT), at pc `second`, inside a running event, as
 * NATIVE_CALL calls it (bytecode.md §9). */
static uint16_t call_native(server *s)
{
    vm_state *vm = machine_vm(s);
    vm_native_function function;
    uint16_t count = vm_native_count(&vm->natives);
    if (s->first < count)
        function = vm_native_at(&vm->natives, s->first)->function;
    else if (vm->natives.modules == epuck_modules && s->first == count)
        function = nat_dsp_fft_truncating_mutant_module.natives[0].function;
    else
        return 0;
    vm->pc = s->second;
    vm->flags = VM_FLAG_EVENT_ACTIVE | VM_FLAG_EVENT_RUNNING;
    function(vm, (const int16_t *)s->bulk.words);
    return 1;
}

static uint16_t run_call(server *s)
{
    vm_state *vm = machine_vm(s);

    switch (s->call) {
    case REMOTE_VM_SETUP_EVENT: return vm_setup_event(vm, s->first);
    case REMOTE_VM_EVENT_ADDRESS: return vm_event_address(vm, s->first);
    case REMOTE_VM_RECEIVE_EVENT:
        vm_receive_event(vm, s->first, s->second, (const int16_t *)s->bulk.words, s->count);
        return 0;
    case REMOTE_VM_RUN: return vm_run(vm, s->first);
    case REMOTE_VM_STEP: return vm_step(vm);
    case REMOTE_VM_SET_BYTECODE: vm_set_bytecode(vm, s->first, s->bulk.words, s->count); return 0;
    case REMOTE_VM_RESET: vm_reset(vm); return 0;
    case REMOTE_VM_COMMAND_RUN: vm_command_run(vm); return 0;
    case REMOTE_VM_COMMAND_PAUSE: vm_command_pause(vm); return 0;
    case REMOTE_VM_COMMAND_STEP: vm_command_step(vm); return 0;
    case REMOTE_VM_COMMAND_STOP: vm_command_stop(vm); return 0;
    case REMOTE_VM_REPORT_STATE: vm_report_state(vm); return 0;
    case REMOTE_VM_BREAKPOINT_SET: return vm_breakpoint_set(vm, s->first);
    case REMOTE_VM_BREAKPOINT_CLEAR: vm_breakpoint_clear(vm, s->first); return 0;
    case REMOTE_VM_BREAKPOINT_CLEAR_ALL: vm_breakpoint_clear_all(vm); return 0;
    case REMOTE_VM_CALL_NATIVE: return call_native(s);
    case REMOTE_NODE_RECEIVE: return node_receive(&s->node, s->bulk.bytes, s->count, s->now);
    case REMOTE_NODE_RECEIVE_BYTE: return node_receive_byte(&s->node, s->bulk.bytes[0], s->now);
    case REMOTE_NODE_POLL: return node_poll(&s->node, s->now);
    default: /* REMOTE_NODE_RAISE_LOCAL */ return node_raise_local_event(&s->node, s->first);
    }
}

/* A call: its arguments, then the host's changes, then the call, then the
 * answer (any events beyond the buffer having gone ahead). */
static uint8_t call(server *s)
{
    uint16_t result;
    uint16_t i;
    bool known = read_call(s);
    bool node_call = s->call >= REMOTE_NODE_RECEIVE;

    read_state(s, machine_vm(s));
    read_runs(s);
    if (!known || s->bad || s->unread != 0 || (node_call && !s->is_node))
        return REMOTE_BAD_REQUEST;

    s->event_length = 0;
    result = run_call(s);
    if (!guards_hold(s))
        return REMOTE_GUARDS_BROKEN;

    send_header(REMOTE_OK, (uint16_t)(2u + s->event_length + 1u + machine_length(s)));
    send16(result);
    for (i = 0; i < s->event_length; i++)
        uart_send(s->events[i]);
    uart_send(REMOTE_EVENT_END);
    send_machine(s);
    return REMOTE_OK;
}

/* --- measuring --------------------------------------------------------------------------- */

static void counter_start(void)
{
    dspic30_write(DSPIC30_T2CON, 0);
    dspic30_write(DSPIC30_T3CON, 0);
    dspic30_write(DSPIC30_PR2, 0xFFFFu);
    dspic30_write(DSPIC30_PR3, 0xFFFFu);
    dspic30_write(DSPIC30_TMR3, 0);
    dspic30_write(DSPIC30_TMR2, 0);
    dspic30_write(DSPIC30_T2CON, DSPIC30_TCON_TON | DSPIC30_TCON_T32);
}

/* Instruction cycles since counter_start. */
static uint32_t counter_now(void)
{
    uint16_t low = dspic30_read(DSPIC30_TMR2);
    return (uint32_t)low | (uint32_t)dspic30_read(HARNESS_TMR3HLD) << 16;
}

static void answer32(uint32_t value)
{
    send16((uint16_t)value);
    send16((uint16_t)(value >> 16));
}

/* Runs the handler of an event of the loaded program once a step at a time
 * (its steps: the firmware's own count), then to its end `runs` times,
 * timed by the counter; then REPEAT'ed NOPs of a known count, so that the
 * host sees what the counter adds. */
static uint8_t bench(server *s)
{
    vm_state *vm = machine_vm(s);
    uint32_t steps = 0;
    uint32_t start;
    uint32_t vm_cycles;
    uint32_t loop_cycles;
    uint16_t event = take16(s);
    uint16_t runs = take16(s);
    uint16_t r;

    if (s->bad || s->unread != 0 || vm_setup_event(vm, event) == 0)
        return REMOTE_BAD_REQUEST;
    while (vm_is_event_active(vm) && vm_step(vm))
        steps++;
    counter_start();
    start = counter_now();
    for (r = 0; r < runs; r++) {
        if (vm_setup_event(vm, event) == 0)
            return REMOTE_BAD_REQUEST;
        vm_run(vm, 0);
    }
    vm_cycles = counter_now() - start;
    start = counter_now();
    __asm__ volatile("repeat #" CALIBRATION_REPEAT_TEXT "\n\tnop");
    loop_cycles = counter_now() - start;

    send_header(REMOTE_OK, 16);
    answer32(steps);
    answer32(vm_cycles);
    answer32(loop_cycles);
    answer32(CALIBRATION_REPEAT + 2ul); /* the REPEAT and its NOP's runs */
    return REMOTE_OK;
}

/* --- the loop ----------------------------------------------------------------------------- */

static void serve(server *s)
{
    uint8_t command;
    uint8_t status;

    if (uart_receive() != REMOTE_REQUEST_MAGIC)
        return; /* resynchronise on the next magic byte */
    command = uart_receive();
    s->unread = uart_receive();
    s->unread = (uint16_t)(s->unread | (uint16_t)uart_receive() << BYTE_BITS);
    s->bad = false;
    switch (command) {
    case REMOTE_OPEN_VM:
    case REMOTE_OPEN_NODE: status = open_machine(s, command); break;
    case REMOTE_CALL: status = call(s); break;
    case REMOTE_BENCH: status = bench(s); break;
    default: status = REMOTE_BAD_REQUEST; break;
    }
    if (status != REMOTE_OK) {
        drain(s);
        send_header(status, 0);
    }
}

int main(void)
{
    link_init();
    bind_areas(&the_server);
    send_header(REMOTE_OK, 0);
    for (;;)
        serve(&the_server);
    return 0;
}

/* The chip's vectors (IRQ numbers: Timer1 3, U1RX 9, U1TX 10), by the names
 * the whole-chip linker script gives them. */
void DSPIC30_INTERRUPT _Interrupt3(void)
{
    dspic30_on_clock_tick(&board);
}

void DSPIC30_INTERRUPT _Interrupt9(void)
{
    dspic30_on_uart1_receive(&board);
}

void DSPIC30_INTERRUPT _Interrupt10(void)
{
    dspic30_on_uart1_transmit(&board);
}
