// The bridge's topics on the broker (docs/mqtt.md is the reference for
// people): events are shared by every network under PREFIX/event/NAME;
// everything else of a network is under PREFIX/network/NETWORK/, and a
// bridge says whether it is online on PREFIX/bridge/NAME.

#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace aseba::mqtt
{

constexpr const char *DEFAULT_PREFIX = "aseba";

// Whether `text` can be one level of a topic name the bridge builds: not
// empty, no '/', and none of the wildcards '+' and '#'.
bool is_topic_level(const std::string &text);

struct TopicLayout {
    std::string prefix = DEFAULT_PREFIX; // may hold '/' (levels of its own)

    // Events, by name, or by number when no program names them (QoS 1).
    std::string event(const std::string &name) const;
    std::string every_event() const; // the filter PREFIX/event/+

    // A bridge: retained {"online": ...} (and its last will).
    std::string status(const std::string &bridge) const;
    // A node's presence and description, retained; emptied when it goes.
    std::string node(const std::string &network, uint16_t id) const;
    // A watched variable of a node, retained, published when it changes.
    std::string variable(const std::string &network, uint16_t id, const std::string &name) const;
    // Commands to the nodes of a network (NODE: an id or "all"), and the
    // bridge's replies (per node).
    std::string command(const std::string &network, const std::string &node) const;
    std::string every_command(const std::string &network) const; // .../node/+/command
    std::string reply(const std::string &network, const std::string &node) const;

    // The event name of a topic under PREFIX/event/, if it is one.
    std::optional<std::string> event_name(const std::string &topic) const;
    // The network and node level of a command topic, if it is one.
    struct CommandAddress {
        std::string network;
        std::string node;
    };
    std::optional<CommandAddress> command_address(const std::string &topic) const;
};

} // namespace aseba::mqtt
