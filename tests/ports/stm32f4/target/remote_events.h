/* What a harness image's machine reports (the VM's events and reports, the
 * node's sent bytes and hooks), written as the remote protocol's events
 * (remote_protocol.h). Both harness images use it, the STM32F4's and the
 * dsPIC30F's (tests/ports/dspic30/target); each keeps its events its own
 * way, through remote_event_bytes. */

#ifndef REMOTE_EVENTS_H
#define REMOTE_EVENTS_H

#include <stdbool.h>
#include <stdint.h>

#include "node.h"

/* Provided by the harness image: keeps `count` bytes of an event for the
 * answer of the call under way; `context` is the one given to the VM and
 * the node. */
void remote_event_bytes(void *context, const void *bytes, uint16_t count);

/* The VM's callbacks, each report written as its remote event. */
extern const vm_callbacks remote_vm_callbacks;

/* The node's transport: each send written as a REMOTE_EVENT_SEND. */
void remote_on_send(void *context, const uint8_t *bytes, uint16_t count, bool frame_complete);

/* The node's hooks, each written as a REMOTE_EVENT_HOOK. */
void remote_on_write_bytecode(void *context, const uint16_t *bytecode, uint16_t size);
void remote_on_reboot(void *context);
void remote_on_suspend(void *context);

#endif
