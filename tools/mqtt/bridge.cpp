// The bridge's loop: frames of the networks to the broker, the broker's
// messages to the networks, presence and watched variables.

#include "bridge.hpp"

#include <algorithm>
#include <random>
#include <sstream>

#include "tools/client/variables.hpp"

namespace aseba::mqtt
{

namespace
{

constexpr Milliseconds POLL_PERIOD{ 50 };     // the longest the loop sleeps
constexpr unsigned LOG_LINES_PER_SECOND = 10; // problems with input, then a summary
constexpr int EVENT_QOS = 1;                  // an event is delivered at least once (docs/mqtt.md)
constexpr int COMMAND_QOS = 1;

int64_t unix_time_ms()
{
    return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

bool is_number(const std::string &text)
{
    return !text.empty() && text.size() <= 5 &&
           std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

} // namespace

std::string new_session_id()
{
    std::random_device device;
    std::mt19937_64 generator((uint64_t(device()) << 32) ^ device() ^
                              uint64_t(client::Clock::now().time_since_epoch().count()));
    std::ostringstream text;
    text << std::hex;
    text.width(16);
    text.fill('0');
    text << generator();
    return text.str();
}

Bridge::Bridge(BridgeOptions options, std::ostream &log)
  : options_(std::move(options))
  , log_(log)
  , session_(new_session_id())
  , network_(std::make_unique<client::Network>())
{
    definitions_ = options_.program ? options_.program->definitions : options_.declared;
    // Frames are handled after each poll, not inside it: passing one on
    // sends on the links that the poll is reading.
    network_->set_listener([this](const client::ReceivedFrame &frame) {
        if (frame.message && std::holds_alternative<client::UserEvent>(*frame.message))
            heard_.push_back(frame);
    });
    network_->set_link_listener(
      [this](size_t target, client::LinkState state, const std::string &reason) {
          log_ << "aseba-mqtt: " << options_.targets[target]
               << (state == client::LinkState::up ? ": connected" : ": down (" + reason + ")")
               << std::endl;
      });
    for (const std::string &target : options_.targets)
        network_->connect(target, client::LinkPolicy::reconnect);
    remote_ids_.resize(options_.targets.size());

    BrokerOptions broker = options_.broker;
    broker.will_topic = options_.topics.status(options_.name);
    broker.will_payload = write_status(false, session_, options_.networks);
    broker.goodbye_payload = broker.will_payload;
    broker_ = std::make_unique<BrokerClient>(broker, [this] { network_->wake(); });
    std::vector<std::string> filters;
    if (options_.accept_events)
        filters.push_back(options_.topics.every_event());
    // Commands are heard even when refused, so that the sender learns why.
    for (const std::string &network : options_.networks)
        filters.push_back(options_.topics.every_command(network));
    broker_->subscribe(filters, COMMAND_QOS);
    tokens_time_ = client::Clock::now();
    event_tokens_ = options_.events_per_second;
}

Bridge::~Bridge()
{
    // The nodes are no longer bridged: their retained presence goes.
    for (const auto &[key, payload] : presence_)
        broker_->publish(options_.topics.node(options_.networks[key.target], key.id), "", 0, true);
    log_ << "aseba-mqtt: stopped; " << counters_.events_published << " events published, "
         << counters_.events_delivered << " delivered to the robots" << std::endl;
}

void Bridge::run(const std::function<bool()> &stop)
{
    while (!stop()) {
        try {
            network_->poll(POLL_PERIOD);
            network_->keep_alive();
            handle_heard_frames();
            report_broker_state();
            broker_->flush_pending(); // what a connection lost again left behind
            handle_broker_messages();
            handle_heard_frames(); // those heard while commands ran
            update_presence();
            sample_variables();
        } catch (const std::exception &error) {
            // A link that failed in the middle of a command: the Network has
            // marked it down and will try again.
            log_ << "aseba-mqtt: " << error.what() << std::endl;
        }
        flush_log_summary();
    }
}

// --- from the networks to the broker --------------------------------------

void Bridge::handle_heard_frames()
{
    std::vector<client::ReceivedFrame> frames;
    frames.swap(heard_);
    for (const client::ReceivedFrame &frame : frames) {
        const auto &event = std::get<client::UserEvent>(*frame.message);
        uint16_t source = frame.frame.source;
        // What we delivered ourselves under a remote node's id, heard back.
        if (remote_ids_[frame.target].is_remote(source) &&
            local_ids(frame.target).count(source) == 0)
            continue;
        publish_event(frame.target, source, event);
        pass_to_other_targets(frame.target, source, event);
    }
}

void Bridge::send_event(size_t target, const client::UserEvent &event, uint16_t source)
{
    if (network_->link_state(target) != client::LinkState::up)
        return;
    try {
        network_->send(target, event, source);
    } catch (const client::TransportError &) {
        // The link went down just now: its listener says so, and the event
        // is lost for that network as it would be on a broken link.
    }
}

void Bridge::publish_event(size_t target, uint16_t source, const client::UserEvent &event)
{
    EventOrigin origin{ session_, ++sequence_, options_.networks[target], source };
    std::string node_name;
    for (NodeKey key : network_->node_keys())
        if (key.target == target && key.id == source && network_->node(key).described)
            node_name = network_->node(key).description.name;
    std::string payload = write_event(event.arguments, origin, node_name, unix_time_ms());
    if (broker_->publish(options_.topics.event(event_name(event.id)), payload, EVENT_QOS, false))
        ++counters_.events_published;
}

void Bridge::pass_to_other_targets(size_t target, uint16_t source, const client::UserEvent &event)
{
    for (size_t other = 0; other < options_.targets.size(); other++) {
        if (other == target)
            continue;
        send_event(other,
                   event,
                   remote_ids_[other].id_for(options_.networks[target], source, local_ids(other)));
    }
}

void Bridge::on_broker_connected()
{
    log_ << "aseba-mqtt: connected to the broker " << options_.broker.address.host << ":"
         << options_.broker.address.port << std::endl;
    broker_->publish(options_.topics.status(options_.name),
                     write_status(true, session_, options_.networks),
                     1,
                     true);
    // The broker may have lost its retained messages: publish them again.
    presence_.clear();
    variables_.clear();
    next_variables_ = {};
    broker_->flush_pending();
}

void Bridge::report_broker_state()
{
    if (broker_->connections() != connections_seen_ && broker_->connected()) {
        connections_seen_ = broker_->connections();
        broker_up_reported_ = true;
        broker_error_reported_.clear();
        on_broker_connected();
    }
    if (!broker_->connected()) {
        std::string error = broker_->last_error();
        if (broker_up_reported_ || (error != broker_error_reported_ && !error.empty())) {
            log_ << "aseba-mqtt: broker " << options_.broker.address.host << ":"
                 << options_.broker.address.port << " unreachable"
                 << (error.empty() ? "" : ": " + error)
                 << "; trying again (QoS 1 events wait, up to " << options_.broker.pending_limit
                 << ")" << std::endl;
            broker_up_reported_ = false;
            broker_error_reported_ = error;
        }
    }
    BrokerDrops drops = broker_->drops();
    if (drops.inbox_full != drops_reported_.inbox_full)
        log_problem("the broker sends faster than the bridge takes: " +
                    std::to_string(drops.inbox_full - drops_reported_.inbox_full) +
                    " messages dropped");
    if (drops.oversized != drops_reported_.oversized)
        log_problem(std::to_string(drops.oversized - drops_reported_.oversized) +
                    " messages over " + std::to_string(options_.broker.payload_limit) +
                    " bytes dropped");
    if (drops.pending_full != drops_reported_.pending_full)
        log_problem(std::to_string(drops.pending_full - drops_reported_.pending_full) +
                    " events dropped: the broker has been away for more than " +
                    std::to_string(options_.broker.pending_limit) + " of them");
    drops_reported_ = drops;
}

// --- from the broker to the networks --------------------------------------

void Bridge::handle_broker_messages()
{
    for (InboundMessage &message : broker_->take_messages()) {
        if (auto name = options_.topics.event_name(message.topic)) {
            if (options_.accept_events)
                handle_event(*name, message.payload);
        } else if (auto address = options_.topics.command_address(message.topic)) {
            handle_command(*address, message.payload);
        }
    }
}

void Bridge::handle_event(const std::string &name, const std::string &payload)
{
    EventPayload event;
    try {
        event = read_event(payload, max_arguments());
    } catch (const PayloadError &error) {
        ++counters_.malformed;
        log_problem(options_.topics.event(name) + ": dropped: " + error.what());
        return;
    }
    if (event.origin && event.origin->bridge == session_) {
        ++counters_.echoes;
        return;
    }
    if (event.origin && duplicates_.seen_before(event.origin->bridge, event.origin->sequence)) {
        ++counters_.duplicates;
        return;
    }
    std::optional<uint16_t> id = event_id(name);
    if (!id) {
        ++counters_.malformed;
        log_problem(options_.topics.event(name) + ": dropped: no event '" + name +
                    "' in the program (--program, --event), and not a number below 32768");
        return;
    }
    if (std::optional<uint16_t> size = event_size(*id); size && *size != event.arguments.size()) {
        ++counters_.malformed;
        log_problem(options_.topics.event(name) + ": dropped: the event takes " +
                    std::to_string(*size) + " arguments, not " +
                    std::to_string(event.arguments.size()));
        return;
    }
    // The token bucket: a second's worth at most.
    auto now = client::Clock::now();
    double rate = options_.events_per_second;
    event_tokens_ = std::min(
      rate, event_tokens_ + rate * std::chrono::duration<double>(now - tokens_time_).count());
    tokens_time_ = now;
    if (event_tokens_ < 1) {
        ++counters_.over_rate;
        log_problem(options_.topics.event(name) + ": dropped: more than " +
                    std::to_string(options_.events_per_second) +
                    " events per second from the broker (--max-event-rate)");
        return;
    }
    event_tokens_ -= 1;
    client::UserEvent user_event{ *id, event.arguments };
    for (size_t target = 0; target < options_.targets.size(); target++) {
        uint16_t source = 0;
        if (event.origin)
            source = remote_ids_[target].id_for(
              event.origin->network, event.origin->node, local_ids(target));
        send_event(target, user_event, source);
    }
    ++counters_.events_delivered;
}

void Bridge::handle_command(const TopicLayout::CommandAddress &address, const std::string &payload)
{
    std::optional<size_t> target = target_of_network(address.network);
    if (!target)
        return;
    std::string reply_topic = options_.topics.reply(address.network, address.node);
    Reply refusal;
    // Read first, so that every reply echoes the command and its request
    // (docs/mqtt.md), a read-only bridge's refusal too.
    Command command;
    std::optional<std::string> malformed;
    try {
        command = read_command(payload);
        refusal.command = command_name(command.kind);
        refusal.request = command.request;
    } catch (const PayloadError &error) {
        malformed = error.what();
    }
    if (!options_.accept_commands) {
        ++counters_.commands_refused;
        refusal.error = "this bridge is read-only: it runs no command (start it with "
                        "--accept-commands)";
        log_problem(options_.topics.command(address.network, address.node) +
                    ": refused: read-only bridge");
        broker_->publish(reply_topic, write_reply(refusal), COMMAND_QOS, false);
        return;
    }
    if (malformed) {
        ++counters_.malformed;
        refusal.error = *malformed;
        log_problem(options_.topics.command(address.network, address.node) +
                    ": refused: " + *malformed);
        broker_->publish(reply_topic, write_reply(refusal), COMMAND_QOS, false);
        return;
    }
    std::vector<NodeKey> keys;
    for (NodeKey key : network_->node_keys())
        if (key.target == *target && network_->node(key).described &&
            (address.node == "all" || address.node == std::to_string(key.id)))
            keys.push_back(key);
    if (keys.empty()) {
        refusal.error = "no node " + address.node + " on network " + address.network;
        broker_->publish(reply_topic, write_reply(refusal), COMMAND_QOS, false);
        return;
    }
    for (NodeKey key : keys) {
        ++counters_.commands;
        Reply reply = run_command(key, command);
        broker_->publish(options_.topics.reply(address.network, std::to_string(key.id)),
                         write_reply(reply),
                         COMMAND_QOS,
                         false);
    }
}

Reply Bridge::run_command(NodeKey key, const Command &command)
{
    Reply reply;
    reply.command = command_name(command.kind);
    reply.request = command.request;
    reply.node = key.id;
    try {
        client::ExecutionState state;
        switch (command.kind) {
        case CommandKind::run: state = network_->run(key); break;
        case CommandKind::pause: state = network_->pause(key); break;
        case CommandKind::stop: state = network_->stop(key); break;
        case CommandKind::reset: state = network_->reset(key); break;
        case CommandKind::reboot: network_->reboot(key); break;
        case CommandKind::load: {
            client::ProgramFile file;
            file.file_name = "program";
            size_t first = command.program.find_first_not_of(" \t\r\n");
            if (first != std::string::npos && command.program[first] == '<') {
                AeslReadResult read = read_aesl(command.program);
                if (!read.ok)
                    throw client::ProgramError("program:" + std::to_string(read.error_line) + ": " +
                                               read.error);
                file.is_project = true;
                file.project = std::move(read.project);
                file.definitions = file.project.definitions;
            } else {
                file.script = command.program;
                file.definitions = definitions_;
            }
            auto program = std::make_shared<const client::CompiledProgram>(
              client::compile_program(file, network_->node(key).description, key.id));
            network_->upload(key, program->result.bytecode);
            network_->set_program(key, program);
            state = network_->run(key);
            // Its events are the network's from now on.
            if (file.is_project)
                definitions_ = file.definitions;
            programs_[key] = program;
            break;
        }
        }
        reply.ok = true;
        if (command.kind != CommandKind::reboot)
            reply.state = state.name();
    } catch (const std::exception &error) {
        reply.error = error.what();
    }
    log_ << "aseba-mqtt: " << options_.networks[key.target] << " node " << key.id << ": "
         << reply.command << (reply.ok ? "" : " failed: " + reply.error) << std::endl;
    return reply;
}

// --- presence and variables ------------------------------------------------

void Bridge::update_presence()
{
    std::vector<NodeKey> keys = network_->node_keys();
    for (NodeKey key : keys) {
        const client::Node &node = network_->node(key);
        std::string payload = write_node(options_.networks[key.target], node);
        auto [entry, is_new] = presence_.try_emplace(key, "");
        if (!is_new && entry->second == payload)
            continue;
        // Once per change: a robot running since before we came tells its state when asked.
        if (node.described && node.compatible && !node.execution && network_->is_alive(key) &&
            network_->link_state(key.target) == client::LinkState::up)
            network_->send(key.target, client::NodeCommand{ NODE_MSG_GET_EXECUTION_STATE, key.id });
        if (broker_->publish(
              options_.topics.node(options_.networks[key.target], key.id), payload, 1, true))
            entry->second = payload;
        else
            presence_.erase(entry); // published again at the next connection
    }
    for (auto entry = presence_.begin(); entry != presence_.end();) {
        if (std::find(keys.begin(), keys.end(), entry->first) == keys.end()) {
            broker_->publish(
              options_.topics.node(options_.networks[entry->first.target], entry->first.id),
              "",
              1,
              true);
            programs_.erase(entry->first);
            entry = presence_.erase(entry);
        } else {
            ++entry;
        }
    }
}

const client::CompiledProgram *Bridge::program_for(NodeKey key)
{
    auto known = programs_.find(key);
    if (known != programs_.end())
        return known->second.get();
    if (!options_.program)
        return nullptr;
    try {
        programs_[key] = std::make_shared<const client::CompiledProgram>(
          client::compile_program(*options_.program, network_->node(key).description, key.id));
    } catch (const client::ProgramError &error) {
        programs_[key] = nullptr;
        log_ << "aseba-mqtt: " << options_.networks[key.target] << " node " << key.id
             << ": its user variables are unknown: " << error.what() << std::endl;
    }
    return programs_[key].get();
}

void Bridge::sample_variables()
{
    if (options_.variables.empty() || !broker_->connected())
        return;
    auto now = client::Clock::now();
    if (now < next_variables_)
        return;
    next_variables_ = now + options_.variable_period;
    for (NodeKey key : network_->node_keys()) {
        const client::Node &node = network_->node(key);
        if (!node.described || !node.compatible || !network_->is_alive(key))
            continue;
        std::vector<client::VariableLocation> map =
          client::variable_map(node.description, program_for(key));
        for (const std::string &name : options_.variables) {
            std::string topic =
              options_.topics.variable(options_.networks[key.target], key.id, name);
            try {
                client::VariableSlice slice =
                  client::resolve_variable(client::parse_variable_reference(name), map);
                std::string values =
                  write_values(network_->read_variables(key, slice.address, slice.length));
                if (variables_[topic] == values)
                    continue;
                if (broker_->publish(topic, values, 0, true))
                    variables_[topic] = values;
            } catch (const client::VariableError &error) {
                if (variable_problems_.insert(topic).second)
                    log_ << "aseba-mqtt: " << topic << ": not published: " << error.what()
                         << std::endl;
            } catch (const client::TimeoutError &) {
                // A robot that does not answer keeps its last values.
            }
        }
    }
}

// --- events by name ------------------------------------------------------------

std::string Bridge::event_name(uint16_t id) const
{
    if (id < definitions_.events.size() && is_topic_level(definitions_.events[id].name))
        return definitions_.events[id].name;
    return std::to_string(id);
}

std::optional<uint16_t> Bridge::event_id(const std::string &name) const
{
    if (std::optional<uint16_t> id = client::global_event_id(definitions_, name))
        return id;
    if (is_number(name) && std::stoul(name) < client::FIRST_SYSTEM_TYPE)
        return uint16_t(std::stoul(name));
    return std::nullopt;
}

std::optional<uint16_t> Bridge::event_size(uint16_t id) const
{
    if (id < definitions_.events.size())
        return definitions_.events[id].size;
    return std::nullopt;
}

size_t Bridge::max_arguments() const
{
    // What the smallest `args` of the described nodes takes: more would be
    // cut, or refused, by the robot.
    size_t limit = client::MAX_EVENT_WORDS;
    for (NodeKey key : network_->node_keys()) {
        const client::Node &node = network_->node(key);
        if (!node.described)
            continue;
        for (const NamedVariable &variable : node.description.named_variables)
            if (variable.name == "args")
                limit = std::min<size_t>(limit, variable.size);
    }
    return limit;
}

std::set<uint16_t> Bridge::local_ids(size_t target) const
{
    std::set<uint16_t> ids;
    for (NodeKey key : network_->node_keys())
        if (key.target == target)
            ids.insert(key.id);
    return ids;
}

std::optional<size_t> Bridge::target_of_network(const std::string &network) const
{
    for (size_t target = 0; target < options_.networks.size(); target++)
        if (options_.networks[target] == network)
            return target;
    return std::nullopt;
}

// --- the log -----------------------------------------------------------------

void Bridge::log_problem(const std::string &text)
{
    auto now = client::Clock::now();
    if (now - log_second_ >= std::chrono::seconds(1)) {
        flush_log_summary();
        log_second_ = now;
        log_lines_this_second_ = 0;
    }
    if (log_lines_this_second_++ < LOG_LINES_PER_SECOND)
        log_ << "aseba-mqtt: " << text << std::endl;
    else
        ++log_lines_suppressed_;
}

void Bridge::flush_log_summary()
{
    if (log_lines_suppressed_ == 0 || client::Clock::now() - log_second_ < std::chrono::seconds(1))
        return;
    log_ << "aseba-mqtt: ... and " << log_lines_suppressed_
         << " more problems like these in the last second" << std::endl;
    log_lines_suppressed_ = 0;
}

} // namespace aseba::mqtt
