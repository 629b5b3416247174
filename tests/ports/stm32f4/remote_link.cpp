#include "tests/ports/stm32f4/remote_link.hpp"

#include <stdexcept>

namespace qemu_test
{

namespace
{

constexpr size_t area_count = 3;

uint16_t *area_words(vm_state *vm, size_t area)
{
    switch (area) {
    case REMOTE_AREA_BYTECODE: return vm->memory.bytecode;
    case REMOTE_AREA_VARIABLES: return reinterpret_cast<uint16_t *>(vm->memory.variables);
    default: return reinterpret_cast<uint16_t *>(vm->memory.stack);
    }
}

uint16_t area_size(const vm_state *vm, size_t area)
{
    switch (area) {
    case REMOTE_AREA_BYTECODE: return vm->memory.bytecode_size;
    case REMOTE_AREA_VARIABLES: return vm->memory.variables_size;
    default: return vm->memory.stack_size;
    }
}

} // namespace

void fail(const std::string &message)
{
    throw std::runtime_error("harness image: " + message);
}

uint8_t Reader::u8()
{
    if (at >= bytes.size())
        fail("an answer ended too early");
    return bytes[at++];
}

uint16_t Reader::u16()
{
    uint16_t low = u8();
    return uint16_t(low | u8() << 8);
}

RemoteMachine &RemoteMachine::instance()
{
    static RemoteMachine machine;
    return machine;
}

Bytes RemoteMachine::exchange(uint8_t command, const Bytes &payload)
{
    if (!link_)
        link_ = open_harness_link(count_instructions);
    if (payload.size() > REMOTE_MAX_PAYLOAD)
        fail("a request of " + std::to_string(payload.size()) + " bytes is too large");
    uint8_t header[REMOTE_HEADER_BYTES] = {
        REMOTE_REQUEST_MAGIC, command, uint8_t(payload.size()), uint8_t(payload.size() >> 8)
    };
    link_->send(header, sizeof header);
    link_->send(payload.data(), payload.size());
    // Events sent ahead (REMOTE_ANSWER_CONTINUES) go after the answer's result.
    Bytes ahead;
    for (;;) {
        link_->receive(header, sizeof header);
        if (header[0] != REMOTE_ANSWER_MAGIC)
            fail("an answer without its magic byte");
        Bytes answer(size_t(header[2] | header[3] << 8));
        link_->receive(answer.data(), answer.size());
        switch (header[1]) {
        case REMOTE_ANSWER_CONTINUES:
            ahead.insert(ahead.end(), answer.begin(), answer.end());
            break;
        case REMOTE_OK:
            if (!ahead.empty()) {
                if (command != REMOTE_CALL || answer.size() < 2)
                    fail("events sent ahead of an answer that is no call's");
                answer.insert(answer.begin() + 2, ahead.begin(), ahead.end());
            }
            return answer;
        case REMOTE_EVENTS_OVERFLOW: fail("a call caused more events than the image can report");
        case REMOTE_GUARDS_BROKEN: fail("the VM wrote outside its memory on the target");
        default: fail("the image refused a request (command " + std::to_string(command) + ")");
        }
    }
}

void RemoteMachine::write_changes(Writer &writer)
{
    writer.u16(vm_->pc);
    writer.u16(uint16_t(vm_->sp));
    writer.u16(vm_->flags);
    writer.u16(vm_->breakpoint_count);
    for (uint16_t breakpoint : vm_->breakpoints)
        writer.u16(breakpoint);
    writer.u16(vm_->random_state);
    writer.u16(vm_->node_id);
    for (size_t area = 0; area < area_count; area++) {
        const uint16_t *words = area_words(vm_, area);
        std::vector<uint16_t> &seen = seen_[area];
        size_t k = 0;
        while (k < seen.size()) {
            if (words[k] == seen[k]) {
                k++;
                continue;
            }
            size_t start = k;
            while (k < seen.size() && words[k] != seen[k])
                seen[k] = words[k], k++;
            writer.u8(uint8_t(area));
            writer.u16(uint16_t(start));
            writer.u16(uint16_t(k - start));
            for (size_t i = start; i < k; i++)
                writer.u16(words[i]);
        }
    }
    writer.u8(REMOTE_AREA_END);
}

void RemoteMachine::take_changes(Reader &reader)
{
    vm_->pc = reader.u16();
    vm_->sp = int16_t(reader.u16());
    vm_->flags = reader.u16();
    vm_->breakpoint_count = reader.u16();
    for (uint16_t &breakpoint : vm_->breakpoints)
        breakpoint = reader.u16();
    vm_->random_state = reader.u16();
    vm_->node_id = reader.u16();
    for (uint8_t area; (area = reader.u8()) != REMOTE_AREA_END;) {
        if (area >= area_count)
            fail("a memory run of an unknown area");
        uint16_t start = reader.u16();
        uint16_t count = reader.u16();
        if (size_t(start) + count > seen_[area].size())
            fail("a memory run outside the VM's memory");
        uint16_t *words = area_words(vm_, area);
        for (uint16_t i = 0; i < count; i++)
            seen_[area][start + i] = words[start + i] = reader.u16();
    }
}

Bytes RemoteMachine::open(uint8_t command,
                          uint8_t natives_or_preset,
                          vm_state *vm,
                          uint16_t node_id)
{
    vm_ = vm;
    Writer writer;
    writer.u16(node_id);
    writer.u8(natives_or_preset);
    writer.u16(vm->memory.bytecode_size);
    writer.u16(vm->memory.variables_size);
    writer.u16(vm->memory.stack_size);
    writer.u16(vm->memory.args_size);
    // The host's memory as it is: the machine starts from the same words.
    for (size_t area = 0; area < area_count; area++)
        seen_[area].assign(area_size(vm_, area), 0);
    write_changes(writer);
    return exchange(command, writer.bytes);
}

Bytes RemoteMachine::call(const Writer &arguments, uint16_t *result)
{
    if (vm_ == nullptr)
        fail("a call before the machine was opened");
    Writer writer = arguments;
    write_changes(writer);
    Bytes answer = exchange(REMOTE_CALL, writer.bytes);
    Reader reader{ answer };
    *result = reader.u16();
    return answer;
}

Bytes RemoteMachine::bench(uint16_t event, uint16_t runs)
{
    Writer writer;
    writer.u16(event);
    writer.u16(runs);
    return exchange(REMOTE_BENCH, writer.bytes);
}

} // namespace qemu_test
