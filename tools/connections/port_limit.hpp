// What one listening port of the host tools (epuck-emu's network, robot,
// control and arena feed ports; aseba-ide's web port) may hold, and who
// gives way when it is full (docs/threat-model.md):
//
// - each port holds at most its own number of connections, so that filling
//   one (a tool opening hundreds of connections) leaves the others
//   reachable, and the process reserves descriptors for all of them;
// - a connection that arrives at a full port takes the place of the one
//   that has said nothing for the longest time, if that one has been silent
//   for the port's grace at least; otherwise the newcomer is closed at once,
//   rather than left waiting for a place that may never come.
//
// A silent client is not closed otherwise: a monitor that only listens
// (asebadump, `aseba monitor`, an arena viewer) is a normal client, and keeps
// its place as long as the port has room. Header only, free of any socket
// library, so that each port's own code (asio, websocketpp) applies it.

#pragma once

#include <sys/resource.h>

#include <cerrno>
#include <chrono>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace aseba::connections
{

using Clock = std::chrono::steady_clock;

// How long a client of a full port must have been silent to give its place.
inline constexpr Clock::duration IDLE_GRACE = std::chrono::seconds(10);

struct PortLimit {
    size_t capacity = 64; // connections held at once
    Clock::duration idle_grace = IDLE_GRACE;
};

// Of the clients [first, last) of a full port, the one that gives its place
// to a newcomer: the one silent the longest (`silent_since(client)`, when it
// last said something), if silent for `limit.idle_grace` at least; `last`
// when none is (the newcomer is closed).
template<typename Iterator, typename SilentSince>
Iterator client_giving_way(Iterator first,
                           Iterator last,
                           SilentSince silent_since,
                           const PortLimit &limit,
                           Clock::time_point now)
{
    Iterator quietest = last;
    for (Iterator client = first; client != last; ++client)
        if (quietest == last || silent_since(*client) < silent_since(*quietest))
            quietest = client;
    if (quietest != last && now - silent_since(*quietest) < limit.idle_grace)
        return last;
    return quietest;
}

// Whether a newcomer may join a port whose clients are `clients` (those
// `is_open` says are still connected): the port has room, or the client
// giving way (client_giving_way) is closed by `close` for it.
template<typename Clients, typename IsOpen, typename SilentSince, typename Close>
bool make_room(Clients &clients,
               IsOpen is_open,
               SilentSince silent_since,
               Close close,
               const PortLimit &limit)
{
    std::vector<typename Clients::value_type *> open;
    for (auto &client : clients)
        if (is_open(client))
            open.push_back(&client);
    if (open.size() < limit.capacity)
        return true;
    auto quietest = client_giving_way(
      open.begin(),
      open.end(),
      [&](const typename Clients::value_type *client) { return silent_since(*client); },
      limit,
      Clock::now());
    if (quietest == open.end())
        return false;
    close(**quietest);
    return true;
}

// Makes sure the process may hold `needed` descriptors (its ports' caps,
// their listeners and its files), raising its soft limit up to the hard one
// if need be; throws std::runtime_error saying what `ulimit -n` would need
// when it cannot. Beyond the limit, accepting fails and every port of the
// process becomes unreachable at once.
inline void reserve_descriptors(size_t needed)
{
    rlimit limit{};
    if (getrlimit(RLIMIT_NOFILE, &limit) != 0)
        throw std::runtime_error(std::string("cannot read the open files limit: ") +
                                 std::strerror(errno));
    if (limit.rlim_cur == RLIM_INFINITY || limit.rlim_cur >= needed)
        return;
    if (limit.rlim_max == RLIM_INFINITY || limit.rlim_max >= needed) {
        limit.rlim_cur = rlim_t(needed);
        if (setrlimit(RLIMIT_NOFILE, &limit) == 0)
            return;
    }
    throw std::runtime_error("the ports need " + std::to_string(needed) +
                             " open files, more than this process may have (" +
                             std::to_string(limit.rlim_max) + ", ulimit -n)");
}

} // namespace aseba::connections
