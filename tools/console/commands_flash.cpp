// flash: a firmware image into every selected robot at once, through their
// Aseba bootloaders, with a progress bar.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <unistd.h>

#include "console.hpp"
#include "tools/client/flasher.hpp"
#include "tools/flash/hex_image.hpp"

extern "C" {
#include "bootloader/boot_application.h"
}

namespace aseba::console
{
namespace
{

constexpr int PROGRESS_BAR_WIDTH = 30;
constexpr Milliseconds PROGRESS_REDRAW{ 100 };
constexpr Milliseconds NO_REBOOT_ENTER_TIMEOUT{ 10000 };

} // namespace

std::vector<client::FlashPage> read_flash_image(const std::string &path)
{
    flash::ProgramImage image;
    try {
        image = flash::read_microchip_hex_file(path, BOOT_APPLICATION_END);
        flash::check_application_image(image);
    } catch (const flash::HexError &error) {
        std::string message = error.what();
        if (message.rfind(path, 0) != 0)
            message = path + ": " + message;
        throw InputError(message + "; no robot was touched");
    }
    std::vector<client::FlashPage> pages;
    for (const flash::Page &page : flash::make_pages(image))
        pages.push_back(
          { page.number, std::vector<uint8_t>(page.bytes.begin(), page.bytes.end()) });
    return pages;
}

namespace
{

bool is_node_id(const std::string &selector)
{
    return !selector.empty() && selector.size() <= 5 &&
           selector.find_first_not_of("0123456789") == std::string::npos;
}

// The selected nodes, plus the ids asked for by number that did not answer
// as nodes: a robot whose application is invalid waits in its bootloader,
// which answers only bootloader messages.
std::vector<NodeKey> flash_targets(Session &session, std::vector<std::string> &silent)
{
    client::Network &network = session.network();
    std::vector<std::string> selectors = session.options().node_selectors;
    if (selectors.empty())
        selectors.push_back("all");
    std::vector<NodeKey> keys;
    for (const std::string &selector : selectors) {
        std::vector<NodeKey> found;
        try {
            found = network.select(selector);
        } catch (const client::NetworkError &) {
            if (!is_node_id(selector))
                throw;
            uint16_t id = uint16_t(std::stoul(selector));
            for (size_t target = 0; target < network.target_count(); target++)
                found.push_back({ target, id });
            silent.push_back(selector);
        }
        for (NodeKey key : found)
            if (std::find(keys.begin(), keys.end(), key) == keys.end())
                keys.push_back(key);
    }
    std::sort(keys.begin(), keys.end());
    return keys;
}

std::string node_label(Session &session, NodeKey key)
{
    for (NodeKey known : session.network().node_keys())
        if (known == key && session.network().node(key).described)
            return session.label(key);
    std::string text = "node " + std::to_string(key.id);
    if (session.network().target_count() > 1)
        text += " (" + session.network().target_name(key.target) + ")";
    return text;
}

// Redraws one line on a terminal: bar, percentage, robots, pages, time.
class ProgressBar
{
  public:
    explicit ProgressBar(bool terminal)
      : terminal_(terminal)
      , start_(client::Clock::now())
    {
    }

    void show(const client::FlashProgress &progress)
    {
        auto now = client::Clock::now();
        bool complete = progress.nodes_done == progress.nodes_total;
        if (!terminal_ || (!complete && now - last_drawn_ < PROGRESS_REDRAW))
            return;
        last_drawn_ = now;
        double fraction = progress.pages_total == 0
                            ? 1.0
                            : double(progress.pages_done) / double(progress.pages_total);
        int filled = int(fraction * PROGRESS_BAR_WIDTH + 0.5);
        std::string bar =
          std::string(size_t(filled), '#') + std::string(size_t(PROGRESS_BAR_WIDTH - filled), '-');
        std::fprintf(stderr,
                     "\r[%s] %3.0f%%  %zu/%zu robots done  %zu/%zu pages  %.1f s\033[K",
                     bar.c_str(),
                     fraction * 100,
                     progress.nodes_done,
                     progress.nodes_total,
                     progress.pages_done,
                     progress.pages_total,
                     seconds());
        if (complete)
            std::fputc('\n', stderr);
    }

    double seconds() const
    {
        return std::chrono::duration<double>(client::Clock::now() - start_).count();
    }

  private:
    bool terminal_;
    client::Clock::time_point start_;
    client::Clock::time_point last_drawn_{};
};

} // namespace

int command_flash(Session &session)
{
    const Options &options = session.options();
    std::vector<client::FlashPage> pages = read_flash_image(options.arguments[0]);
    std::vector<std::string> silent;
    std::vector<NodeKey> nodes = flash_targets(session, silent);
    for (const std::string &id : silent)
        std::cerr << "aseba: node " << id
                  << " did not answer as a node; flashing it in case it waits in its bootloader\n";

    client::FlashSettings settings;
    settings.reboot_first = !options.no_reboot;
    if (options.no_reboot) // a person switches the robots on meanwhile
        settings.enter_timeout = std::max(NO_REBOOT_ENTER_TIMEOUT, options.timeout);
    settings.page_timeout = std::max(settings.page_timeout, options.timeout);
    settings.cancelled = interrupted;
    std::cout << "flashing " << options.arguments[0] << " (" << pages.size() << " pages of "
              << pages.front().bytes.size() << " bytes) into " << nodes.size() << " robot"
              << (nodes.size() == 1 ? "" : "s") << std::endl;
    ProgressBar bar(isatty(STDERR_FILENO) != 0);
    std::vector<client::FlashOutcome> outcomes = client::flash_nodes(
      session.network(), nodes, pages, settings, [&](const auto &progress) { bar.show(progress); });

    size_t failed = 0;
    for (const client::FlashOutcome &outcome : outcomes) {
        std::cout << node_label(session, outcome.key) << ": ";
        if (outcome.problem.empty()) {
            std::cout << "flashed " << outcome.pages_written << " pages";
            if (outcome.pages_sent_again > 0)
                std::cout << " (" << outcome.pages_sent_again << " sent again)";
            std::cout << ", running the new image\n";
        } else {
            failed++;
            std::cout << "FAILED after " << outcome.pages_written << " pages: " << outcome.problem
                      << "\n";
        }
    }
    double seconds = bar.seconds();
    size_t written = 0;
    for (const client::FlashOutcome &outcome : outcomes)
        written += outcome.pages_written;
    std::printf("%zu of %zu robots flashed in %.1f s (%.0f pages/s)\n",
                outcomes.size() - failed,
                outcomes.size(),
                seconds,
                double(written) / std::max(seconds, 1e-3));
    return failed == 0 ? 0 : EXIT_FAILED;
}

} // namespace aseba::console
