// The IDE's link to the robots: a thread of its own that owns the client
// library's Network (whose commands wait for answers) so that the web side
// never waits for a robot. It runs the tasks the server gives it, reads the
// variables the browsers show, and reports what it hears on the server's
// io_context: frames, robots that appear, change or go, links that go down
// or come back (the Network reconnects them by itself).

#pragma once

#include <atomic>
#include <chrono>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <asio/io_context.hpp>

#include "tools/client/network.hpp"

namespace aseba::ide
{

using client::NodeKey;

// Everything the IDE shows of a robot, copied out of the network model.
struct RobotSnapshot {
    NodeKey key;
    bool described = false;
    bool compatible = true;
    bool alive = true; // heard from in the last 3 s
    uint16_t protocol_version = 0;
    TargetDescription description; // when described
    std::optional<client::ExecutionState> execution;
};

// One link of the network: up, or down with the reason.
struct LinkStatus {
    std::string target;
    bool up = false;
    std::string error;
};

// What the worker reports; each is called on the server's io_context.
struct NetworkReports {
    std::function<void(std::vector<client::ReceivedFrame> &&)> frames;
    std::function<void(RobotSnapshot &&)> robot_changed;
    std::function<void(NodeKey)> robot_gone;
    std::function<void(std::vector<LinkStatus> &&)> links_changed;
    std::function<void(NodeKey, std::vector<int16_t> &&values)> variables; // from address 0
};

// A piece of work for the network thread. `network` is null when the worker
// is stopping: the task must then say so to whoever waits for it.
using NetworkTask = std::function<void(client::Network *network)>;

class NetworkWorker
{
  public:
    // How often a watched robot's variables are read at most (Studio: 10 Hz).
    static constexpr std::chrono::milliseconds VARIABLES_PERIOD{ 100 };

    // Starts the thread, which connects to `targets` (transport.hpp syntax)
    // and keeps them connected; throws TransportError for a malformed one.
    NetworkWorker(asio::io_context &reports_context,
                  std::vector<std::string> targets,
                  NetworkReports reports,
                  client::Milliseconds answer_timeout = client::DEFAULT_ANSWER_TIMEOUT);
    // Stops the thread; tasks not yet run are run with a null network.
    ~NetworkWorker();
    NetworkWorker(const NetworkWorker &) = delete;
    NetworkWorker &operator=(const NetworkWorker &) = delete;

    // Queues `task`; tasks run one at a time, in order.
    void submit(NetworkTask task);

    // The robots whose variables to read, and how many words from address 0.
    void watch(std::map<NodeKey, uint16_t> words);

  private:
    void run();
    void run_tasks();
    void refresh_variables();
    void report_robots();
    void report_links();
    // Runs `function(reports)` on the server's io_context.
    template<typename Function>
    void report(Function &&function);

    asio::io_context &reports_context_;
    const std::vector<std::string> targets_;
    // Shared with the reports in flight, which may run after the worker is gone.
    const std::shared_ptr<const NetworkReports> reports_;
    const client::Milliseconds answer_timeout_;

    // Shared with the server's thread.
    std::mutex mutex_;
    std::deque<NetworkTask> tasks_;
    std::map<NodeKey, uint16_t> watched_;
    bool stopping_ = false;

    // The network thread's own (wake() excepted).
    std::unique_ptr<client::Network> network_;
    bool serving_ = true; // false once stopping: tasks get no network
    std::vector<client::ReceivedFrame> heard_;
    std::map<NodeKey, std::string> reported_robots_; // key -> what was last reported
    // Robots of unknown execution state -> when they were last asked for it.
    std::map<NodeKey, client::Clock::time_point> state_asked_;
    std::vector<LinkStatus> links_;
    std::string links_reported_;
    client::Clock::time_point next_variables_read_{};

    std::thread thread_;
};

} // namespace aseba::ide
