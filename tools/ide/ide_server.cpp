// The IDE server's state and its handlers (see ide_server.hpp).

#include "ide_server.hpp"

#include <algorithm>
#include <fstream>
#include <iostream>

#include <asio/post.hpp>

#include "binary_file.hpp"
#include "tools/client/message_text.hpp"
#include "tools/client/variables.hpp"

namespace aseba::ide
{

namespace
{

// Events a robot may send per second before the log keeps only a sample of
// them: the rate is still counted, the browsers are not flooded.
constexpr size_t MAX_LOGGED_EVENTS_PER_FLUSH = 2000;
// The window over which a robot's event rate is counted.
constexpr auto EVENT_RATE_WINDOW = std::chrono::seconds(5);

// Invalid UTF-8 (a robot's name, a script pasted from anywhere) is replaced,
// not thrown on.
std::string json_text(const Json &message)
{
    return message.dump(-1, ' ', false, Json::error_handler_t::replace);
}

int64_t milliseconds_since_epoch(std::chrono::system_clock::time_point time)
{
    return std::chrono::duration_cast<std::chrono::milliseconds>(time.time_since_epoch()).count();
}

std::string state_name(const std::optional<client::ExecutionState> &execution)
{
    return execution ? execution->name() : "unknown";
}

Json description_json(const TargetDescription &description)
{
    Json variables = Json::array();
    for (const NamedVariable &variable : description.named_variables)
        variables.push_back({ { "name", variable.name }, { "size", variable.size } });
    Json events = Json::array();
    for (const LocalEvent &event : description.local_events)
        events.push_back({ { "name", event.name }, { "description", event.description } });
    Json natives = Json::array();
    for (const NativeFunction &function : description.native_functions) {
        Json parameters = Json::array();
        for (const NativeParameter &parameter : function.parameters)
            parameters.push_back({ { "name", parameter.name }, { "size", parameter.size } });
        natives.push_back({ { "name", function.name },
                            { "description", function.description },
                            { "parameters", parameters } });
    }
    return { { "name", description.name },
             { "bytecodeSize", description.bytecode_size },
             { "variablesSize", description.variables_size },
             { "stackSize", description.stack_size },
             { "variables", variables },
             { "localEvents", events },
             { "natives", natives } };
}

Json compile_json(const CompileResult &result, const TargetDescription &description)
{
    Json json{ { "ok", result.ok },
               { "bytecodeSize", description.bytecode_size },
               { "variablesSize", description.variables_size } };
    if (result.ok) {
        json["bytecodeWords"] = result.bytecode.size();
        json["variableWords"] = result.allocated_variables;
    } else {
        json["error"] = { { "message", result.error.message },
                          { "line", result.error.has_position ? result.error.position.line : 0 },
                          { "column",
                            result.error.has_position ? result.error.position.column : 0 } };
    }
    return json;
}

Json variable_map_json(const std::vector<client::VariableLocation> &map)
{
    Json variables = Json::array();
    for (const client::VariableLocation &location : map)
        variables.push_back({ { "name", location.name },
                              { "address", location.address },
                              { "size", location.size },
                              { "user", !location.named } });
    return variables;
}

// A run-time error a node reported, with the line it happened on.
std::optional<Json> runtime_error_json(const client::Message &message,
                                       const client::CompiledProgram *program)
{
    std::string kind;
    uint16_t pc = 0;
    std::string text;
    if (const auto *bounds = std::get_if<client::ArrayAccessOutOfBounds>(&message)) {
        kind = "array-access-out-of-bounds";
        pc = bounds->pc;
        text = "index " + std::to_string(bounds->index) + " is out of an array of size " +
               std::to_string(bounds->size);
    } else if (const auto *division = std::get_if<client::DivisionByZero>(&message)) {
        kind = "division-by-zero";
        pc = division->pc;
        text = "division by zero";
    } else if (const auto *killed = std::get_if<client::EventExecutionKilled>(&message)) {
        kind = "event-execution-killed";
        pc = killed->pc;
        text = "the event handler was still running when the next event came, and was stopped";
    } else if (const auto *specific = std::get_if<client::NodeSpecificError>(&message)) {
        kind = "node-specific-error";
        pc = specific->pc;
        text = specific->message;
    } else {
        return std::nullopt;
    }
    unsigned line = program ? client::source_line_of(*program, pc) : 0;
    return Json{ { "kind", kind }, { "pc", pc }, { "line", line }, { "message", text } };
}

std::shared_ptr<client::CompiledProgram> compiled(NodeKey key,
                                                  const TargetDescription &description,
                                                  const CommonDefinitions &definitions,
                                                  const std::string &source)
{
    auto program = std::make_shared<client::CompiledProgram>();
    program->file_name = robot_name(key);
    program->source = source;
    program->definitions = definitions;
    program->result = compile(source, description, program->definitions);
    return program;
}

} // namespace

struct IdeServer::Robot {
    RobotSnapshot snapshot;
    bool present = false;        // on the network now
    bool seen_described = false; // described itself at least once
    // The program this server loaded and the robot runs, with its source.
    std::shared_ptr<const client::CompiledProgram> program;
    bool program_stored = false; // written to the robot's flash since loaded
    std::vector<unsigned> breakpoints;
    Json last_error; // null, or the last run-time error
    std::deque<client::Clock::time_point> recent_events;
    std::vector<int16_t> last_variables;

