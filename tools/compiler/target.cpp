// What every target must respect, and the one text form of a target's
// definitions that is not a file: a global event declared on a command line.

#include "tools/compiler/target.hpp"

#include <stdexcept>

namespace aseba
{

std::string natives_limit_error(size_t count)
{
    if (count <= MAX_NATIVE_FUNCTIONS)
        return "";
    return std::to_string(count) + " native functions, more than the " +
           std::to_string(MAX_NATIVE_FUNCTIONS) + " the bytecode can call";
}

std::string local_events_limit_error(size_t count)
{
    if (count <= MAX_LOCAL_EVENTS)
        return "";
    return std::to_string(count) + " local events, more than the " +
           std::to_string(MAX_LOCAL_EVENTS) + " whose ids stay apart from the global events'";
}

std::string target_limits_error(const TargetDescription &target)
{
    std::string natives = natives_limit_error(target.native_functions.size());
    return natives.empty() ? local_events_limit_error(target.local_events.size()) : natives;
}

GlobalEvent parse_event_declaration(const std::string &text)
{
    GlobalEvent event;
    size_t colon = text.find(':');
    event.name = text.substr(0, colon);
    if (event.name.empty())
        throw std::invalid_argument("--event expects NAME[:SIZE], not '" + text + "'");
    if (colon == std::string::npos)
        return event;
    std::string size = text.substr(colon + 1);
    bool digits = !size.empty() && size.size() <= 3 &&
                  size.find_first_not_of("0123456789") == std::string::npos;
    if (!digits || std::stoul(size) > MAX_EVENT_WORDS)
        throw std::invalid_argument("--event " + text + ": SIZE must be a number of words up to " +
                                    std::to_string(MAX_EVENT_WORDS));
    event.size = uint16_t(std::stoul(size));
    return event;
}

} // namespace aseba
