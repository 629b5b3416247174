// The group IDE's server: between the browsers (WebServer) and the robots
// (NetworkWorker). It holds what every browser tab shares: the robots as the
// network shows them, the project (global events, constants, each robot's
// script, breakpoints), the programs it loaded, the event log; it compiles
// while the user types, against each robot's own description, and turns
// requests into commands for the robots. All of it runs on one thread, the
// io_context's; only NetworkWorker's tasks run elsewhere.

#pragma once

#include <chrono>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <asio/io_context.hpp>
#include <asio/steady_timer.hpp>
#include <nlohmann/json.hpp>

#include "arena_link.hpp"
#include "background_worker.hpp"
#include "network_worker.hpp"
#include "requests.hpp"
#include "web_server.hpp"
#include "workspace.hpp"

namespace aseba::ide
{

using Json = nlohmann::json;

struct IdeOptions {
    std::vector<std::string> targets; // Aseba networks, transport.hpp syntax
    WebServerOptions web;
    std::string project_path; // an .aesl file to open and save to, or empty
    // The robots already run the project's programs (epuck-emu --load of the
    // same file): a robot's program is known from its first description, as
    // if this IDE had loaded it, without an upload.
    bool robots_run_project = false;
    // The arena feed of the first target's simulated robots (tcp:HOST;PORT
    // or HOST:PORT), or empty.
    std::string arena_feed;
    client::Milliseconds answer_timeout = client::DEFAULT_ANSWER_TIMEOUT;
    // What the robots' scripts may take together, in bytes: what any page
    // can make the server keep (a script is kept only for a robot that is
    // or was on the network, each at most MAX_SCRIPT_BYTES).
    size_t max_script_bytes = 16 * 1024 * 1024;
};

class IdeServer
{
  public:
    // How often the event log goes to the browsers, in one message.
    static constexpr std::chrono::milliseconds LOG_PERIOD{ 50 };
    // How often the robots' event rates go to the browsers.
    static constexpr std::chrono::milliseconds STATUS_PERIOD{ 500 };
    // Entries of the event log a new browser tab receives.
    static constexpr size_t LOG_HISTORY = 2000;

    // Opens the project (if any), listens and starts talking to the robots.
    // Throws WebServerError or ProjectError.
    IdeServer(asio::io_context &io, IdeOptions options, std::vector<StaticFile> files);
    ~IdeServer();

    // The port the page is served on.
    uint16_t port() const;

    // Closes every browser and stops listening; io.run() then returns once
    // the network thread is stopped by the destructor.
    void stop();

  private:
    struct Robot;
    struct Browser;

    // From the browsers.
    void opened(ConnectionId connection);
    void received(ConnectionId connection, std::string &&text);
    void closed(ConnectionId connection);

    // From the network.
    void heard(std::vector<client::ReceivedFrame> &&frames);
    void robot_changed(RobotSnapshot &&snapshot);
    void robot_gone(NodeKey key);
    void links_changed(std::vector<LinkStatus> &&links);
    void variables_read(NodeKey key, std::vector<int16_t> &&values);

    // From the arena feed.
    void arena_state(Json &&state);

    // One handler per request type; each replies now or when the robots
    // have answered.
    void handle(ConnectionId connection, uint64_t id, CompileRequest &request);
    void handle(ConnectionId connection, uint64_t id, LoadRequest &request);
    void handle(ConnectionId connection, uint64_t id, ControlRequest &request);
    void handle(ConnectionId connection, uint64_t id, BreakpointsRequest &request);
    void handle(ConnectionId connection, uint64_t id, SetVariableRequest &request);
    void handle(ConnectionId connection, uint64_t id, EmitRequest &request);
    void handle(ConnectionId connection, uint64_t id, DefinitionsRequest &request);
    void handle(ConnectionId connection, uint64_t id, WatchRequest &request);
    void handle(ConnectionId connection, uint64_t id, ScriptRequest &request);
    void handle(ConnectionId connection, uint64_t id, OpenProjectRequest &request);
    void handle(ConnectionId connection, uint64_t id, SaveProjectRequest &request);
    void handle(ConnectionId connection, uint64_t id, BytecodeRequest &request);

