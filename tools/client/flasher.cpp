// Flashing a group of nodes through their bootloaders (see flasher.hpp): one
// small state machine per node, all driven by the network's frames and by
// their deadlines.

#include "flasher.hpp"

#include <algorithm>
#include <sstream>

namespace aseba::client
{
namespace
{

constexpr uint16_t BOOTLOADER_ERROR_INVALID_FRAME_SIZE = 1;
constexpr uint16_t BOOTLOADER_ERROR_NOT_PROGRAMMING = 3;
constexpr Milliseconds LIST_NODES_RETRY{ 250 }; // while waiting for a node to come back
constexpr Milliseconds LONGEST_WAIT{ 50 };      // between two looks at the deadlines
const char *const refused_image =
  "every page was written but its bootloader did not accept the "
  "image as a valid application (descriptor or CRC) and stays active";

enum class Stage {
    entering,           // REBOOT sent, waiting for BOOTLOADER_DESCRIPTION
    awaiting_write_ack, // WRITE_PAGE sent
    awaiting_page_ack,  // the page's chunks sent
    resetting,          // BOOTLOADER_RESET sent
    restarting,         // acknowledged; waiting for the node to answer LIST_NODES
    finished
};

struct Job {
    FlashOutcome outcome;
    Stage stage = Stage::entering;
    size_t page_index = 0;
    unsigned attempts = 0; // sends of the current page
    Clock::time_point deadline;
    Clock::time_point next_list_nodes;
};

std::string hex_address(uint16_t value)
{
    std::ostringstream text;
    text << "0x" << std::hex << std::uppercase << value;
    return text.str();
}

std::string ack_problem(const BootloaderAck &ack, uint16_t page)
{
    std::string where = "page " + std::to_string(page) + ": ";
    switch (ack.error_code) {
    case BOOTLOADER_ERROR_INVALID_FRAME_SIZE:
        return where + "the bootloader received a chunk of the wrong size";
    case BOOTLOADER_ERROR_PROGRAMMING_FAILED:
        return where + "the bootloader refused or could not program it" +
               (ack.error_address ? " (flash address " + hex_address(*ack.error_address) + ")"
                                  : std::string());
    case BOOTLOADER_ERROR_NOT_PROGRAMMING:
        return where + "the bootloader was not expecting page data";
    default:
        return where + "the bootloader answered with error code " + std::to_string(ack.error_code);
    }
}

class GroupFlash
{
  public:
    GroupFlash(Network &network,
               const std::vector<NodeKey> &nodes,
               const std::vector<FlashPage> &pages,
               const FlashSettings &settings,
               const std::function<void(const FlashProgress &)> &on_progress)
      : network_(network)
      , pages_(pages)
      , settings_(settings)
      , on_progress_(on_progress)
    {
        progress_.nodes_total = nodes.size();
        progress_.pages_total = nodes.size() * pages.size();
        for (NodeKey key : nodes) {
            Job job;
            job.outcome.key = key;
            jobs_.push_back(job);
        }
    }

    std::vector<FlashOutcome> run()
    {
        network_.set_listener([this](const ReceivedFrame &frame) { receive(frame); });
        const auto start = Clock::now();
        for (Job &job : jobs_) {
            job.deadline = start + settings_.enter_timeout;
            if (settings_.reboot_first)
                network_.send(job.outcome.key.target,
                              NodeCommand{ NODE_MSG_REBOOT, job.outcome.key.id });
        }
        while (progress_.nodes_done < jobs_.size()) {
            if (settings_.cancelled && settings_.cancelled()) {
                for (Job &job : jobs_)
                    if (job.stage != Stage::finished)
                        finish(job, "interrupted: its bootloader waits for a new flashing");
                break;
            }
            network_.poll(std::min(LONGEST_WAIT, time_to_next_deadline()));
            check_deadlines();
        }
        network_.set_listener(nullptr);
        std::vector<FlashOutcome> outcomes;
        for (const Job &job : jobs_)
            outcomes.push_back(job.outcome);
        return outcomes;
    }

  private:
    Network &network_;
    const std::vector<FlashPage> &pages_;
    const FlashSettings &settings_;
    const std::function<void(const FlashProgress &)> &on_progress_;
    std::vector<Job> jobs_;
    FlashProgress progress_;

    void report()
    {
        if (on_progress_)
            on_progress_(progress_);
    }

    void finish(Job &job, const std::string &problem = {})
    {
        job.stage = Stage::finished;
        job.outcome.problem = problem;
        progress_.nodes_done++;
        report();
    }

    void send_page(Job &job)
    {
        const FlashPage &page = pages_[job.page_index];
        job.attempts++;
        job.stage = Stage::awaiting_write_ack;
        job.deadline = Clock::now() + settings_.page_timeout;
        network_.send(
          job.outcome.key.target,
          BootloaderPageCommand{ MSG_BOOTLOADER_WRITE_PAGE, job.outcome.key.id, page.number });
    }

    void send_chunks(Job &job)
    {
        const FlashPage &page = pages_[job.page_index];
        for (size_t offset = 0; offset < page.bytes.size(); offset += BOOTLOADER_DATA_CHUNK) {
            BootloaderPageDataWrite chunk;
            chunk.dest = job.outcome.key.id;
            std::copy_n(
              page.bytes.begin() + long(offset), BOOTLOADER_DATA_CHUNK, chunk.data.begin());
            network_.send(job.outcome.key.target, chunk);
        }
        job.stage = Stage::awaiting_page_ack;
        job.deadline = Clock::now() + settings_.page_timeout;
    }

    void send_reset(Job &job)
    {
        job.stage = Stage::resetting;
        job.deadline = Clock::now() + settings_.page_timeout;
        network_.send(job.outcome.key.target,
                      NodeCommand{ MSG_BOOTLOADER_RESET, job.outcome.key.id });
    }

