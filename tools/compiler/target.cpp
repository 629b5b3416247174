// The one text form of a target's definitions that is not a file: a global
// event declared on a command line.

#include "tools/compiler/target.hpp"

#include <stdexcept>

namespace aseba
{

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