    // Runs `work` on the network thread, then `done` here with its result or
    // the error it threw (also "the network is down").
    void on_network(std::function<Json(client::Network &)> work,
                    std::function<void(Json &&result, const std::string &error)> done);

    // A robot that can take a program now, or an exception saying why not.
    Robot &ready_robot(NodeKey key);
    // Compiles `source` for `robot` with the project's definitions.
    std::shared_ptr<client::CompiledProgram> compile_for(const Robot &robot,
                                                         const std::string &source) const;

    // A program to compile for a robot, off the thread that serves pages.
    struct CompileJob {
        NodeKey robot;
        TargetDescription description;
        std::string source;
        std::shared_ptr<client::CompiledProgram> program; // once compiled
    };
    using CompileJobs = std::vector<CompileJob>;
    static CompileJob compile_job(const Robot &robot, const std::string &source);
    // Compiles `jobs` on the background thread with the project's
    // definitions as they are now, then calls `done` here (or replies with
    // the error to request `id`).
    void compile_then(ConnectionId connection,
                      uint64_t id,
                      CompileJobs jobs,
                      std::function<void(CompileJobs &)> done);

    // A compiled program on its way to its robot, with its breakpoints.
    struct Upload {
        NodeKey key;
        std::shared_ptr<const client::CompiledProgram> program;
        std::vector<std::pair<unsigned, std::optional<uint16_t>>> breakpoints;
    };
    // Loads `uploads` (and runs them if `run`), then replies to `id`.
    void upload(ConnectionId connection, uint64_t id, std::vector<Upload> uploads, bool run);
    // Replies to `id` with `bytecode` as Studio's .abo file for robot `key`.
    void save_binary(ConnectionId connection,
                     uint64_t id,
                     NodeKey key,
                     const TargetDescription &description,
                     const std::vector<uint16_t> &bytecode);
    // Makes `project` the one every page edits; replies to `id`.
    void open_project(ConnectionId connection, uint64_t id, AeslProject &&project);
    // Breakpoint lines and their addresses in `program`.
    static std::vector<std::pair<unsigned, std::optional<uint16_t>>> breakpoint_addresses(
      const client::CompiledProgram &program,
      const std::vector<unsigned> &lines);
    void remember_script(ConnectionId from, NodeKey key, const std::string &source);
    void update_watch();
    void log(Json &&entry);

    void reply(ConnectionId connection, uint64_t id, Json &&payload);
    void reply_error(ConnectionId connection, uint64_t id, const std::string &error);
    using BrowserFilter = std::function<bool(ConnectionId, const Browser &)>;
    void deliver(ConnectionId connection,
                 Browser &browser,
                 const std::string &text,
                 Delivery delivery);
    void send(ConnectionId connection, const Json &message, Delivery delivery);
    // To every browser, or to those `to` accepts.
    void broadcast(const Json &message, Delivery delivery, const BrowserFilter &to = {});
    Json robot_json(const Robot &robot) const;
    Json hello() const;
    void flush_log();
    void send_status();
    void schedule(asio::steady_timer &timer,
                  std::chrono::milliseconds period,
                  void (IdeServer::*tick)());

    asio::io_context &io_;
    IdeOptions options_;
    Workspace workspace_;
    std::map<NodeKey, Robot> robots_;
    std::map<ConnectionId, Browser> browsers_;
    std::vector<LinkStatus> links_;
    std::deque<Json> log_history_;
    Json log_pending_ = Json::array();
    asio::steady_timer log_timer_;
    asio::steady_timer status_timer_;
    Json arena_; // the arena's geometry, or null
    std::unique_ptr<ArenaLink> arena_link_;
    std::unique_ptr<WebServer> web_;
    std::unique_ptr<BackgroundWorker> background_;
    // Last: it is stopped first, before what its reports would touch.
    std::unique_ptr<NetworkWorker> worker_;
};

} // namespace aseba::ide