    double event_rate(client::Clock::time_point now)
    {
        while (!recent_events.empty() && now - recent_events.front() > EVENT_RATE_WINDOW)
            recent_events.pop_front();
        return double(recent_events.size()) /
               std::chrono::duration<double>(EVENT_RATE_WINDOW).count();
    }
};

struct IdeServer::Browser {
    std::set<NodeKey> watching;
    uint64_t skipped = 0; // updates not sent while it lagged
};

IdeServer::IdeServer(asio::io_context &io, IdeOptions options, std::vector<StaticFile> files)
  : io_(io)
  , options_(std::move(options))
  , log_timer_(io)
  , status_timer_(io)
{
    if (!options_.project_path.empty()) {
        workspace_.file_path = options_.project_path;
        std::ifstream probe(options_.project_path);
        if (probe) // a new file is created by the first save
            workspace_.open(options_.project_path, read_project_file(options_.project_path));
    }
    WebServerHandlers handlers;
    handlers.opened = [this](ConnectionId connection, const std::string &) { opened(connection); };
    handlers.received = [this](ConnectionId connection, std::string &&text) {
        received(connection, std::move(text));
    };
    handlers.closed = [this](ConnectionId connection) { closed(connection); };
    background_ = std::make_unique<BackgroundWorker>(io_);
    web_ = std::make_unique<WebServer>(io_, options_.web, std::move(files), std::move(handlers));

    NetworkReports reports;
    reports.frames = [this](std::vector<client::ReceivedFrame> &&frames) {
        heard(std::move(frames));
    };
    reports.robot_changed = [this](RobotSnapshot &&snapshot) {
        robot_changed(std::move(snapshot));
    };
    reports.robot_gone = [this](NodeKey key) { robot_gone(key); };
    reports.links_changed = [this](std::vector<LinkStatus> &&links) {
        links_changed(std::move(links));
    };
    reports.variables = [this](NodeKey key, std::vector<int16_t> &&values) {
        variables_read(key, std::move(values));
    };
    for (const std::string &target : options_.targets)
        links_.push_back(LinkStatus{ target, false, "connecting" });
    worker_ = std::make_unique<NetworkWorker>(
      io_, options_.targets, std::move(reports), options_.answer_timeout);
    if (!options_.arena_feed.empty()) {
        client::TargetAddress feed = client::parse_target(options_.arena_feed);
        if (feed.kind != client::TargetAddress::Kind::tcp)
            throw client::TransportError("the arena feed is a TCP address, not '" +
                                         options_.arena_feed + "'");
        ArenaReports arena_reports;
        arena_reports.arena = [this](Json &&geometry) {
            arena_ = std::move(geometry);
            broadcast({ { "type", "arena" }, { "arena", arena_ } }, Delivery::essential);
        };
        arena_reports.state = [this](Json &&state) { arena_state(std::move(state)); };
        arena_reports.gone = [this] {
            arena_ = nullptr;
            broadcast({ { "type", "arena" }, { "arena", nullptr } }, Delivery::essential);
        };
        arena_link_ =
          std::make_unique<ArenaLink>(io_, feed.host, feed.port, std::move(arena_reports));
    }
    schedule(log_timer_, LOG_PERIOD, &IdeServer::flush_log);
    schedule(status_timer_, STATUS_PERIOD, &IdeServer::send_status);
}

IdeServer::~IdeServer()
{
    worker_.reset();
}

uint16_t IdeServer::port() const
{
    return web_->port();
}

void IdeServer::stop()
{
    log_timer_.cancel();
    status_timer_.cancel();
    web_->stop();
}

void IdeServer::schedule(asio::steady_timer &timer,
                         std::chrono::milliseconds period,
                         void (IdeServer::*tick)())
{
    timer.expires_after(period);
    timer.async_wait([this, &timer, period, tick](const std::error_code &error) {
        if (error)
            return;
        (this->*tick)();
        schedule(timer, period, tick);
    });
}

// --- browsers ---------------------------------------------------------------

void IdeServer::opened(ConnectionId connection)
{
    browsers_[connection] = Browser{};
    send(connection, hello(), Delivery::essential);
}

void IdeServer::closed(ConnectionId connection)
{
    browsers_.erase(connection);
    update_watch();
}

void IdeServer::received(ConnectionId connection, std::string &&text)
{
    ParsedRequest parsed;
    try {
        parsed = parse_request(text);
    } catch (const RequestError &error) {
        reply_error(connection, request_id_of(text), std::string("bad request: ") + error.what());
        return;
    }
    try {
        std::visit([&](auto &request) { handle(connection, parsed.id, request); }, parsed.request);
    } catch (const std::exception &error) {
        reply_error(connection, parsed.id, error.what());
    }
}

Json IdeServer::hello() const
{
    Json robots = Json::array();
    for (const auto &[key, robot] : robots_)
        robots.push_back(robot_json(robot));
    Json scripts = Json::object();
    for (const auto &[key, source] : workspace_.scripts)
        scripts[robot_name(key)] = source;
    Json links = Json::array();
    for (const LinkStatus &link : links_)
        links.push_back({ { "target", link.target }, { "up", link.up }, { "error", link.error } });
    Json definitions = { { "events", Json::array() }, { "constants", Json::array() } };
    for (const GlobalEvent &event : workspace_.definitions.events)
        definitions["events"].push_back({ { "name", event.name }, { "size", event.size } });
    for (const Constant &constant : workspace_.definitions.constants)
        definitions["constants"].push_back(
          { { "name", constant.name }, { "value", constant.value } });
    Json waiting = Json::array();
    for (const AeslNode &program : workspace_.waiting)
        waiting.push_back({ { "name", program.name }, { "id", program.node_id } });
    return { { "type", "hello" },
             { "links", links },
             { "robots", robots },
             { "definitions", definitions },
             { "scripts", scripts },
             { "waitingPrograms", waiting },
             { "projectFile", workspace_.file_path },
             { "arena", arena_ },
             { "log", Json(log_history_) } };
}

Json IdeServer::robot_json(const Robot &robot) const
{
    const RobotSnapshot &snapshot = robot.snapshot;
    Json json{ { "robot", robot_name(snapshot.key) },
               { "id", snapshot.key.id },
               { "target", snapshot.key.target },
               { "name", snapshot.described ? snapshot.description.name : "" },
               { "present", robot.present },
               { "alive", robot.present && snapshot.alive },
               { "described", snapshot.described },
               { "compatible", snapshot.compatible },
               { "protocol", snapshot.protocol_version },
               { "state", robot.present ? state_name(snapshot.execution) : "offline" },
               { "breakpoints", robot.breakpoints },
               { "lastError", robot.last_error } };
    if (snapshot.execution) {
        json["pc"] = snapshot.execution->pc;
        json["line"] = robot.program && !snapshot.execution->running()
                         ? client::source_line_of(*robot.program, snapshot.execution->pc)
                         : 0;
    }
    if (snapshot.described) {
        json["description"] = description_json(snapshot.description);
        json["variables"] =
          variable_map_json(client::variable_map(snapshot.description, robot.program.get()));
    }
    if (robot.program)
        json["program"] = { { "source", robot.program->source },
                            { "bytecodeWords", robot.program->result.bytecode.size() },
                            { "variableWords", robot.program->result.allocated_variables },
                            { "stored", robot.program_stored } };
    return json;
}

void IdeServer::deliver(ConnectionId connection,
                        Browser &browser,
                        const std::string &text,
                        Delivery delivery)
{
    // A browser that lagged is told how many updates it missed, once it
    // reads again.
    if (delivery == Delivery::skippable && browser.skipped > 0 &&
        web_->buffered_bytes(connection) < options_.web.max_buffered_bytes / 2 &&
        web_->send(connection,
                   Json{ { "type", "skipped" }, { "count", browser.skipped } }.dump(),
                   Delivery::essential))
        browser.skipped = 0;
    if (!web_->send(connection, text, delivery) && delivery == Delivery::skippable)
        browser.skipped++;
}

void IdeServer::send(ConnectionId connection, const Json &message, Delivery delivery)
{
    auto browser = browsers_.find(connection);
    if (browser != browsers_.end())
        deliver(connection, browser->second, json_text(message), delivery);
}

void IdeServer::broadcast(const Json &message, Delivery delivery, const BrowserFilter &to)
{
    if (browsers_.empty())
        return;
    std::string text = json_text(message);
    for (auto &[connection, browser] : browsers_)
        if (!to || to(connection, browser))
            deliver(connection, browser, text, delivery);
}

void IdeServer::reply(ConnectionId connection, uint64_t id, Json &&payload)
{
    if (id == 0)
        return;
    payload["type"] = "reply";
    payload["id"] = id;
    if (!payload.contains("ok"))
        payload["ok"] = true;
    send(connection, payload, Delivery::essential);
}

void IdeServer::reply_error(ConnectionId connection, uint64_t id, const std::string &error)
{
    send(connection,
         Json{ { "type", "reply" }, { "id", id }, { "ok", false }, { "error", error } },
         Delivery::essential);
}

void IdeServer::on_network(std::function<Json(client::Network &)> work,
                           std::function<void(Json &&, const std::string &)> done)
{
    worker_->submit(
      [this, work = std::move(work), done = std::move(done)](client::Network *network) {
          Json result;
          std::string error;
          if (network == nullptr) {
              error = "the IDE is stopping";
          } else {
              try {
                  result = work(*network);
              } catch (const std::exception &exception) {
                  error = exception.what();
              }
          }
          asio::post(io_, [done, result = std::move(result), error]() mutable {
              done(std::move(result), error);
          });
      });
}

// --- the network --------------------------------------------------------------

void IdeServer::links_changed(std::vector<LinkStatus> &&links)
{
    // Said in the terminal too: whoever started the IDE learns there that a
    // target is wrong, without opening the page.
    for (size_t i = 0; i < links.size(); i++) {
        const LinkStatus &link = links[i];
        const LinkStatus *before = i < links_.size() ? &links_[i] : nullptr;
        if (link.up && before && !before->up)
            std::cerr << "aseba-ide: " << link.target << ": connected\n";
        else if (!link.up && !link.error.empty() &&
                 (!before || before->up || before->error != link.error))
            std::cerr << "aseba-ide: " << link.target << ": " << link.error << " (trying again)\n";
    }
    links_ = std::move(links);
    Json json = Json::array();
    for (const LinkStatus &link : links_)
        json.push_back({ { "target", link.target }, { "up", link.up }, { "error", link.error } });
    broadcast({ { "type", "links" }, { "links", json } }, Delivery::essential);
}

void IdeServer::robot_changed(RobotSnapshot &&snapshot)
{
    NodeKey key = snapshot.key;
    Robot &robot = robots_[key];
    bool newly_described = snapshot.described && (!robot.present || !robot.snapshot.described);
    bool first_described = newly_described && !robot.seen_described;
    robot.seen_described = robot.seen_described || snapshot.described;
    robot.snapshot = std::move(snapshot);
    robot.present = true;
    if (newly_described && workspace_.match(key, robot.snapshot.description.name)) {
        broadcast({ { "type", "script" },
                    { "robot", robot_name(key) },
                    { "source", workspace_.scripts[key] } },
                  Delivery::essential);
        // Only at a robot's first appearance: one that comes back has
        // rebooted into whatever its flash holds.
        if (options_.robots_run_project && first_described && robot.snapshot.compatible) {
            std::shared_ptr<const client::CompiledProgram> program =
              compile_for(robot, workspace_.scripts[key]);
            if (program->result.ok) {
                robot.program = program;
                on_network(
                  [key, program](client::Network &network) {
                      network.set_program(key, program);
                      return Json();
                  },
                  [](Json &&, const std::string &) {});
            }
        }
    }
    broadcast({ { "type", "robot" }, { "robot", robot_json(robot) } }, Delivery::essential);
    update_watch();
}

void IdeServer::robot_gone(NodeKey key)
{
    auto found = robots_.find(key);
    if (found == robots_.end())
        return;
    Robot &robot = found->second;
    robot.present = false;
    // When it comes back it runs what its flash holds, not what we loaded.
    if (!robot.program_stored)
        robot.program.reset();
    broadcast({ { "type", "robot" }, { "robot", robot_json(robot) } }, Delivery::essential);
}

void IdeServer::variables_read(NodeKey key, std::vector<int16_t> &&values)
{
    auto found = robots_.find(key);
    if (found == robots_.end())
        return;
    found->second.last_variables = values;
    Json message{ { "type", "variables" },
                  { "robot", robot_name(key) },
                  { "time", milliseconds_since_epoch(std::chrono::system_clock::now()) },
                  { "values", values } };
    broadcast(message, Delivery::skippable, [key](ConnectionId, const Browser &browser) {
        return browser.watching.count(key) > 0;
    });
}

// The feed names robots by node id; they are the first target's.
void IdeServer::arena_state(Json &&state)
{
    Json robots = Json::array();
    for (Json &robot : state["robots"]) {
        if (!robot.is_object() || !robot["id"].is_number_unsigned())
            continue;
        robot["robot"] = robot_name(NodeKey{ 0, robot["id"].get<uint16_t>() });
        robots.push_back(std::move(robot));
    }
    broadcast(
      { { "type", "arena-state" }, { "time", state.value("time", 0.0) }, { "robots", robots } },
      Delivery::skippable);
}

void IdeServer::heard(std::vector<client::ReceivedFrame> &&frames)
{
    for (client::ReceivedFrame &frame : frames) {
        NodeKey key{ frame.target, frame.frame.source };
        bool from_host = frame.frame.source == client::HOST_SOURCE;
        auto robot = from_host ? robots_.end() : robots_.find(key);
        Json entry{ { "time", milliseconds_since_epoch(frame.wall_time) },
                    { "source", from_host ? "host" : robot_name(key) } };
        if (!frame.message) {
            entry["kind"] = "malformed";
            entry["message"] = frame.error;
            log(std::move(entry));
            continue;
        }
        if (const auto *event = std::get_if<client::UserEvent>(&*frame.message)) {
            entry["kind"] = "event";
            entry["event"] = event->id;
            if (event->id < workspace_.definitions.events.size())
                entry["name"] = workspace_.definitions.events[event->id].name;
            entry["args"] = event->arguments;
            if (robot != robots_.end())
                robot->second.recent_events.push_back(frame.time);
            log(std::move(entry));
            continue;
        }
        if (robot == robots_.end())
            continue;
        std::optional<Json> error = runtime_error_json(*frame.message, robot->second.program.get());
        if (!error)
            continue;
        (*error)["time"] = entry["time"];
        robot->second.last_error = *error;
        broadcast(
          { { "type", "runtime-error" }, { "robot", robot_name(key) }, { "error", *error } },
          Delivery::essential);
        entry["kind"] = "error";
        entry["error"] = std::move(*error);
        log(std::move(entry));
    }
}

void IdeServer::log(Json &&entry)
{
    if (log_pending_.size() < MAX_LOGGED_EVENTS_PER_FLUSH)
        log_pending_.push_back(entry);
    log_history_.push_back(std::move(entry));
    while (log_history_.size() > LOG_HISTORY)
        log_history_.pop_front();
}

void IdeServer::flush_log()
{
    if (log_pending_.empty())
        return;
    broadcast({ { "type", "log" }, { "entries", log_pending_ } }, Delivery::skippable);
    log_pending_ = Json::array();
}

void IdeServer::send_status()
{
    auto now = client::Clock::now();
    Json rates = Json::object();
    for (auto &[key, robot] : robots_)
        rates[robot_name(key)] = robot.event_rate(now);
    broadcast({ { "type", "status" }, { "eventRates", rates } }, Delivery::skippable);
}

// Reads, for every robot some browser shows, its named variables and those
// of the program it runs.
void IdeServer::update_watch()
{
    std::map<NodeKey, uint16_t> words;
    for (const auto &[connection, browser] : browsers_) {
        for (NodeKey key : browser.watching) {
            auto robot = robots_.find(key);
            if (robot == robots_.end() || !robot->second.present ||
                !robot->second.snapshot.described)
                continue;
            uint16_t used = 0;
            for (const client::VariableLocation &location : client::variable_map(
                   robot->second.snapshot.description, robot->second.program.get()))
                used = std::max<uint16_t>(used, location.address + location.size);
            words[key] = used;
        }
    }
    worker_->watch(std::move(words));
}

// --- requests ------------------------------------------------------------------

IdeServer::Robot &IdeServer::ready_robot(NodeKey key)
{
    auto found = robots_.find(key);
    if (found == robots_.end() || !found->second.present)
        throw std::runtime_error("robot " + robot_name(key) + " is not on the network");
    Robot &robot = found->second;
    if (!robot.snapshot.described)
        throw std::runtime_error("robot " + robot_name(key) + " has not described itself yet");
    if (!robot.snapshot.compatible)
        throw std::runtime_error("robot " + robot_name(key) + " speaks protocol " +
                                 std::to_string(robot.snapshot.protocol_version) + ", not 4 or 5");
    return robot;
}

std::shared_ptr<client::CompiledProgram> IdeServer::compile_for(const Robot &robot,
                                                                const std::string &source) const
{
    return compiled(robot.snapshot.key, robot.snapshot.description, workspace_.definitions, source);
}

IdeServer::CompileJob IdeServer::compile_job(const Robot &robot, const std::string &source)
{
    return { robot.snapshot.key, robot.snapshot.description, source, nullptr };
}

void IdeServer::compile_then(ConnectionId connection,
                             uint64_t id,
                             CompileJobs jobs,
                             std::function<void(CompileJobs &)> done)
{
    auto shared = std::make_shared<CompileJobs>(std::move(jobs));
    background_->run(
      [shared, definitions = workspace_.definitions] {
          for (CompileJob &job : *shared)
              job.program = compiled(job.robot, job.description, definitions, job.source);
      },
      [this, connection, id, shared, done = std::move(done)](const std::string &error) {
          if (!error.empty())
              return reply_error(connection, id, error);
          done(*shared);
      });
}

std::vector<std::pair<unsigned, std::optional<uint16_t>>> IdeServer::breakpoint_addresses(
  const client::CompiledProgram &program,
  const std::vector<unsigned> &lines)
{
    std::vector<std::pair<unsigned, std::optional<uint16_t>>> addresses;
    for (unsigned line : lines)
        addresses.emplace_back(line, client::address_of_line(program, line));
    return addresses;
}

void IdeServer::remember_script(ConnectionId from, NodeKey key, const std::string &source)
{
    // What a page can make the server keep: a script for each robot that is
    // or was on the network, and all of them within a budget.
    if (robots_.count(key) == 0)
        throw std::runtime_error("robot " + robot_name(key) +
                                 " is not on the network and never was: its script is not kept");
    size_t total = source.size();
    for (const auto &[other, text] : workspace_.scripts)
        total += other == key ? 0 : text.size();
    if (total > options_.max_script_bytes)
        throw std::runtime_error(
          "the robots' scripts would take " + std::to_string(total) + " bytes, more than the " +
          std::to_string(options_.max_script_bytes) + " the IDE keeps: the script of " +
          robot_name(key) + " is not kept");
    std::string &script = workspace_.scripts[key];
    if (script == source)
        return;
    script = source;
    broadcast({ { "type", "script" }, { "robot", robot_name(key) }, { "source", source } },
              Delivery::essential,
              [from](ConnectionId connection, const Browser &) { return connection != from; });
}

void IdeServer::handle(ConnectionId connection, uint64_t id, CompileRequest &request)
{
    if (request.remember)
        remember_script(connection, request.robot, request.source);
    Robot &robot = ready_robot(request.robot);
    compile_then(
      connection,
      id,
      { compile_job(robot, request.source) },
      [this, connection, id](CompileJobs &jobs) {
          reply(connection,
                id,
                { { "compile", compile_json(jobs[0].program->result, jobs[0].description) } });
      });
}

void IdeServer::handle(ConnectionId connection, uint64_t id, ScriptRequest &request)
{
    remember_script(connection, request.robot, request.source);
    reply(connection, id, {});
}

void IdeServer::handle(ConnectionId connection, uint64_t id, LoadRequest &request)
{
    CompileJobs jobs;
    std::vector<std::vector<unsigned>> breakpoints;
    for (LoadRequest::Program &entry : request.programs) {
        remember_script(connection, entry.robot, entry.source);
        Robot &robot = ready_robot(entry.robot);
        robot.breakpoints = entry.breakpoints;
        jobs.push_back(compile_job(robot, entry.source));
        breakpoints.push_back(entry.breakpoints);
    }
    bool run = request.run;
    // Compile for everyone first: one bad program loads nothing.
    compile_then(connection,
                 id,
                 std::move(jobs),
                 [this, connection, id, breakpoints, run](CompileJobs &compiled_jobs) {
                     std::vector<Upload> uploads;
                     Json failures = Json::array();
                     for (size_t i = 0; i < compiled_jobs.size(); i++) {
                         const CompileJob &job = compiled_jobs[i];
                         if (!job.program->result.ok) {
                             Json failure = compile_json(job.program->result, job.description);
                             failure["robot"] = robot_name(job.robot);
                             failures.push_back(failure);
                             continue;
                         }
                         uploads.push_back({ job.robot,
                                             job.program,
                                             breakpoint_addresses(*job.program, breakpoints[i]) });
                     }
                     if (!failures.empty()) {
                         reply(connection,
                               id,
                               { { "ok", false },
                                 { "error", "a program does not compile: nothing was loaded" },
                                 { "failures", failures } });
                         return;
                     }
                     upload(connection, id, std::move(uploads), run);
                 });
}

void IdeServer::upload(ConnectionId connection, uint64_t id, std::vector<Upload> uploads, bool run)
{
    on_network(
      [uploads, run](client::Network &network) {
          Json results = Json::array();
          for (const Upload &upload : uploads) {
              Json result{ { "robot", robot_name(upload.key) } };
              try {
                  network.upload(upload.key, upload.program->result.bytecode);
                  network.set_program(upload.key, upload.program);
                  network.clear_all_breakpoints(upload.key);
                  Json breakpoints = Json::array();
                  for (const auto &[line, address] : upload.breakpoints)
                      breakpoints.push_back(
                        { { "line", line },
                          { "set", address && network.set_breakpoint(upload.key, *address) } });
                  result["breakpoints"] = breakpoints;
                  client::ExecutionState state =
                    run ? network.run(upload.key) : network.execution_state(upload.key);
                  result["state"] = state.name();
                  result["ok"] = true;
              } catch (const std::exception &error) {
                  result["ok"] = false;
                  result["error"] = error.what();
              }
              results.push_back(result);
          }
          return results;
      },
      [this, connection, id, uploads](Json &&results, const std::string &error) {
          if (!error.empty())
              return reply_error(connection, id, error);
          bool all_ok = true;
          for (size_t i = 0; i < uploads.size(); i++) {
              if (!results[i]["ok"].get<bool>()) {
                  all_ok = false;
                  continue;
              }
              auto robot = robots_.find(uploads[i].key);
              if (robot == robots_.end())
                  continue;
              robot->second.program = uploads[i].program;
              robot->second.program_stored = false;
              robot->second.last_error = nullptr;
              broadcast({ { "type", "robot" }, { "robot", robot_json(robot->second) } },
                        Delivery::essential);
          }
          update_watch();
          reply(connection, id, { { "ok", all_ok }, { "results", std::move(results) } });
      });
}

void IdeServer::handle(ConnectionId connection, uint64_t id, ControlRequest &request)
{
    std::vector<NodeKey> robots;
    for (NodeKey key : request.robots) {
        ready_robot(key);
        robots.push_back(key);
    }
    Action action = request.action;
    on_network(
      [robots, action](client::Network &network) {
          Json results = Json::array();
          for (NodeKey key : robots) {
              Json result{ { "robot", robot_name(key) } };
              try {
                  std::optional<client::ExecutionState> state;
                  switch (action) {
                  case Action::run: state = network.run(key); break;
                  case Action::pause: state = network.pause(key); break;
                  case Action::stop: state = network.stop(key); break;
                  case Action::reset: state = network.reset(key); break;
                  case Action::step:
                      state =
                        network.node(key).program ? network.step_line(key) : network.step(key);
                      break;
                  case Action::store: network.write_bytecode(key); break;
                  case Action::reboot: network.reboot(key); break;
                  }
                  if (state)
                      result["state"] = state->name();
                  result["ok"] = true;
              } catch (const std::exception &error) {
                  result["ok"] = false;
                  result["error"] = error.what();
              }
              results.push_back(result);
          }
          return results;
      },
      [this, connection, id, action, robots](Json &&results, const std::string &error) {
          if (!error.empty())
              return reply_error(connection, id, error);
          bool all_ok = true;
          for (size_t i = 0; i < robots.size(); i++) {
              bool ok = results[i]["ok"].get<bool>();
              all_ok = all_ok && ok;
              auto robot = robots_.find(robots[i]);
              if (!ok || robot == robots_.end())
                  continue;
              if (action == Action::store)
                  robot->second.program_stored = robot->second.program != nullptr;
              // Rebooted, it runs what its flash holds, not what we loaded.
              else if (action == Action::reboot && !robot->second.program_stored)
                  robot->second.program.reset();
              else
                  continue;
              broadcast({ { "type", "robot" }, { "robot", robot_json(robot->second) } },
                        Delivery::essential);
          }
          reply(connection, id, { { "ok", all_ok }, { "results", std::move(results) } });
      });
}

void IdeServer::handle(ConnectionId connection, uint64_t id, BreakpointsRequest &request)
{
    auto found = robots_.find(request.robot);
    if (found == robots_.end())
        throw std::runtime_error("robot " + robot_name(request.robot) + " is not on the network");
    Robot &robot = found->second;
    robot.breakpoints = request.lines;
    broadcast({ { "type", "robot" }, { "robot", robot_json(robot) } },
              Delivery::essential,
              [connection](ConnectionId other, const Browser &) { return other != connection; });
    if (!robot.present || !robot.program) {
        Json lines = Json::array();
        for (unsigned line : request.lines)
            lines.push_back({ { "line", line }, { "set", false } });
        reply(connection, id, { { "breakpoints", lines }, { "pending", true } });
        return;
    }
    NodeKey key = request.robot;
    auto addresses = breakpoint_addresses(*robot.program, request.lines);
    on_network(
      [key, addresses](client::Network &network) {
          network.clear_all_breakpoints(key);
          Json lines = Json::array();
          for (const auto &[line, address] : addresses)
              lines.push_back(
                { { "line", line }, { "set", address && network.set_breakpoint(key, *address) } });
          return lines;
      },
      [this, connection, id](Json &&lines, const std::string &error) {
          if (!error.empty())
              return reply_error(connection, id, error);
          reply(connection, id, { { "breakpoints", std::move(lines) } });
      });
}

void IdeServer::handle(ConnectionId connection, uint64_t id, SetVariableRequest &request)
{
    Robot &robot = ready_robot(request.robot);
    std::vector<client::VariableLocation> map =
      client::variable_map(robot.snapshot.description, robot.program.get());
    auto location =
      std::find_if(map.begin(), map.end(), [&](const client::VariableLocation &entry) {
          return entry.name == request.name;
      });
    if (location == map.end())
        throw std::runtime_error("robot " + robot_name(request.robot) + " has no variable '" +
                                 request.name + "'");
    if (request.index + request.values.size() > location->size)
        throw std::runtime_error("'" + request.name + "' has " + std::to_string(location->size) +
                                 (location->size == 1 ? " word" : " words") + ": cannot write " +
                                 std::to_string(request.values.size()) + " from index " +
                                 std::to_string(request.index));
    NodeKey key = request.robot;
    uint16_t address = uint16_t(location->address + request.index);
    std::vector<int16_t> values = request.values;
    on_network(
      [key, address, values](client::Network &network) {
          network.write_variables(key, address, values);
          return Json::object();
      },
      [this, connection, id](Json &&, const std::string &error) {
          if (!error.empty())
              return reply_error(connection, id, error);
          reply(connection, id, {});
      });
}

void IdeServer::handle(ConnectionId connection, uint64_t id, EmitRequest &request)
{
    const std::vector<GlobalEvent> &events = workspace_.definitions.events;
    auto event = std::find_if(events.begin(), events.end(), [&](const GlobalEvent &known) {
        return known.name == request.event;
    });
    if (event == events.end())
        throw std::runtime_error("no global event '" + request.event + "' is declared");
    if (request.arguments.size() > event->size)
        throw std::runtime_error("'" + request.event + "' takes " + std::to_string(event->size) +
                                 " arguments, not " + std::to_string(request.arguments.size()));
    std::vector<int16_t> arguments = request.arguments;
    arguments.resize(event->size, 0);
    uint16_t event_id = uint16_t(event - events.begin());
    std::string name = event->name;
    on_network(
      [event_id, arguments](client::Network &network) {
          network.emit(event_id, arguments);
          return Json::object();
      },
      [this, connection, id, event_id, arguments, name](Json &&, const std::string &error) {
          if (!error.empty())
              return reply_error(connection, id, error);
          log({ { "time", milliseconds_since_epoch(std::chrono::system_clock::now()) },
                { "source", "ide" },
                { "kind", "event" },
                { "event", event_id },
                { "name", name },
                { "args", arguments } });
          reply(connection, id, {});
      });
}

void IdeServer::handle(ConnectionId connection, uint64_t id, DefinitionsRequest &request)
{
    workspace_.definitions = std::move(request.definitions);
    Json definitions = hello()["definitions"];
    broadcast({ { "type", "definitions" }, { "definitions", definitions } }, Delivery::essential);
    reply(connection, id, {});
}

void IdeServer::handle(ConnectionId connection, uint64_t id, WatchRequest &request)
{
    browsers_[connection].watching =
      std::set<NodeKey>(request.robots.begin(), request.robots.end());
    update_watch();
    reply(connection, id, {});
}

void IdeServer::handle(ConnectionId connection, uint64_t id, OpenProjectRequest &request)
{
    auto project = std::make_shared<AeslProject>();
    background_->run(
      [project, name = request.file_name, content = std::move(request.content)] {
          *project = read_project(name, content);
      },
      [this, connection, id, project](const std::string &error) {
          if (!error.empty())
              return reply_error(connection, id, error);
          open_project(connection, id, std::move(*project));
      });
}

void IdeServer::open_project(ConnectionId connection, uint64_t id, AeslProject &&project)
{
    workspace_.open(std::move(project));
    std::map<NodeKey, std::string> names;
    for (const auto &[key, robot] : robots_)
        if (robot.present && robot.snapshot.described)
            names[key] = robot.snapshot.description.name;
    Json matched = Json::array();
    for (NodeKey key : workspace_.assign(names))
        matched.push_back(robot_name(key));
    Json welcome = hello();
    broadcast({ { "type", "project" },
                { "definitions", welcome["definitions"] },
                { "scripts", welcome["scripts"] },
                { "waitingPrograms", welcome["waitingPrograms"] },
                { "projectFile", workspace_.file_path } },
              Delivery::essential);
    reply(connection,
          id,
          { { "matched", matched }, { "waitingPrograms", welcome["waitingPrograms"] } });
}

void IdeServer::handle(ConnectionId connection, uint64_t id, SaveProjectRequest &request)
{
    std::map<NodeKey, std::string> names;
    for (const auto &[key, robot] : robots_)
        if (robot.snapshot.described)
            names[key] = robot.snapshot.description.name;
    std::string text = workspace_.to_aesl(names);
    Json result{ { "content", text } };
    if (request.to_server_file) {
        if (workspace_.file_path.empty())
            throw std::runtime_error("the IDE was started without a project file (--project FILE)");
        write_project_file(workspace_.file_path, text);
        result["savedTo"] = workspace_.file_path;
    }
    reply(connection, id, std::move(result));
}

void IdeServer::handle(ConnectionId connection, uint64_t id, BytecodeRequest &request)
{
    Robot &robot = ready_robot(request.robot);
    compile_then(connection,
                 id,
                 { compile_job(robot, request.source) },
                 [this, connection, id](CompileJobs &jobs) {
                     const CompileJob &job = jobs[0];
                     if (!job.program->result.ok)
                         return reply_error(connection,
                                            id,
                                            "the program does not compile: " +
                                              job.program->result.error.message);
                     save_binary(
                       connection, id, job.robot, job.description, job.program->result.bytecode);
                 });
}

void IdeServer::save_binary(ConnectionId connection,
                            uint64_t id,
                            NodeKey key,
                            const TargetDescription &description,
                            const std::vector<uint16_t> &bytecode)
{
    on_network(
      [key, description](client::Network &network) {
          // .abo files carry the robot's product id and firmware version.
          Json identity = Json::object();
          std::vector<client::VariableLocation> map = client::variable_map(description, nullptr);
          for (const char *name : { "_productId", "_fwversion" })
              for (const client::VariableLocation &location : map)
                  if (location.name == name)
                      identity[name] = network.read_variables(key, location.address, 1).at(0);
          return identity;
      },
      [this, connection, id, key, description, bytecode](Json &&identity,
                                                         const std::string &error) {
          if (!error.empty())
              return reply_error(connection, id, error);
          BinaryIdentity binary{ key.id,
                                 uint16_t(identity.value("_productId", 0)),
                                 uint16_t(identity.value("_fwversion", 0)) };
          reply(connection,
                id,
                { { "fileName", description.name + "-" + std::to_string(key.id) + ".abo" },
                  { "base64", base64(binary_file(description, binary, bytecode)) } });
      });
}

} // namespace aseba::ide
