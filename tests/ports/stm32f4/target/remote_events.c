/* The remote protocol's events, from the machine's callbacks (remote_events.h). */

#include "remote_events.h"

#include "tests/ports/stm32f4/remote_protocol.h"

#define BYTE_BITS 8u

static void event_byte(void *context, uint8_t value)
{
    remote_event_bytes(context, &value, 1);
}

static void event16(void *context, uint16_t value)
{
    uint8_t bytes[2];
    bytes[0] = (uint8_t)value;
    bytes[1] = (uint8_t)(value >> BYTE_BITS);
    remote_event_bytes(context, bytes, 2);
}

static void event_words(void *context, uint8_t kind, const uint16_t *words, uint16_t count)
{
    uint16_t i;
    event_byte(context, kind);
    for (i = 0; i < count; i++)
        event16(context, words[i]);
}

static void on_emit(void *context, uint16_t event, const int16_t *payload, uint16_t count)
{
    uint16_t i;
    event_byte(context, REMOTE_EVENT_EMIT);
    event16(context, event);
    event16(context, count);
    for (i = 0; i < count; i++)
        event16(context, (uint16_t)payload[i]);
}

/* Each report type carries its own count of words (vm.h). */
static void on_report(void *context, uint16_t type, const uint16_t *words, uint16_t count)
{
    (void)count;
    switch (type) {
    case VM_REPORT_EXECUTION_STATE_CHANGED:
        event_words(context, REMOTE_EVENT_STATE, words, 2);
        break;
    case VM_REPORT_EVENT_EXECUTION_KILLED:
        event_words(context, REMOTE_EVENT_KILLED, words, 1);
        break;
    case VM_REPORT_ARRAY_ACCESS_OUT_OF_BOUNDS:
        event_words(context, REMOTE_EVENT_ARRAY, words, 3);
        break;
    case VM_REPORT_DIVISION_BY_ZERO: event_words(context, REMOTE_EVENT_DIVISION, words, 1); break;
    default: break;
    }
}

static void on_node_error(void *context, uint16_t pc, const char *text)
{
    uint8_t length = 0;
    while (text[length] != '\0' && length < VM_NODE_ERROR_LENGTH)
        length++;
    event_byte(context, REMOTE_EVENT_NODE_ERROR);
    event16(context, pc);
    event_byte(context, length);
    remote_event_bytes(context, text, length);
}

const vm_callbacks remote_vm_callbacks = { on_emit, on_report, on_node_error };

void remote_on_send(void *context, const uint8_t *bytes, uint16_t count, bool frame_complete)
{
    event_byte(context, REMOTE_EVENT_SEND);
    event16(context, count);
    event_byte(context, frame_complete ? 1 : 0);
    remote_event_bytes(context, bytes, count);
}

static void on_hook(void *context, uint8_t which)
{
    event_byte(context, REMOTE_EVENT_HOOK);
    event_byte(context, which);
}

void remote_on_write_bytecode(void *context, const uint16_t *bytecode, uint16_t size)
{
    (void)bytecode;
    (void)size;
    on_hook(context, REMOTE_HOOK_WRITE_BYTECODE);
}

void remote_on_reboot(void *context)
{
    on_hook(context, REMOTE_HOOK_REBOOT);
}

void remote_on_suspend(void *context)
{
    on_hook(context, REMOTE_HOOK_SUSPEND);
}
