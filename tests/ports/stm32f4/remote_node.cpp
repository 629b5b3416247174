// node.h for the host tests, run by the harness image in QEMU: each call is
// one call to the firmware's node on the emulated Cortex-M4, with the
// description of one of tests/node/node_harness.cpp's presets, its frames
// to the caller's transport, its hooks to the caller's hooks, its memory
// and error counters brought back into the caller's node_state. Linked
// instead of the node library (its description and frame code, which only
// compute and encode, stay linked for fingerprints), it runs the node's
// trace tests unchanged on the microcontroller's instruction set.

#include <cstring>

#include "tests/ports/stm32f4/remote_link.hpp"

extern "C" {
#include "node.h"
}

using qemu_test::Bytes;
using qemu_test::fail;
using qemu_test::Reader;
using qemu_test::RemoteMachine;
using qemu_test::Writer;

namespace
{

node_state *the_node = nullptr;

void dispatch_node_events(node_state *node, Reader &reader)
{
    for (uint8_t kind; (kind = reader.u8()) != REMOTE_EVENT_END;) {
        if (kind == REMOTE_EVENT_SEND) {
            Bytes piece(reader.u16());
            bool complete = reader.u8() != 0;
            for (uint8_t &byte : piece)
                byte = reader.u8();
            node->transport.send(
              node->transport.context, piece.data(), uint16_t(piece.size()), complete);
        } else if (kind == REMOTE_EVENT_HOOK) {
            uint8_t which = reader.u8();
            const node_hooks &hooks = node->hooks;
            if (which == REMOTE_HOOK_WRITE_BYTECODE && hooks.write_bytecode)
                hooks.write_bytecode(
                  hooks.context, node->vm.memory.bytecode, node->vm.memory.bytecode_size);
            else if (which == REMOTE_HOOK_REBOOT && hooks.reboot)
                hooks.reboot(hooks.context);
            else if (which == REMOTE_HOOK_SUSPEND && hooks.suspend_to_ram)
                hooks.suspend_to_ram(hooks.context);
        } else {
            fail("a node sent a bare VM's event");
        }
    }
}

void take_errors(node_state *node, Reader &reader)
{
    node_error_counters &errors = node->errors;
    errors.oversize = reader.u16();
    errors.truncated = reader.u16();
    errors.malformed = reader.u16();
    errors.wrong_destination = reader.u16();
    errors.ignored = reader.u16();
}

uint16_t call(node_state *node, const Writer &arguments)
{
    if (node != the_node)
        fail("a call on a node the image does not run");
    uint16_t result;
    Bytes answer = RemoteMachine::instance().call(arguments, &result);
    Reader reader{ answer, 2 };
    dispatch_node_events(node, reader);
    RemoteMachine::instance().take_changes(reader);
    take_errors(node, reader);
    return result;
}

Writer call_at(uint8_t which, uint32_t now_ms)
{
    Writer writer;
    writer.u8(which);
    writer.u32(now_ms);
    return writer;
}

} // namespace

extern "C" {

void node_init(node_state *node,
               uint16_t node_id,
               const node_description *description,
               const vm_memory *memory,
               const node_transport *transport,
               const node_hooks *hooks)
{
    uint8_t preset;
    if (std::strcmp(description->name, "tinynode") == 0)
        preset = REMOTE_PRESET_TINY;
    else if (std::strcmp(description->name, "refnode") == 0)
        preset = REMOTE_PRESET_REFNODE;
    else
        fail(std::string("the image has no preset ") + description->name);
    std::memset(node, 0, sizeof *node);
    node->description = description;
    node->transport = *transport;
    if (hooks)
        node->hooks = *hooks;
    node->vm.memory = *memory;
    the_node = node;

    Bytes answer = RemoteMachine::instance().open(REMOTE_OPEN_NODE, preset, &node->vm, node_id);
    Reader reader{ answer };
    uint16_t fingerprint = reader.u16();
    RemoteMachine::instance().take_changes(reader);
    take_errors(node, reader);
    uint16_t expected = node_description_fingerprint(
      description, memory->bytecode_size, memory->stack_size, memory->variables_size);
    if (fingerprint != expected)
        fail(std::string("the image's ") + description->name +
             " is not the host's (description fingerprints differ)");
}

uint16_t node_receive(node_state *node, const uint8_t *bytes, uint16_t count, uint32_t now_ms)
{
    Writer writer = call_at(REMOTE_NODE_RECEIVE, now_ms);
    writer.u16(count);
    writer.bytes.insert(writer.bytes.end(), bytes, bytes + count);
    return call(node, writer);
}

bool node_receive_byte(node_state *node, uint8_t byte, uint32_t now_ms)
{
    Writer writer = call_at(REMOTE_NODE_RECEIVE_BYTE, now_ms);
    writer.u8(byte);
    return call(node, writer) != 0;
}

bool node_poll(node_state *node, uint32_t now_ms)
{
    return call(node, call_at(REMOTE_NODE_POLL, now_ms)) != 0;
}

bool node_raise_local_event(node_state *node, uint16_t index)
{
    Writer writer;
    writer.u8(REMOTE_NODE_RAISE_LOCAL);
    writer.u16(index);
    return call(node, writer) != 0;
}

} // extern "C"
