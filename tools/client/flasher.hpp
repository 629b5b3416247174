// Flashing a firmware image into a group of nodes at once through their
// Aseba bootloaders (protocol.md §6.9). Each node is rebooted into its
// bootloader, gets every page (WRITE_PAGE, then the page's 4-byte
// PAGE_DATA_WRITE chunks, each page acknowledged), and is sent
// BOOTLOADER_RESET; then the flasher waits for it to answer as a node again,
// which shows that its bootloader accepted the new application. Nodes
// progress independently and concurrently: a slow or failing robot holds up
// nobody, and a page whose acknowledgement is lost (a radio drop) is sent
// again a few times before the node counts as failed.

#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "network.hpp"

namespace aseba::client
{

// One page of the image as the bootloader numbers it (byte address / page
// size); `bytes` holds exactly one page.
struct FlashPage {
    uint16_t number = 0;
    std::vector<uint8_t> bytes;
};

struct FlashSettings {
    bool reboot_first = true;             // send REBOOT, else the node is already in its bootloader
    Milliseconds enter_timeout{ 5000 };   // REBOOT to BOOTLOADER_DESCRIPTION
    Milliseconds page_timeout{ 1000 };    // a command to its acknowledgement
    unsigned page_attempts = 3;           // sends of one page before giving up
    Milliseconds restart_timeout{ 5000 }; // BOOTLOADER_RESET to the node answering again
    std::function<bool()> cancelled;      // checked often: true abandons the unfinished nodes
};

struct FlashProgress {
    size_t pages_done = 0;  // acknowledged pages of every node
    size_t pages_total = 0; // pages × nodes
    size_t nodes_done = 0;  // finished, well or not
    size_t nodes_total = 0;
};

struct FlashOutcome {
    NodeKey key;
    bool flashed = false;   // every page acknowledged and BOOTLOADER_RESET acknowledged
    bool restarted = false; // then answered as a node again
    size_t pages_written = 0;
    unsigned pages_sent_again = 0;
    std::string problem; // empty when flashed and restarted
};

// Flashes `pages` into every node of `nodes` and returns one outcome per
// node, in the same order. `on_progress` is called after every
// acknowledged page and when a node finishes. Throws NetworkError before
// touching any node when `pages` is empty or the pages differ in size; a
// node whose bootloader has another page size or range fails alone.
std::vector<FlashOutcome> flash_nodes(
  Network &network,
  const std::vector<NodeKey> &nodes,
  const std::vector<FlashPage> &pages,
  const FlashSettings &settings,
  const std::function<void(const FlashProgress &)> &on_progress);

} // namespace aseba::client
