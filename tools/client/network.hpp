// The console's model of Aseba networks: the links it is connected to, the
// nodes discovered on them with their descriptions and execution states, and
// the commands of protocol.md §6 with their answers awaited within a time
// limit. It never prints and never exits: failures are exceptions
// (TransportError, ProtocolError, TimeoutError, NetworkError) whose what()
// is a sentence for people.
//
// A Network is used by one thread; only wake() may be called from others.
// Its links run on standalone asio, which this header does not include.

#pragma once

#include <chrono>
#include <compare>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "messages.hpp"
#include "program.hpp"
#include "transport.hpp"

namespace aseba::client
{

using Clock = std::chrono::steady_clock;
using Milliseconds = std::chrono::milliseconds;

constexpr Milliseconds DEFAULT_ANSWER_TIMEOUT{ 1000 };
constexpr unsigned DEFAULT_MAX_LINE_STEPS = 10000; // a line that loops on itself
constexpr Milliseconds LIST_NODES_PERIOD{ 1000 };  // as Aseba Studio
constexpr Milliseconds NODE_SILENCE_LIMIT{ 3000 }; // then a node counts as gone
constexpr Milliseconds RECONNECT_PERIOD{ 500 };    // between attempts on a link that is down
// discover()'s wait for more nodes: at least this, and this when no node
// answers LIST_NODES (protocol 4 nodes do not).
constexpr Milliseconds DISCOVERY_QUIET_MIN{ 5 };
constexpr Milliseconds DISCOVERY_QUIET_WITHOUT_ANSWER{ 150 };

// What a link does when its target cannot be reached or goes away.
enum class LinkPolicy {
    // connect() throws, and so does poll() when the link drops: a command
    // line tool fails fast with a clear error.
    fail_fast,
    // connect() never throws for an unreachable target: the link starts
    // down and poll() tries again every RECONNECT_PERIOD, without waiting
    // for long. A link that drops is marked down and its nodes forgotten;
    // back up, its nodes are discovered again. For long-running tools.
    reconnect,
};

enum class LinkState { up, down };

// A node that did not answer in time.
class TimeoutError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// A request the network cannot serve: unknown node, node not described, ...
class NetworkError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// A node is known by the link it is on and its id there.
struct NodeKey {
    size_t target = 0;
    uint16_t id = 0;
    auto operator<=>(const NodeKey &) const = default;
};

// The last EXECUTION_STATE_CHANGED of a node (bytecode.md §6).
struct ExecutionState {
    uint16_t pc = 0;
    uint16_t flags = 0;
    // Step by step inside an event (e.g. on a breakpoint).
    bool stepping() const
    {
        return (flags & FLAG_STEP_BY_STEP) && (flags & FLAG_EVENT_ACTIVE);
    }
    bool stopped() const
    {
        return (flags & FLAG_STEP_BY_STEP) && !(flags & FLAG_EVENT_ACTIVE);
    }
    bool running() const
    {
        return !(flags & FLAG_STEP_BY_STEP);
    }
    // "running", "stepping" or "stopped", as Aseba Studio names them.
    std::string name() const;
};

struct Node {
    NodeKey key;
    uint16_t protocol_version = 0; // from NODE_PRESENT, then DESCRIPTION
    bool described = false;        // every part of the description arrived
    bool compatible = true;        // protocol version in [4, 5]
    TargetDescription description; // complete when `described`
    std::optional<ExecutionState> execution;
    Clock::time_point last_seen{};
    std::shared_ptr<const CompiledProgram> program; // loaded by this client

    // The name, or "node ID" before the description arrives.
    std::string label() const;
};

// One frame received from a link, decoded if it could be.
struct ReceivedFrame {
    Clock::time_point time;                          // for intervals
    std::chrono::system_clock::time_point wall_time; // for people
    size_t target = 0;
    Frame frame;
    std::optional<Message> message; // empty when the payload was malformed
    std::string error;              // why it was malformed
};

class Network
{
  public:
    explicit Network(Milliseconds answer_timeout = DEFAULT_ANSWER_TIMEOUT);
    ~Network();
    Network(const Network &) = delete;
    Network &operator=(const Network &) = delete;

    // Connects to a target string (transport.hpp); returns its index. With
    // fail_fast, throws TransportError when the target cannot be reached
    // within the answer timeout; with reconnect, only for a malformed
    // target string.
    size_t connect(const std::string &target, LinkPolicy policy = LinkPolicy::fail_fast);
    size_t target_count() const;
    std::string target_name(size_t target) const;

    // Whether link `target` is up now, and why it went down (empty when up).
    LinkState link_state(size_t target) const;
    std::string link_error(size_t target) const;

    // Called from poll() when a link goes down (with the reason) or comes
    // back up (reconnect links).
    void set_link_listener(
      std::function<void(size_t target, LinkState state, const std::string &reason)> listener);

    // Makes a poll() in progress, or the next one, return promptly. The only
    // member that may be called from any thread.
    void wake();

    // The time every command waits for an answer.
    Milliseconds answer_timeout() const
    {
        return answer_timeout_;
    }

    // Broadcasts LIST_NODES on every link that is up and collects the nodes
    // that answer and their descriptions. Returns as soon as every node that
    // answered has described itself and no new node appeared for `quiet`
    // (default: twice the time the first node took to answer, which is how
    // far apart the nodes' answers may be), or after the answer timeout.
    void discover(std::optional<Milliseconds> quiet = std::nullopt);

    // For long sessions (monitors, an IDE): broadcasts LIST_NODES if the last
    // one is older than a second, so that nodes keep showing they are alive
    // and new ones get described (protocol.md §6.1). Call it often.
    void keep_alive();

