// The IDE's link to a simulated arena's feed (epuck-emu --arena-feed): the
// arena's geometry, then the robots' poses and LEDs, one JSON line each. It
// connects again after the emulator restarts, as the robots' links do.

#pragma once

#include <functional>
#include <memory>
#include <string>

#include <asio/io_context.hpp>
#include <nlohmann/json.hpp>

namespace aseba::ide
{

struct ArenaReports {
    std::function<void(nlohmann::json &&geometry)> arena; // the feed connected
    std::function<void(nlohmann::json &&state)> state;    // robots at a time
    std::function<void()> gone;                           // the feed went away
};

class ArenaLink
{
  public:
    // How long to wait before connecting again.
    static constexpr std::chrono::milliseconds RETRY_PERIOD{ 1000 };

    // Starts connecting to `host`:`port`; reports run on `io`'s thread.
    ArenaLink(asio::io_context &io, std::string host, uint16_t port, ArenaReports reports);
    ~ArenaLink();
    ArenaLink(const ArenaLink &) = delete;
    ArenaLink &operator=(const ArenaLink &) = delete;

  private:
    struct Implementation;
    std::shared_ptr<Implementation> implementation_;
};

} // namespace aseba::ide
