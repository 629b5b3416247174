// The client library's flasher against a scripted bootloader on a loopback
// socket that loses acknowledgements as a radio link would, or refuses a
// page: the flasher must send lost pages again, end with every page written
// as sent, and name the page a bootloader refused.

#include <gtest/gtest.h>

#include <map>
#include <mutex>
#include <set>

#include "console_support.hpp"
#include "tools/client/flasher.hpp"

using namespace aseba;
using namespace aseba::client;

namespace
{

constexpr uint16_t NODE_ID = 3;
constexpr uint16_t PAGE_SIZE = 128;
constexpr uint16_t PAGES_START = 4;
constexpr uint16_t PAGES_COUNT = 100;
constexpr uint16_t FAILED_ADDRESS = 0x1234;

struct BootloaderScript {
    std::set<uint16_t> lose_write_ack_once; // WRITE_PAGE acknowledged, but the ack is lost
    std::set<uint16_t> lose_page_ack_once;  // the page is programmed, its ack lost
    std::optional<uint16_t> refuse;         // programming fails
};

// A node in its bootloader: REBOOT makes it describe itself, pages are kept
// as programmed, BOOTLOADER_RESET starts an "application" that answers
// LIST_NODES.
class FakeBootloader
{
  public:
    explicit FakeBootloader(BootloaderScript script)
      : script_(std::move(script))
      , peer_([this](const Frame &frame) { return answer(frame); })
    {
    }
    std::string target() const
    {
        return peer_.target();
    }
    std::map<uint16_t, std::vector<uint8_t>> programmed()
    {
        std::lock_guard<std::mutex> lock(mutex_);
        return programmed_;
    }

  private:
    std::vector<Frame> answer(const Frame &frame)
    {
        std::vector<Frame> replies;
        auto send = [&](const Message &message) { replies.push_back(encode(message, NODE_ID)); };
        Message message = decode(frame);
        if (const auto *command = std::get_if<NodeCommand>(&message)) {
            if (command->type == NODE_MSG_REBOOT && command->dest == NODE_ID)
                send(BootloaderDescription{ PAGE_SIZE, PAGES_START, PAGES_COUNT });
            else if (command->type == MSG_BOOTLOADER_RESET && command->dest == NODE_ID) {
                send(BootloaderAck{ 0, {} });
                application_ = true;
            }
        } else if (std::holds_alternative<ListNodes>(message) && application_) {
            send(NodePresent{ PROTOCOL_VERSION });
        } else if (const auto *write_page = std::get_if<BootloaderPageCommand>(&message)) {
            page_ = write_page->page;
            data_.clear();
            if (script_.lose_write_ack_once.erase(*page_) == 0)
                send(BootloaderAck{ 0, {} });
        } else if (const auto *chunk = std::get_if<BootloaderPageDataWrite>(&message)) {
            if (!page_)
                return replies;
            data_.insert(data_.end(), chunk->data.begin(), chunk->data.end());
            if (data_.size() < PAGE_SIZE)
                return replies;
            if (script_.refuse == page_) {
                send(BootloaderAck{ BOOTLOADER_ERROR_PROGRAMMING_FAILED, FAILED_ADDRESS });
            } else {
                {
                    std::lock_guard<std::mutex> lock(mutex_);
                    programmed_[*page_] = data_;
                }
                if (script_.lose_page_ack_once.erase(*page_) == 0)
                    send(BootloaderAck{ 0, {} });
            }
            page_.reset();
        }
        return replies;
    }

    BootloaderScript script_;
    bool application_ = false;
    std::optional<uint16_t> page_;
    std::vector<uint8_t> data_;
    std::mutex mutex_;
    std::map<uint16_t, std::vector<uint8_t>> programmed_;
    console_test::ScriptedPeer peer_; // last: it answers from its thread at once
};

std::vector<FlashPage> test_pages(uint16_t count)
{
    std::vector<FlashPage> pages;
    for (uint16_t i = 0; i < count; i++) {
        FlashPage page{ uint16_t(PAGES_START + i), std::vector<uint8_t>(PAGE_SIZE) };
        for (size_t b = 0; b < PAGE_SIZE; b++)
            page.bytes[b] = uint8_t(i * 7 + b);
        pages.push_back(page);
    }
    return pages;
}

FlashSettings quick_settings()
{
    FlashSettings settings;
    settings.enter_timeout = Milliseconds(1000);
    settings.page_timeout = Milliseconds(100);
    settings.restart_timeout = Milliseconds(1000);
    return settings;
}

} // namespace