    // Whether `key` sent anything in the last 3 s (upstream hosts' rule).
    bool is_alive(NodeKey key) const;

    // Every node heard of, described or not, in key order.
    std::vector<NodeKey> node_keys() const;
    const Node &node(NodeKey key) const;

    // The described nodes matching `selector`: "all", a node id, or a node
    // name (every node of that name). Throws NetworkError when none match,
    // saying why the nodes that answered cannot be used (a description that
    // never completed, another protocol version).
    std::vector<NodeKey> select(const std::string &selector) const;

    // Sends `message` on one link (`target`; TransportError when it is
    // down), or on every link that is up. `source` is the sender's id: a
    // host's (0) unless a bridge passes on another network's node.
    void send(size_t target, const Message &message, uint16_t source = HOST_SOURCE);
    void send_to_all(const Message &message);

    // Reads what the links have, waiting at most `timeout` for the first
    // bytes (or a link going up or down, or wake()); updates the model and
    // calls the listeners for every frame and link change. Reconnect links
    // that are down are tried again from here.
    void poll(Milliseconds timeout);

    // Polls until `done()` is true (true) or `timeout` passes (false).
    bool wait_until(const std::function<bool()> &done, Milliseconds timeout);

    // Called for every received frame (monitoring).
    void set_listener(std::function<void(const ReceivedFrame &)> listener);

    // Malformed frames received so far (they are reported, then dropped).
    uint64_t malformed_frames() const
    {
        return malformed_frames_;
    }

    // --- execution control (bytecode.md §6.4); each returns the new state.
    ExecutionState execution_state(NodeKey key); // asks the node
    ExecutionState reset(NodeKey key);
    ExecutionState pause(NodeKey key);
    ExecutionState stop(NodeKey key);
    // Studio's Run: STEP first when the node is stepping (past a breakpoint).
    ExecutionState run(NodeKey key);
    // One instruction, if an event is active; else the state is unchanged.
    ExecutionState step(NodeKey key);

    // Aseba Studio's "Next": steps until the node leaves the current source
    // line of its program (or enters an event handler, or its event ends),
    // at most `max_steps` instructions. Needs the node's program.
    ExecutionState step_line(NodeKey key, unsigned max_steps = DEFAULT_MAX_LINE_STEPS);

    // Uploads `bytecode` in chunks of at most 256 words (each answered by an
    // EXECUTION_STATE_CHANGED); the node is then reset, not running.
    void upload(NodeKey key, const std::vector<uint16_t> &bytecode);

    // Remembers the program now on the node (for names and source lines).
    void set_program(NodeKey key, std::shared_ptr<const CompiledProgram> program);

    // Variable memory: read in requests of at most 257 words, write in
    // messages of at most 256 values.
    std::vector<int16_t> read_variables(NodeKey key, uint16_t start, uint16_t length);
    void write_variables(NodeKey key, uint16_t start, const std::vector<int16_t> &values);

    // Breakpoints at bytecode addresses; set returns the node's verdict.
    bool set_breakpoint(NodeKey key, uint16_t pc);
    void clear_breakpoint(NodeKey key, uint16_t pc);
    void clear_all_breakpoints(NodeKey key);

    // A global event from the host (source 0) on every link.
    void emit(uint16_t event_id, const std::vector<int16_t> &arguments);

    // WRITE_BYTECODE and REBOOT: no answer is defined, so none is awaited.
    // After REBOOT the node's execution state is unknown until it says it.
    void write_bytecode(NodeKey key);
    void reboot(NodeKey key);

  private:
    struct Link;
    struct Io; // the asio context the links run on
    void start_reading(size_t target);
    void open_link(size_t target);
    // Handles what the links' handlers left: bytes, failures, openings.
    // Returns whether anything happened.
    bool process_links();
    void link_went_down(size_t target, std::string reason);
    void forget_nodes(size_t target);
    [[noreturn]] void no_usable_node(const std::string &selector) const;
    // Why node `key`, which answered, has no complete description.
    std::string description_problem(NodeKey key) const;
    // A description being received: the header, then its parts in order.
    struct DescriptionAssembly {
        Description header;
        TargetDescription parts;
    };
    Node &known_node(NodeKey key);
    const Node &described_node(NodeKey key) const;
    void handle(size_t target, Frame frame);
    void update_model(size_t target, const Frame &frame, const Message &message);
    // Runs `request`, then polls until `answered()`, offering every decoded
    // message of node `key` to `collect`; throws TimeoutError naming `what`.
    void exchange(NodeKey key,
                  const std::function<void()> &request,
                  const std::function<void(const Message &)> &collect,
                  const std::function<bool()> &answered,
                  const std::string &what);
    // Sends `command` and waits for the node's next EXECUTION_STATE_CHANGED.
    ExecutionState command_with_state(NodeKey key, const Message &command, const char *what);
    [[noreturn]] void timed_out(NodeKey key, const std::string &what) const;

    Milliseconds answer_timeout_;
    std::unique_ptr<Io> io_;
    std::vector<std::unique_ptr<Link>> links_;
    std::function<void(size_t, LinkState, const std::string &)> link_listener_;
    std::map<NodeKey, Node> nodes_;
    std::map<NodeKey, DescriptionAssembly> assemblies_;
    std::function<void(const ReceivedFrame &)> listener_;
    // While a command waits for its answer, every decoded frame goes here too.
    std::function<void(const ReceivedFrame &)> collector_;
    Clock::time_point last_new_node_{};
    Clock::time_point last_list_nodes_{};
    std::optional<Clock::time_point> first_answer_; // NODE_PRESENT since the last discover()
    uint64_t malformed_frames_ = 0;
};

} // namespace aseba::client
