#include "node_harness.hpp"
#include "reference_decoder.hpp"
#include "tests/support/native_table.hpp"

#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>

extern "C" {
#include "nat_standard.h"
}

namespace node_test
{

// --- descriptions ------------------------------------------------------------

namespace
{

// test.sqrt(x): x = floor(sqrt(x)); a negative x is the error of
// bytecode.md §8.3, with upstream's text.
void test_sqrt(vm_state *vm, const int16_t *arguments)
{
    int16_t *x = vm_variables(vm, static_cast<uint16_t>(arguments[0]), 1);
    if (x == nullptr)
        return;
    if (*x < 0) {
        vm_error_node_specific(vm, "Negative input to sqrt");
        return;
    }
    int32_t root = 0;
    while ((root + 1) * (root + 1) <= *x)
        root++;
    *x = static_cast<int16_t>(root);
}

// test.fill(dest, value): dest[i] = value; dest is template -1.
void test_fill(vm_state *vm, const int16_t *arguments)
{
    uint16_t size = static_cast<uint16_t>(arguments[2]);
    int16_t *value = vm_variables(vm, static_cast<uint16_t>(arguments[1]), 1);
    if (value == nullptr)
        return;
    int16_t *dest = vm_variables(vm, static_cast<uint16_t>(arguments[0]), size);
    if (dest == nullptr)
        return;
    for (uint16_t i = 0; i < size; i++)
        dest[i] = *value;
}

// Packed descriptions (vm.h): stack words, name, 0x1F and the
// documentation, then each parameter's size + 0x10 and its name.
const vm_native test_sqrt_native = { test_sqrt,
                                     "\x01"
                                     "test.sqrt\x1F"
                                     "integer square root\x11"
                                     "x" };
const vm_native test_fill_native = { test_fill,
                                     "\x03"
                                     "test.fill\x1F"
                                     "fills dest with value\x0F"
                                     "dest\x11"
                                     "value" };
const vm_native tiny_native_list[] = { test_sqrt_native, test_fill_native };
const test_support::OneModuleTable tiny_natives(tiny_native_list, 2);

const node_named_variable tiny_variables[] = { { "id", 1 },
                                               { "source", 1 },
                                               { "args", 4 },
                                               { "leds", 3 } };
const node_local_event tiny_events[] = { { "timer", "periodic tick" }, { "button", "pressed" } };
const node_description tiny_description = {
    "tinynode", NODE_PROTOCOL_VERSION, tiny_variables, 4, tiny_events, 2, &tiny_natives.table()
};

const node_named_variable dummy_variables[] = { { "id", 1 },
                                                { "source", 1 },
                                                { "args", 32 },
                                                { "_productId", 1 },
                                                { "timer.period", 1 } };
const node_local_event dummy_events[] = { { "timer", "periodic timer" } };
const node_description refnode_description = {
    "refnode", NODE_PROTOCOL_VERSION, dummy_variables, 5, dummy_events, 1, &nat_standard_table
};

} // namespace

const Preset &preset(const std::string &name)
{
    static const std::map<std::string, Preset> presets = {
        { "tiny", { "tiny", &tiny_description, 64, 16, 40 } },
        { "refnode", { "refnode", &refnode_description, 512, 64, 1060 } },
    };
    auto found = presets.find(name);
    if (found == presets.end())
        throw std::runtime_error("unknown preset " + name);
    return found->second;
}

// --- frames ------------------------------------------------------------------

Bytes make_frame(uint16_t source, uint16_t type, const Bytes &payload)
{
    Bytes frame;
    frame.reserve(6 + payload.size());
    for (size_t field : { payload.size(), size_t(source), size_t(type) }) {
        frame.push_back(uint8_t(field));
        frame.push_back(uint8_t(field >> 8));
    }
    for (uint8_t byte : payload)
        frame.push_back(byte);
    return frame;
}

Bytes words(std::initializer_list<uint16_t> values)
{
    Bytes bytes;
    for (uint16_t value : values) {
        bytes.push_back(uint8_t(value));
        bytes.push_back(uint8_t(value >> 8));
    }
    return bytes;
}

std::string hex(const Bytes &bytes)
{
    std::string text;
    char digits[4];
    for (uint8_t byte : bytes) {
        std::snprintf(digits, sizeof digits, "%02x ", byte);
        text += digits;
    }
    if (!text.empty())
        text.pop_back();
    return text;
}

namespace
{

// Reads a payload as upstream hosts do: any overread or leftover is fatal.
struct Reader {
    const Bytes &bytes;
    size_t position = 6;
    std::string error;