TEST(Flasher, SendsAgainThePagesWhoseAcknowledgementIsLost)
{
    FakeBootloader bootloader({ { 5, 8 }, { 6, 9 }, {} });
    Network network;
    size_t target = network.connect(bootloader.target());
    std::vector<FlashPage> pages = test_pages(8);
    size_t progress_calls = 0;
    std::vector<FlashOutcome> outcomes = flash_nodes(
      network, { { target, NODE_ID } }, pages, quick_settings(), [&](const FlashProgress &) {
          progress_calls++;
      });

    ASSERT_EQ(outcomes.size(), 1u);
    EXPECT_TRUE(outcomes[0].flashed);
    EXPECT_TRUE(outcomes[0].restarted);
    EXPECT_EQ(outcomes[0].problem, "");
    EXPECT_EQ(outcomes[0].pages_written, pages.size());
    EXPECT_EQ(outcomes[0].pages_sent_again, 4u); // two write acks and two page acks lost
    EXPECT_EQ(progress_calls, pages.size() + 1); // every page, then the end

    std::map<uint16_t, std::vector<uint8_t>> programmed = bootloader.programmed();
    ASSERT_EQ(programmed.size(), pages.size());
    for (const FlashPage &page : pages)
        EXPECT_EQ(programmed[page.number], page.bytes) << "page " << page.number;
}

TEST(Flasher, NamesThePageABootloaderRefuses)
{
    FakeBootloader bootloader({ {}, {}, uint16_t(PAGES_START + 2) });
    Network network;
    size_t target = network.connect(bootloader.target());
    std::vector<FlashOutcome> outcomes =
      flash_nodes(network, { { target, NODE_ID } }, test_pages(5), quick_settings(), {});

    ASSERT_EQ(outcomes.size(), 1u);
    EXPECT_FALSE(outcomes[0].flashed);
    EXPECT_EQ(outcomes[0].pages_written, 2u);
    EXPECT_NE(outcomes[0].problem.find("page 6"), std::string::npos) << outcomes[0].problem;
    EXPECT_NE(outcomes[0].problem.find("0x1234"), std::string::npos) << outcomes[0].problem;
}

TEST(Flasher, RefusesPagesOutsideTheBootloadersRange)
{
    FakeBootloader bootloader({});
    Network network;
    size_t target = network.connect(bootloader.target());
    std::vector<FlashPage> pages = test_pages(2);
    pages[1].number = PAGES_START + PAGES_COUNT; // one past the last
    std::vector<FlashOutcome> outcomes =
      flash_nodes(network, { { target, NODE_ID } }, pages, quick_settings(), {});

    ASSERT_EQ(outcomes.size(), 1u);
    EXPECT_FALSE(outcomes[0].flashed);
    EXPECT_EQ(outcomes[0].pages_written, 0u);
    EXPECT_NE(outcomes[0].problem.find("outside the pages"), std::string::npos)
      << outcomes[0].problem;
    EXPECT_TRUE(bootloader.programmed().empty());
}

TEST(Flasher, ANodeThatNeverEntersItsBootloaderTimesOut)
{
    FakeBootloader bootloader({});
    Network network;
    size_t target = network.connect(bootloader.target());
    FlashSettings settings = quick_settings();
    settings.enter_timeout = Milliseconds(200);
    // Node 9 is not there: nothing answers its REBOOT.
    std::vector<FlashOutcome> outcomes =
      flash_nodes(network, { { target, 9 } }, test_pages(1), settings, {});
    ASSERT_EQ(outcomes.size(), 1u);
    EXPECT_NE(outcomes[0].problem.find("no BOOTLOADER_DESCRIPTION"), std::string::npos)
      << outcomes[0].problem;
}
