// What the arena looks like, for viewers (aseba-ide's arena view): its
// geometry once, then the robots' poses and LEDs a few times a second, as
// JSON lines on a TCP port (docs/ide-protocol.md, "arena"). The Aseba
// network cannot carry it: robots do not know where they are.

#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "arena_file.hpp"
#include "enki_world.hpp"
#include "tools/connections/port_limit.hpp"

namespace aseba::arena
{

// One robot as a viewer sees it.
struct FeedRobot {
    uint16_t node_id = 0;
    Pose pose;
    std::array<bool, 8> ring{}; // ring LEDs, 0 at the front, clockwise
    bool body = false;          // the green body LED
    bool front = false;         // the red front LED
};

class ArenaFeed
{
  public:
    // How often viewers get the robots, in wall-clock seconds.
    static constexpr double PERIOD_SECONDS = 1.0 / 15;
    // Viewers at once (tools/connections/port_limit.hpp). Viewers never
    // speak: when the feed is full, the oldest gives its place once it has
    // watched for the grace.
    static constexpr size_t MOST_VIEWERS = 8;

    // Listens on `address`:`port` (0: any free port); throws
    // std::runtime_error with the system's reason.
    ArenaFeed(const Arena &arena,
              const std::string &address,
              uint16_t port,
              const connections::PortLimit &limit = { MOST_VIEWERS, connections::IDLE_GRACE });
    ~ArenaFeed();
    ArenaFeed(const ArenaFeed &) = delete;
    ArenaFeed &operator=(const ArenaFeed &) = delete;

    uint16_t port() const;

    // Sends the robots at `simulated_seconds` to every viewer; a viewer that
    // does not read misses updates, never the geometry.
    void publish(double simulated_seconds, const std::vector<FeedRobot> &robots);

    // Accepts viewers and moves bytes, without waiting.
    void service();

    // Viewers connected now.
    size_t viewer_count() const;

  private:
    struct Implementation;
    std::unique_ptr<Implementation> implementation_;
};

// The geometry line a viewer receives first: {"type":"arena","arena":{...}}.
std::string arena_geometry_json(const Arena &arena);

} // namespace aseba::arena
