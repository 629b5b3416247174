// Test support for the node: descriptions to run it with, a harness that
// feeds it bytes and collects the frames it sends, and a frame checker
// written from protocol.md §5 alone, as strict as upstream hosts (which abort
// on any payload that their layout does not consume exactly).

#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

extern "C" {
#include "node.h"
}

namespace node_test
{

using Bytes = std::vector<uint8_t>;

// A node's description with the memory sizes it runs with.
struct Preset {
    std::string name;
    const node_description *description;
    uint16_t bytecode_size;
    uint16_t stack_size;
    uint16_t variables_size;
};

// "tiny": 4 named variables, 2 local events, 2 test natives (test.sqrt,
// test.fill). "refnode": the dummy node layout of protocol.md §5.2 with the
// 30 standard natives.
const Preset &preset(const std::string &name);

// Empty when `frame` (header included) is a well-formed message from node
// `source`, else what is wrong with it.
std::string check_frame(const Bytes &frame, uint16_t source);

// Bytes of a frame: header then payload.
Bytes make_frame(uint16_t source, uint16_t type, const Bytes &payload);

// Little-endian payload of 16-bit words.
Bytes words(std::initializer_list<uint16_t> values);

std::string hex(const Bytes &bytes);

// A node with canaries around its struct and its memory, whose sent frames
// are reassembled from the transport's pieces and checked one by one.
class Harness
{
  public:
    Harness(const Preset &preset, uint16_t node_id);
    ~Harness();
    Harness(const Harness &) = delete;
    Harness &operator=(const Harness &) = delete;

    node_state &node();
    uint16_t id() const
    {
        return node_id_;
    }

    // Feeds bytes at the current time, all at once or one call per byte,
    // polling whenever the node takes no more; then polls until idle.
    void feed(const Bytes &bytes, bool byte_by_byte = false);
    // Polls until node_poll says there is nothing more to do, at most
    // `poll_limit` times (a program may loop forever).
    void poll_until_idle();

    uint32_t now = 0; // the clock given to the node, in ms
    unsigned poll_limit = 64;
    // Also show each sent frame to upstream's message library (after
    // check_frame accepted it).
    bool use_reference = true;

    std::deque<Bytes> frames;     // sent frames not yet looked at
    std::vector<std::string> bad; // what check_frame found wrong
    uint64_t frames_sent = 0;

    unsigned write_bytecode_calls = 0;
    unsigned reboot_calls = 0;
    unsigned suspend_calls = 0;

    // Whether every canary is intact.
    bool canaries_intact() const;

  private:
    static void send(void *context, const uint8_t *bytes, uint16_t count, bool frame_complete);
    static void on_write_bytecode(void *context, const uint16_t *bytecode, uint16_t size);
    static void on_reboot(void *context);
    static void on_suspend(void *context);

    struct Guarded; // the node between canaries
    Guarded *guarded_;
    std::vector<uint16_t> bytecode_;
    std::vector<int16_t> variables_;
    std::vector<int16_t> stack_;
    Bytes partial_; // pieces of the frame being sent
    uint16_t node_id_;
};

} // namespace node_test
