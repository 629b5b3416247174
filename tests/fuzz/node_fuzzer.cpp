// libFuzzer target for the node: the frame assembler and the handling of
// every message, fed arbitrary bytes with arbitrary timing. It stops on any
// sanitizer report, on a frame the node sends that an upstream host would
// reject (tests/node's strict decoder), on a broken canary, or when the node
// no longer answers LIST_NODES after a quiet line.
//
// Input: byte 0 chooses the node (bit 0: refnode with the standard natives,
// else the tiny test node) and the feeding (bit 1: one byte per call). Then
// records: one control byte (bits 0-5: how many data bytes follow, bits 6-7:
// the pause before them: 0, 1, 250 or 600 ms), then the data bytes.
//
// Every frame the node sends is also read by Debian's libasebacommon (see
// tests/node/reference_decoder.hpp), as upstream hosts would.
//
// Built and run by `make fuzz` (scripts/fuzz.sh).

#include "../node/node_harness.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>

using namespace node_test;

namespace
{

constexpr uint8_t length_mask = 0x3F;
constexpr unsigned pause_shift = 6;
constexpr uint32_t pauses_ms[] = { 0, 1, 250, 600 };

[[noreturn]] void fail(const std::string &why)
{
    std::fprintf(stderr, "node_fuzzer: %s\n", why.c_str());
    __builtin_trap();
}

void check(Harness &harness)
{
    if (!harness.bad.empty())
        fail("malformed frame: " + harness.bad.front());
    if (!harness.canaries_intact())
        fail("a canary was overwritten");
    harness.frames.clear();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0)
        return 0;
    Harness harness(preset(data[0] & 1 ? "refnode" : "tiny"), 1);
    bool byte_by_byte = (data[0] & 2) != 0;
    harness.poll_limit = 2; // fuzzed programs may loop forever

    size_t position = 1;
    while (position < size) {
        uint8_t control = data[position++];
        size_t count = control & length_mask;
        if (count > size - position)
            count = size - position;
        harness.now += pauses_ms[control >> pause_shift];
        harness.feed(Bytes(data + position, data + position + count), byte_by_byte);
        position += count;
        check(harness);
    }

    // Whatever came before, a quiet line and LIST_NODES get NODE_PRESENT.
    harness.now += NODE_INTER_BYTE_TIMEOUT_MS + 1;
    harness.feed(make_frame(0, 0xA011, words({ 5 })));
    bool present = false;
    for (const Bytes &frame : harness.frames)
        present = present || frame == make_frame(1, 0x900C, words({ 5 }));
    if (!present)
        fail("no NODE_PRESENT after a quiet line");
    check(harness);
    return 0;
}
