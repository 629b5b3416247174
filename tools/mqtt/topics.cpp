// Topic names, built and taken apart.

#include "topics.hpp"

namespace aseba::mqtt
{

namespace
{

bool starts_with(const std::string &text, const std::string &start)
{
    return text.compare(0, start.size(), start) == 0;
}

} // namespace

bool is_topic_level(const std::string &text)
{
    return !text.empty() && text.find_first_of("/+#") == std::string::npos &&
           text.find('\0') == std::string::npos;
}

std::string TopicLayout::event(const std::string &name) const
{
    return prefix + "/event/" + name;
}

std::string TopicLayout::every_event() const
{
    return prefix + "/event/+";
}

std::string TopicLayout::status(const std::string &bridge) const
{
    return prefix + "/bridge/" + bridge;
}

std::string TopicLayout::node(const std::string &network, uint16_t id) const
{
    return prefix + "/network/" + network + "/node/" + std::to_string(id);
}

std::string TopicLayout::variable(const std::string &network,
                                  uint16_t id,
                                  const std::string &name) const
{
    return node(network, id) + "/variable/" + name;
}

std::string TopicLayout::command(const std::string &network, const std::string &node_level) const
{
    return prefix + "/network/" + network + "/node/" + node_level + "/command";
}

std::string TopicLayout::every_command(const std::string &network) const
{
    return command(network, "+");
}

std::string TopicLayout::reply(const std::string &network, const std::string &node_level) const
{
    return prefix + "/network/" + network + "/node/" + node_level + "/reply";
}

std::optional<std::string> TopicLayout::event_name(const std::string &topic) const
{
    std::string start = prefix + "/event/";
    if (!starts_with(topic, start))
        return std::nullopt;
    std::string name = topic.substr(start.size());
    if (!is_topic_level(name))
        return std::nullopt;
    return name;
}

std::optional<TopicLayout::CommandAddress> TopicLayout::command_address(
  const std::string &topic) const
{
    std::string start = prefix + "/network/";
    std::string end = "/command";
    if (!starts_with(topic, start) || topic.size() < start.size() + end.size() ||
        topic.compare(topic.size() - end.size(), end.size(), end) != 0)
        return std::nullopt;
    // NETWORK/node/NODE between them.
    std::string middle = topic.substr(start.size(), topic.size() - start.size() - end.size());
    size_t node_level = middle.find("/node/");
    if (node_level == std::string::npos)
        return std::nullopt;
    CommandAddress address{ middle.substr(0, node_level), middle.substr(node_level + 6) };
    if (!is_topic_level(address.network) || !is_topic_level(address.node))
        return std::nullopt;
    return address;
}

} // namespace aseba::mqtt