    // The bootloader describes itself: check that the image fits it, then
    // write (or, after an unexpected restart, resume) the pages.
    void described(Job &job, const BootloaderDescription &description)
    {
        if (job.stage == Stage::finished)
            return;
        if (job.stage == Stage::restarting) {
            // A bootloader that finds no valid application stays and says so.
            finish(job, refused_image);
            return;
        }
        if (description.page_size != pages_.front().bytes.size()) {
            finish(job,
                   "its bootloader writes pages of " + std::to_string(description.page_size) +
                     " bytes; the image is cut into pages of " +
                     std::to_string(pages_.front().bytes.size()));
            return;
        }
        uint32_t first = description.pages_start;
        uint32_t end = first + description.pages_count;
        for (const FlashPage &page : pages_) {
            if (page.number < first || page.number >= end) {
                finish(job,
                       "the image has page " + std::to_string(page.number) +
                         ", outside the pages its bootloader may write (" + std::to_string(first) +
                         " to " + std::to_string(end - 1) + ")");
                return;
            }
        }
        if (job.stage != Stage::entering)
            job.outcome.pages_sent_again++; // it restarted in the middle: resume the page
        job.attempts = 0;
        send_page(job);
    }

    void acknowledged(Job &job, const BootloaderAck &ack)
    {
        if (job.stage == Stage::resetting) {
            if (ack.error_code != 0) {
                finish(job,
                       "BOOTLOADER_RESET answered with error code " +
                         std::to_string(ack.error_code));
                return;
            }
            job.outcome.flashed = true;
            job.stage = Stage::restarting;
            job.deadline = Clock::now() + settings_.restart_timeout;
            job.next_list_nodes = Clock::now();
            return;
        }
        if (job.stage != Stage::awaiting_write_ack && job.stage != Stage::awaiting_page_ack)
            return;
        if (ack.error_code != 0) {
            finish(job, ack_problem(ack, pages_[job.page_index].number));
            return;
        }
        if (job.stage == Stage::awaiting_write_ack) {
            send_chunks(job);
            return;
        }
        job.outcome.pages_written++;
        progress_.pages_done++;
        report();
        job.page_index++;
        job.attempts = 0;
        if (job.page_index < pages_.size())
            send_page(job);
        else
            send_reset(job);
    }

    void receive(const ReceivedFrame &frame)
    {
        if (!frame.message)
            return;
        for (Job &job : jobs_) {
            if (frame.target != job.outcome.key.target || frame.frame.source != job.outcome.key.id)
                continue;
            if (const auto *description = std::get_if<BootloaderDescription>(&*frame.message))
                described(job, *description);
            else if (const auto *ack = std::get_if<BootloaderAck>(&*frame.message))
                acknowledged(job, *ack);
            else if (job.stage == Stage::restarting &&
                     std::holds_alternative<NodePresent>(*frame.message)) {
                job.outcome.restarted = true;
                finish(job);
            }
        }
    }

    Milliseconds time_to_next_deadline() const
    {
        auto now = Clock::now();
        Milliseconds shortest = LONGEST_WAIT;
        for (const Job &job : jobs_) {
            if (job.stage == Stage::finished)
                continue;
            auto left = std::chrono::duration_cast<Milliseconds>(job.deadline - now);
            shortest = std::clamp(left, Milliseconds(0), shortest);
        }
        return shortest;
    }

    void check_deadlines()
    {
        auto now = Clock::now();
        for (Job &job : jobs_) {
            if (job.stage == Stage::restarting && now >= job.next_list_nodes) {
                job.next_list_nodes = now + LIST_NODES_RETRY;
                network_.send(job.outcome.key.target, ListNodes{});
            }
            if (job.stage == Stage::finished || now < job.deadline)
                continue;
            switch (job.stage) {
            case Stage::entering:
                finish(job,
                       "no BOOTLOADER_DESCRIPTION within " +
                         std::to_string(settings_.enter_timeout.count()) +
                         " ms: the node did not enter its bootloader");
                break;
            case Stage::awaiting_write_ack:
            case Stage::awaiting_page_ack:
                if (job.attempts < settings_.page_attempts) {
                    job.outcome.pages_sent_again++;
                    send_page(job);
                } else {
                    finish(job,
                           "page " + std::to_string(pages_[job.page_index].number) +
                             ": no acknowledgement after " + std::to_string(job.attempts) +
                             " attempts");
                }
                break;
            case Stage::resetting:
                finish(job, "every page written, but BOOTLOADER_RESET was not acknowledged");
                break;
            case Stage::restarting:
                finish(job,
                       "did not answer within " +
                         std::to_string(settings_.restart_timeout.count()) +
                         " ms of BOOTLOADER_RESET; " + refused_image);
                break;
            case Stage::finished: break;
            }
        }
    }
};

} // namespace

std::vector<FlashOutcome> flash_nodes(Network &network,
                                      const std::vector<NodeKey> &nodes,
                                      const std::vector<FlashPage> &pages,
                                      const FlashSettings &settings,
                                      const std::function<void(const FlashProgress &)> &on_progress)
{
    if (pages.empty())
        throw NetworkError("the image holds no page to flash");
    for (const FlashPage &page : pages)
        if (page.bytes.size() != pages.front().bytes.size() || page.bytes.empty() ||
            page.bytes.size() % BOOTLOADER_DATA_CHUNK != 0)
            throw NetworkError("the image's pages must all have the same size, a multiple of " +
                               std::to_string(BOOTLOADER_DATA_CHUNK) + " bytes");
    return GroupFlash(network, nodes, pages, settings, on_progress).run();
}

} // namespace aseba::client
