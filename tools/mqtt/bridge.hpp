// The MQTT bridge: Aseba networks (the client library's Network, its links
// reconnecting by themselves) on one side, an MQTT broker on the other
// (BrokerClient), joined by the topics of docs/mqtt.md. One thread runs it:
// it polls the networks and takes what the broker's thread left in the
// inbox, which wakes it.
//
// Read-only unless told otherwise: it publishes the networks' events, nodes
// and watched variables, and delivers nothing to the robots; events from the
// broker and commands are accepted only when their options say so.

#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "broker_client.hpp"
#include "payloads.hpp"
#include "remote_nodes.hpp"
#include "tools/client/network.hpp"
#include "tools/client/program.hpp"
#include "topics.hpp"

namespace aseba::mqtt
{

using client::Milliseconds;
using client::NodeKey;

constexpr unsigned DEFAULT_EVENTS_PER_SECOND = 1000;
constexpr Milliseconds DEFAULT_VARIABLE_PERIOD{ 1000 };

struct BridgeOptions {
    std::string name;                  // the bridge's name on the broker
    std::vector<std::string> targets;  // Aseba targets (transport.hpp)
    std::vector<std::string> networks; // their names on the broker, one per target
    TopicLayout topics;
    BrokerOptions broker;
    bool accept_events = false;   // deliver the broker's events to the robots
    bool accept_commands = false; // run the broker's commands (else: refuse them)
    // Event names and sizes, and the user variables of the nodes' program.
    std::optional<client::ProgramFile> program;
    CommonDefinitions declared;         // --event NAME[:SIZE]
    std::vector<std::string> variables; // watched: NAME, NAME[i], NAME[i:j]
    Milliseconds variable_period = DEFAULT_VARIABLE_PERIOD;
    // From the broker to the robots, at most (more are dropped, and logged).
    unsigned events_per_second = DEFAULT_EVENTS_PER_SECOND;
};

// What went through, for the log and the tests.
struct BridgeCounters {
    uint64_t events_published = 0; // from the networks to the broker
    uint64_t events_delivered = 0; // from the broker to the networks
    uint64_t echoes = 0;           // our own events, heard back from the broker
    uint64_t duplicates = 0;       // delivered once already
    uint64_t malformed = 0;        // refused: bad payload, unknown name, wrong size
    uint64_t over_rate = 0;        // dropped beyond events_per_second
    uint64_t commands = 0;         // run
    uint64_t commands_refused = 0; // read-only
};

class Bridge
{
  public:
    // Connects to the targets and the broker in the background (neither has
    // to be up yet); throws TransportError for a malformed target and
    // BrokerError for unusable broker options.
    Bridge(BridgeOptions options, std::ostream &log);
    // Removes the nodes' retained presence and says offline.
    ~Bridge();
    Bridge(const Bridge &) = delete;
    Bridge &operator=(const Bridge &) = delete;

    // Bridges until `stop()` is true (asked at least every 50 ms).
    void run(const std::function<bool()> &stop);

    const BridgeCounters &counters() const
    {
        return counters_;
    }

  private:
    void handle_heard_frames();
    // Sends an event on a link if it is up; a link failing now loses it.
    void send_event(size_t target, const client::UserEvent &event, uint16_t source);
    void publish_event(size_t target, uint16_t source, const client::UserEvent &event);
    void pass_to_other_targets(size_t target, uint16_t source, const client::UserEvent &event);
    void on_broker_connected();
    void handle_broker_messages();
    void handle_event(const std::string &name, const std::string &payload);
    void handle_command(const TopicLayout::CommandAddress &address, const std::string &payload);
    Reply run_command(NodeKey key, const Command &command);
    void update_presence();
    void sample_variables();
    void report_broker_state();
    // A problem with input from outside, rate-limited (a flood must not
    // flood the log).
    void log_problem(const std::string &text);
    void flush_log_summary();

    std::string event_name(uint16_t id) const;
    std::optional<uint16_t> event_id(const std::string &name) const;
    std::optional<uint16_t> event_size(uint16_t id) const;
    size_t max_arguments() const;
    std::set<uint16_t> local_ids(size_t target) const;
    std::optional<size_t> target_of_network(const std::string &network) const;
    const client::CompiledProgram *program_for(NodeKey key);

    BridgeOptions options_;
    std::ostream &log_;
    const std::string session_; // this run's id in published events
    uint64_t sequence_ = 0;
    CommonDefinitions definitions_; // the program's events, else the declared ones
    std::unique_ptr<client::Network> network_;
    std::vector<client::ReceivedFrame> heard_; // user events of the last poll
    std::unique_ptr<BrokerClient> broker_;
    std::vector<RemoteNodeIds> remote_ids_; // per target
    DuplicateFilter duplicates_;
    BridgeCounters counters_;

    uint64_t connections_seen_ = 0;
    bool broker_up_reported_ = false;
    std::string broker_error_reported_;
    BrokerDrops drops_reported_;

    std::map<NodeKey, std::string> presence_;      // published payload per node
    std::map<std::string, std::string> variables_; // topic -> published values
    std::map<NodeKey, std::shared_ptr<const client::CompiledProgram>> programs_;
    std::set<std::string> variable_problems_; // logged once each
    client::Clock::time_point next_variables_{};

    // Token bucket of events from the broker.
    double event_tokens_ = 0;
    client::Clock::time_point tokens_time_{};

    client::Clock::time_point log_second_{};
    unsigned log_lines_this_second_ = 0;
    uint64_t log_lines_suppressed_ = 0;
};

// A session id for the published events: random, 16 hex digits.
std::string new_session_id();

} // namespace aseba::mqtt
