// libFuzzer target for the console client's side of the wire (tools/client):
// arbitrary bytes, cut into arbitrary chunks, go through the frame assembler;
// every frame it yields is decoded, rendered as the monitor prints it and,
// when it decodes, encoded again. It stops on any sanitizer report, on an
// exception other than ProtocolError, or when a decoded frame does not encode
// back to the same type and payload (decoding is strict, so it must).
//
// Input: records of one control byte (bits 0-5: how many stream bytes
// follow) and the bytes, so that frames are split at every possible place.
//
// Built and run by `make fuzz` (scripts/fuzz.sh).

#include <cstddef>
#include <cstdint>
#include <cstdio>

#include "tools/client/message_text.hpp"
#include "tools/client/messages.hpp"
#include "tools/client/wire.hpp"

using namespace aseba::client;

namespace
{

constexpr uint8_t chunk_length_mask = 0x3F;

[[noreturn]] void fail(const char *why, const Frame &frame)
{
    std::fprintf(stderr,
                 "client_fuzzer: %s (type 0x%04X, %zu payload bytes)\n",
                 why,
                 frame.type,
                 frame.payload.size());
    __builtin_trap();
}

void check_frame(const Frame &frame)
{
    Message message;
    try {
        message = decode(frame);
    } catch (const ProtocolError &) {
        return; // rejected, as upstream hosts reject it
    }
    message_text(message, nullptr, nullptr);
    Frame again = encode(message, frame.source);
    if (again.type != frame.type || again.payload != frame.payload)
        fail("a decoded frame encodes differently", frame);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FrameAssembler assembler;
    size_t position = 0;
    while (position < size) {
        size_t count = data[position++] & chunk_length_mask;
        if (count > size - position)
            count = size - position;
        try {
            assembler.feed(data + position, count);
            while (auto frame = assembler.next())
                check_frame(*frame);
        } catch (const ProtocolError &) {
            return 0; // the stream is broken for good
        }
        position += count;
    }
    return 0;
}
