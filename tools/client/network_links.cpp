// The network's links over asio: opening them (at once, or again and again
// for reconnect links), reading in the background of poll(), writing with a
// time limit, and telling the model and the link listener what happened.
// The model itself (frames, nodes, commands) is network.cpp's.

#include "network.hpp"

#include <array>
#include <atomic>

#include "byte_stream.hpp"

namespace aseba::client
{

namespace
{

constexpr size_t READ_CHUNK = 4096;

} // namespace

struct Network::Io {
    asio::io_context context;
    // poll() waits its whole time even when no link is open.
    asio::executor_work_guard<asio::io_context::executor_type> work =
      asio::make_work_guard(context);
    std::atomic<bool> woken{ false };
};

// A link and what its asio handlers left for poll() to handle.
struct Network::Link {
    explicit Link(asio::io_context &io)
      : stream(io)
    {
    }
    std::string name; // the canonical target text
    TargetAddress address;
    LinkPolicy policy = LinkPolicy::fail_fast;
    detail::ByteStream stream;
    LinkState state = LinkState::down;
    std::string error; // why it is down
    FrameAssembler assembler;
    std::array<uint8_t, READ_CHUNK> input{};
    bool reading = false;
    std::vector<uint8_t> received;      // read, not handled yet
    std::optional<std::string> failure; // the link failed while reading
    bool opening = false;
    std::optional<std::string> opened; // an opening ended: empty, or why it failed
    Clock::time_point next_attempt{};
};

Network::Network(Milliseconds answer_timeout)
  : answer_timeout_(answer_timeout)
  , io_(std::make_unique<Io>())
{
}

// The links close before the io_context goes, which destroys the handlers
// still pending without running them.
Network::~Network()
{
    links_.clear();
}

size_t Network::connect(const std::string &target, LinkPolicy policy)
{
    TargetAddress address = parse_target(target);
    auto link = std::make_unique<Link>(io_->context);
    link->name = target_text(address);
    link->address = address;
    link->policy = policy;
    if (policy == LinkPolicy::fail_fast) {
        link->stream.open(address, answer_timeout_);
        link->state = LinkState::up;
    }
    links_.push_back(std::move(link));
    size_t target_index = links_.size() - 1;
    if (policy == LinkPolicy::fail_fast)
        start_reading(target_index);
    else
        open_link(target_index);
    return target_index;
}

size_t Network::target_count() const
{
    return links_.size();
}

std::string Network::target_name(size_t target) const
{
    return links_.at(target)->name;
}

LinkState Network::link_state(size_t target) const
{
    return links_.at(target)->state;
}

std::string Network::link_error(size_t target) const
{
    return links_.at(target)->error;
}

void Network::set_link_listener(
  std::function<void(size_t target, LinkState state, const std::string &reason)> listener)
{
    link_listener_ = std::move(listener);
}

void Network::wake()
{
    io_->woken = true;
    asio::post(io_->context, [] {});
}

void Network::open_link(size_t target)
{
    Link *link = links_.at(target).get();
    link->opening = true;
    link->stream.async_open(link->address, answer_timeout_, [link](const std::string &failure) {
        link->opening = false;
        link->opened = failure;
    });
}

void Network::start_reading(size_t target)
{
    Link *link = links_.at(target).get();
    if (link->reading || link->state != LinkState::up)
        return;
    link->reading = true;
    link->stream.async_read_some(
      asio::buffer(link->input), [this, target, link](std::error_code error, size_t count) {
          link->reading = false;
          if (link->state != LinkState::up || error == asio::error::operation_aborted)
              return; // closed on purpose
          if (error == asio::error::eof) {
              link->failure = link->name + ": the connection was closed";
              return;
          }
          if (error) {
              link->failure = link->name + ": read failed: " + error.message();
              return;
          }
          link->received.insert(
            link->received.end(), link->input.begin(), link->input.begin() + long(count));
          start_reading(target);
      });
}

void Network::forget_nodes(size_t target)
{
    std::erase_if(nodes_, [target](const auto &entry) { return entry.first.target == target; });
    std::erase_if(assemblies_,
                  [target](const auto &entry) { return entry.first.target == target; });
}

void Network::link_went_down(size_t target, std::string reason)
{
    Link &link = *links_.at(target);
    bool was_up = link.state == LinkState::up;
    bool news = was_up || link.error != reason;
    link.stream.close();
    link.state = LinkState::down;
    link.error = reason;
    link.assembler = FrameAssembler{};
    link.received.clear();
    link.failure.reset();
    link.next_attempt = Clock::now() + RECONNECT_PERIOD;
    if (link.policy == LinkPolicy::fail_fast)
        throw TransportError(reason);
    forget_nodes(target);
    if (news && link_listener_)
        link_listener_(target, LinkState::down, reason);
}

bool Network::process_links()
{
    bool happened = false;
    for (size_t target = 0; target < links_.size(); target++) {
        Link &link = *links_[target];
        if (link.opened) {
            std::string failure = *link.opened;
            link.opened.reset();
            happened = true;
            if (!failure.empty()) {
                link_went_down(target, failure);
                continue;
            }
            link.state = LinkState::up;
            link.error.clear();
            start_reading(target);
            if (link_listener_)
                link_listener_(target, LinkState::up, "");
            // Its nodes describe themselves again (protocol.md §6.1).
            try {
                send(target, ListNodes{ PROTOCOL_VERSION });
            } catch (const TransportError &) {
                continue; // down again at once: the listener heard it
            }
        }
        if (!link.received.empty()) {
            happened = true;
            std::vector<uint8_t> bytes;
            bytes.swap(link.received);
            try {
                link.assembler.feed(bytes.data(), bytes.size());
                while (std::optional<Frame> frame = link.assembler.next())
                    handle(target, std::move(*frame));
            } catch (const ProtocolError &error) {
                std::string reason = link.name + ": " + error.what();
                if (link.policy == LinkPolicy::fail_fast)
                    throw ProtocolError(reason);
                link_went_down(target, reason);
                continue;
            }
        }
        if (link.failure) {
            happened = true;
            link_went_down(target, *link.failure);
        }
    }
    return happened;
}

void Network::send(size_t target, const Message &message, uint16_t source)
{
    Link &link = *links_.at(target);
    if (link.state != LinkState::up)
        throw TransportError(link.name + ": the link is down" +
                             (link.error.empty() ? "" : " (" + link.error + ")"));
    std::vector<uint8_t> bytes = serialize_frame(encode(message, source));
    try {
        link.stream.write_all(bytes.data(), bytes.size(), answer_timeout_, link.name);
    } catch (const TransportError &error) {
        link_went_down(target, error.what()); // throws for fail_fast links
        throw;
    }
}

void Network::send_to_all(const Message &message)
{
    for (size_t target = 0; target < links_.size(); target++) {
        if (links_[target]->state != LinkState::up)
            continue;
        try {
            send(target, message);
        } catch (const TransportError &) {
            // A reconnect link that just went down is news for its listener,
            // not a failure of the other links.
            if (links_[target]->policy == LinkPolicy::fail_fast)
                throw;
        }
    }
}

void Network::poll(Milliseconds timeout)
{
    asio::io_context &io = io_->context;
    const auto deadline = Clock::now() + timeout;
    auto retry_due_links = [&] {
        Clock::time_point next = deadline;
        for (size_t target = 0; target < links_.size(); target++) {
            Link &link = *links_[target];
            if (link.policy != LinkPolicy::reconnect || link.state == LinkState::up ||
                link.opening || link.opened)
                continue;
            if (Clock::now() >= link.next_attempt)
                open_link(target);
            else
                next = std::min(next, link.next_attempt);
        }
        return next;
    };
    bool happened = process_links();
    while (!happened && !io_->woken.exchange(false)) {
        Clock::time_point wake_at = retry_due_links();
        if (io.stopped())
            io.restart();
        io.run_one_until(wake_at);
        happened = process_links();
        if (Clock::now() >= deadline)
            break;
    }
    // Whatever else is ready, without waiting.
    io.poll();
    process_links();
}

bool Network::wait_until(const std::function<bool()> &done, Milliseconds timeout)
{
    const auto deadline = Clock::now() + timeout;
    while (!done()) {
        auto left = std::chrono::duration_cast<Milliseconds>(deadline - Clock::now());
        if (left.count() <= 0)
            return false;
        poll(left);
    }
    return true;
}

} // namespace aseba::client
