// The arena of dsPIC robots (see dspic30_arena.hpp).

#include "dspic30_arena.hpp"

#include <stdexcept>
#include <string>

extern "C" {
#include "hal/hal.h"
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

void Dspic30Arena::step()
{
    for (uint32_t tick = 0; tick < milliseconds_per_step; tick++) {
        milliseconds_++;
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
