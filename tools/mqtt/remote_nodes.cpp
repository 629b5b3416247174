// Remapped ids and the duplicate filter.

#include "remote_nodes.hpp"

namespace aseba::mqtt
{

uint16_t RemoteNodeIds::id_for(const std::string &network,
                               uint16_t id,
                               const std::set<uint16_t> &local_ids)
{
    if (id == 0)
        return 0;
    std::string origin = network + "/" + std::to_string(id);
    auto known = ids_.find(origin);
    if (known != ids_.end()) {
        if (local_ids.count(known->second) == 0)
            return known->second;
        // A node of ours took that id since: give another.
        owners_.erase(known->second);
        ids_.erase(known);
    }
    if (ids_.size() >= LIMIT) {
        ids_.clear();
        owners_.clear();
    }
    auto free = [&](uint16_t candidate) {
        return candidate != 0 && local_ids.count(candidate) == 0 && owners_.count(candidate) == 0;
    };
    uint16_t given = id;
    if (!free(given)) {
        given = 1;
        while (!free(given))
            ++given; // ends: fewer than 65535 ids are taken
    }
    ids_[origin] = given;
    owners_[given] = origin;
    return given;
}

bool DuplicateFilter::seen_before(const std::string &bridge, uint64_t sequence)
{
    auto found = windows_.find(bridge);
    if (found == windows_.end()) {
        if (windows_.size() >= BRIDGE_LIMIT)
            windows_.erase(windows_.begin());
        windows_[bridge] = Window{ sequence, 1 };
        return false;
    }
    Window &window = found->second;
    if (sequence > window.highest) {
        uint64_t shift = sequence - window.highest;
        window.seen = shift >= WINDOW ? 0 : window.seen << shift;
        window.seen |= 1;
        window.highest = sequence;
        return false;
    }
    uint64_t age = window.highest - sequence;
    if (age >= WINDOW)
        return true;
    uint64_t bit = uint64_t(1) << age;
    if (window.seen & bit)
        return true;
    window.seen |= bit;
    return false;
}

} // namespace aseba::mqtt
