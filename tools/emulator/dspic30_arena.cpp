// The arena of dsPIC robots (see dspic30_arena.hpp).

#include "dspic30_arena.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

extern "C" {
#include "bootloader/bootloader.h"
#include "hal/hal.h"
#include "vm/node_protocol.h"
}

namespace aseba::arena
{
namespace
{

constexpr uint32_t milliseconds_per_step = uint32_t(EnkiWorld::step_seconds * 1000 + 0.5);
// A millisecond is 14745.6 cycles: each ends at the cycle below its end.
uint64_t cycle_at(uint64_t milliseconds)
{
    return milliseconds * HOST_CYCLES_PER_SECOND / 1000;
}
// The node ids the selector gives (the firmware's (selector & 7) + 1).
constexpr uint16_t selector_ids = 8;
// A program is sent once the firmware runs: after the bootloader's wait
// for a host, and the application's start-up.
constexpr uint64_t load_at_milliseconds = BOOT_WAIT_MS + 500;
// Words of bytecode per SET_BYTECODE, well within a frame's payload.
constexpr size_t bytecode_chunk_words = 128;

// A frame from the hosts' id (0): its length, source and type, then `words`.
void put_frame(std::vector<uint8_t> &bytes, uint16_t type, const std::vector<uint16_t> &words)
{
    const uint16_t header[] = { uint16_t(2 * words.size()), 0, type };
    for (uint16_t word : header)
        bytes.insert(bytes.end(), { uint8_t(word & 0xFF), uint8_t(word >> 8) });
    for (uint16_t word : words)
        bytes.insert(bytes.end(), { uint8_t(word & 0xFF), uint8_t(word >> 8) });
}

} // namespace

Dspic30Arena::Dspic30Arena(const Arena &arena,
                           uint32_t seed,
                           const std::map<uint32_t, uint32_t> &image)
  : world_(arena, seed)
{
    for (size_t i = 0; i < arena.robots.size(); i++) {
        world_.set_selector(i, uint16_t(i % selector_ids));
        auto member = std::make_unique<Member>(image, *world_.world_of(i));
        host_board_init(&member->link, nullptr, nullptr);
        network_.attach(&member->link);
        robots_.push_back(std::move(member));
    }
}

Dspic30Arena::~Dspic30Arena() = default;

void Dspic30Arena::load_at_start(std::vector<uint16_t> bytecode)
{
    program_ = std::move(bytecode);
}

// SET_BYTECODE in chunks then RUN, to each robot's node id, straight into
// its UART1.
void Dspic30Arena::load_program()
{
    for (size_t i = 0; i < robots_.size(); i++) {
        const uint16_t node = uint16_t(i % selector_ids + 1);
        std::vector<uint8_t> bytes;
        for (size_t at = 0; at < program_.size(); at += bytecode_chunk_words) {
            std::vector<uint16_t> words = { node, uint16_t(at) };
            const size_t end = std::min(program_.size(), at + bytecode_chunk_words);
            words.insert(words.end(), program_.begin() + long(at), program_.begin() + long(end));
            put_frame(bytes, NODE_MSG_SET_BYTECODE, words);
        }
        put_frame(bytes, NODE_MSG_RUN, { node });
        robots_[i]->chip.receive(bytes.data(), bytes.size());
    }
    program_.clear();
}

void Dspic30Arena::step()
{
    for (uint32_t tick = 0; tick < milliseconds_per_step; tick++) {
        milliseconds_++;
        if (!program_.empty() && milliseconds_ == load_at_milliseconds)
            load_program();
        for (size_t i = 0; i < robots_.size(); i++) {
            Member &member = *robots_[i];
            dspic30::Outcome outcome = member.chip.run_until(cycle_at(milliseconds_));
            if (outcome != dspic30::Outcome::cycle_limit)
                throw std::runtime_error("robot " + std::to_string(i + 1) +
                                         "'s chip stopped: " + dspic30::outcome_name(outcome));
            std::vector<uint8_t> sent = member.chip.take_output();
            for (size_t at = 0; at < sent.size();) {
                uint16_t count = uint16_t(std::min<size_t>(sent.size() - at, UINT16_MAX));
                if (member.link.link_output)
                    member.link.link_output(member.link.link_context, sent.data() + at, count);
                at += count;
            }
        }
        network_.service(0);
        for (auto &member : robots_) {
            uint8_t bytes[256];
            while (uint16_t count = hal_link_receive(&member->link, bytes, sizeof bytes))
                member->chip.receive(bytes, count);
        }
    }
    world_.step();
}

double Dspic30Arena::seconds() const
{
    return double(milliseconds_) / 1000;
}

} // namespace aseba::arena
