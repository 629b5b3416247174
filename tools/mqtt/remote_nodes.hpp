// What joins networks without loops or duplicates: the ids under which the
// nodes of other networks appear on ours (remapped when they clash with our
// own nodes' ids, as asebaswitch does), and the events already delivered.

#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>

namespace aseba::mqtt
{

// For one network: the ids given to the nodes of other networks.
class RemoteNodeIds
{
  public:
    // At most this many remote nodes are remembered; beyond, the map starts
    // again (ids are then given anew).
    static constexpr size_t LIMIT = 4096;

    // The id under which node `id` of network `network` appears here, where
    // our own nodes have `local_ids`: its own id when no local node and no
    // other remote node has it, else the lowest free id. Stable while it
    // does not clash. Id 0 (a host tool) stays 0.
    uint16_t id_for(const std::string &network, uint16_t id, const std::set<uint16_t> &local_ids);

    // Whether `id` was given to a remote node (a frame from that source on
    // our network is our own delivery, heard back).
    bool is_remote(uint16_t id) const
    {
        return owners_.count(id) != 0;
    }

  private:
    std::map<std::string, uint16_t> ids_; // "network/id" -> id here
    std::map<uint16_t, std::string> owners_;
};

// The events delivered so far, by the bridge session and sequence number of
// their publisher: QoS 1 may deliver one twice (after a reconnection).
class DuplicateFilter
{
  public:
    static constexpr size_t BRIDGE_LIMIT = 1024; // sessions remembered
    static constexpr uint64_t WINDOW = 64;       // how far back out-of-order events are told

    // Whether this event was seen before (or is older than the window);
    // records it.
    bool seen_before(const std::string &bridge, uint64_t sequence);

  private:
    struct Window {
        uint64_t highest = 0;
        uint64_t seen = 0; // bit i: highest - i was seen
    };
    std::map<std::string, Window> windows_;
};

} // namespace aseba::mqtt