    bool need(size_t count)
    {
        if (error.empty() && position + count > bytes.size())
            error = "attempt to overread";
        return error.empty();
    }
    uint16_t u16()
    {
        if (!need(2))
            return 0;
        uint16_t value = uint16_t(bytes[position] | bytes[position + 1] << 8);
        position += 2;
        return value;
    }
    void string()
    {
        if (!need(1))
            return;
        size_t length = bytes[position++];
        if (need(length))
            position += length;
    }
    void rest_of_words()
    {
        if (error.empty() && (bytes.size() - position) % 2 != 0)
            error = "odd number of bytes in a word array";
        position = bytes.size();
    }
};

} // namespace

std::string check_frame(const Bytes &frame, uint16_t source)
{
    if (frame.size() < 6)
        return "shorter than a header";
    size_t length = size_t(frame[0] | frame[1] << 8);
    uint16_t frame_source = uint16_t(frame[2] | frame[3] << 8);
    uint16_t type = uint16_t(frame[4] | frame[5] << 8);
    if (length != frame.size() - 6)
        return "length field " + std::to_string(length) + " for " +
               std::to_string(frame.size() - 6) + " payload bytes";
    if (length > 516)
        return "payload above 516 bytes";
    if (frame_source != source)
        return "source " + std::to_string(frame_source);

    Reader reader{ frame, 6, "" };
    switch (type) {
    case 0x9000: // DESCRIPTION
        reader.string();
        if (reader.u16() != 5 && reader.error.empty())
            reader.error = "protocol version is not 5";
        for (int i = 0; i < 6; i++)
            reader.u16();
        break;
    case 0x9001: reader.u16(), reader.string(); break;
    case 0x9002: reader.string(), reader.string(); break;
    case 0x9003: {
        reader.string();
        reader.string();
        uint16_t count = reader.u16();
        for (uint16_t i = 0; i < count && reader.error.empty(); i++) {
            reader.u16();
            reader.string();
        }
        break;
    }
    case 0x9005: reader.u16(), reader.rest_of_words(); break;
    case 0x9006: reader.u16(), reader.u16(), reader.u16(); break;
    case 0x9007:
    case 0x9008: reader.u16(); break;
    case 0x9009: reader.u16(), reader.string(); break;
    case 0x900A: reader.u16(), reader.u16(); break;
    case 0x900B:
        reader.u16();
        if (reader.u16() > 1 && reader.error.empty())
            reader.error = "breakpoint result neither 0 nor 1";
        break;
    case 0x900C:
        if (reader.u16() != 5 && reader.error.empty())
            reader.error = "NODE_PRESENT version is not 5";
        break;
    default:
        if (type >= 0x8000)
            return "a node does not send type " + std::to_string(type);
        reader.rest_of_words(); // user event: int16 words
    }
    if (!reader.error.empty())
        return reader.error;
    if (reader.position != frame.size())
        return "message not fully deserialized";
    return "";
}

// --- harness -----------------------------------------------------------------

namespace
{
constexpr size_t canary_words = 16;
constexpr uint16_t canary_value = 0xC0DE;
} // namespace

struct Harness::Guarded {
    uint16_t before[canary_words];
    node_state node;
    uint16_t after[canary_words];
};

Harness::Harness(const Preset &preset, uint16_t node_id)
  : guarded_(new Guarded)
  , bytecode_(preset.bytecode_size + 2 * canary_words, canary_value)
  , variables_(preset.variables_size + 2 * canary_words, int16_t(canary_value))
  , stack_(preset.stack_size + 2 * canary_words, int16_t(canary_value))
  , node_id_(node_id)
{
    std::memset(guarded_, 0x5A, sizeof *guarded_);
    for (size_t i = 0; i < canary_words; i++)
        guarded_->before[i] = guarded_->after[i] = canary_value;
    vm_memory memory = {};
    memory.bytecode = bytecode_.data() + canary_words;
    memory.bytecode_size = preset.bytecode_size;
    memory.variables = variables_.data() + canary_words;
    memory.variables_size = preset.variables_size;
    memory.stack = stack_.data() + canary_words;
    memory.stack_size = preset.stack_size;
    node_transport transport = { send, this };
    node_hooks hooks = { on_write_bytecode, on_reboot, on_suspend, this };
    node_init(&guarded_->node, node_id, preset.description, &memory, &transport, &hooks);
}

Harness::~Harness()
{
    delete guarded_;
}

node_state &Harness::node()
{
    return guarded_->node;
}

bool Harness::canaries_intact() const
{
    for (size_t i = 0; i < canary_words; i++) {
        if (guarded_->before[i] != canary_value || guarded_->after[i] != canary_value)
            return false;
        size_t last = bytecode_.size() - 1 - i;
        if (bytecode_[i] != canary_value || bytecode_[last] != canary_value)
            return false;
        if (uint16_t(variables_[i]) != canary_value ||
            uint16_t(variables_[variables_.size() - 1 - i]) != canary_value)
            return false;
        if (uint16_t(stack_[i]) != canary_value ||
            uint16_t(stack_[stack_.size() - 1 - i]) != canary_value)
            return false;
    }
    return true;
}

void Harness::send(void *context, const uint8_t *bytes, uint16_t count, bool frame_complete)
{
    auto *self = static_cast<Harness *>(context);
    if (count > NODE_TRANSMIT_CHUNK)
        self->bad.emplace_back("a piece larger than the transmit chunk");
    self->partial_.insert(self->partial_.end(), bytes, bytes + count);
    if (!frame_complete)
        return;
    std::string problem = check_frame(self->partial_, self->node_id_);
    if (problem.empty() && self->use_reference)
        problem = reference_check(self->partial_);
    if (!problem.empty())
        self->bad.push_back(problem + ": " + hex(self->partial_));
    self->frames.push_back(self->partial_);
    self->frames_sent++;
    self->partial_.clear();
}

void Harness::on_write_bytecode(void *context, const uint16_t *, uint16_t)
{
    static_cast<Harness *>(context)->write_bytecode_calls++;
}

void Harness::on_reboot(void *context)
{
    static_cast<Harness *>(context)->reboot_calls++;
}

void Harness::on_suspend(void *context)
{
    static_cast<Harness *>(context)->suspend_calls++;
}

void Harness::poll_until_idle()
{
    for (unsigned i = 0; i < poll_limit; i++) {
        if (!node_poll(&node(), now))
            break;
    }
}

void Harness::feed(const Bytes &bytes, bool byte_by_byte)
{
    size_t position = 0;
    while (position < bytes.size()) {
        size_t left = bytes.size() - position;
        uint16_t count = byte_by_byte ? 1 : uint16_t(left < 0xFFFF ? left : 0xFFFF);
        uint16_t taken = node_receive(&node(), bytes.data() + position, count, now);
        position += taken;
        if (taken < count)
            node_poll(&node(), now); // a frame waits: let the node handle it
    }
    poll_until_idle();
}

} // namespace node_test
