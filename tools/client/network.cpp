// The network model: links, discovery, description assembly and the
// request/answer pairs of protocol.md §6.

#include "network.hpp"

#include <algorithm>

namespace aseba::client
{

namespace
{

bool is_number(const std::string &text)
{
    return !text.empty() &&
           std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

bool description_complete(const Description &header, const TargetDescription &parts)
{
    return parts.named_variables.size() == header.named_variables_count &&
           parts.local_events.size() == header.local_events_count &&
           parts.native_functions.size() == header.native_functions_count;
}

// Where the VM stopped, for the run-time errors that stop it; an event
// killed by the next one does not stop it.
std::optional<uint16_t> stopping_error_pc(const Message &message)
{
    if (const auto *bounds = std::get_if<ArrayAccessOutOfBounds>(&message))
        return bounds->pc;
    if (const auto *division = std::get_if<DivisionByZero>(&message))
        return division->pc;
    if (const auto *specific = std::get_if<NodeSpecificError>(&message))
        return specific->pc;
    return std::nullopt;
}

} // namespace

std::string ExecutionState::name() const
{
    if (stepping())
        return "stepping";
    if (stopped())
        return "stopped";
    return "running";
}

std::string Node::label() const
{
    if (described)
        return description.name + " " + std::to_string(key.id);
    return "node " + std::to_string(key.id);
}

void Network::set_listener(std::function<void(const ReceivedFrame &)> listener)
{
    listener_ = std::move(listener);
}

void Network::handle(size_t target, Frame frame)
{
    ReceivedFrame received;
    received.time = Clock::now();
    received.wall_time = std::chrono::system_clock::now();
    received.target = target;
    try {
        received.message = decode(frame);
    } catch (const ProtocolError &error) {
        received.error = error.what();
        malformed_frames_++;
    }
    received.frame = std::move(frame);
    if (received.message)
        update_model(target, received.frame, *received.message);
    if (collector_)
        collector_(received);
    if (listener_)
        listener_(received);
}

void Network::update_model(size_t target, const Frame &frame, const Message &message)
{
    // Frames of hosts (ours echoed by a switch, or other tools') say nothing
    // about nodes.
    if (frame.source == HOST_SOURCE || frame.type >= NODE_MSG_GET_DESCRIPTION ||
        (frame.type >= FIRST_SYSTEM_TYPE && frame.type < MSG_BOOTLOADER_DESCRIPTION))
        return;
    NodeKey key{ target, frame.source };
    auto [entry, is_new] = nodes_.try_emplace(key);
    Node &node = entry->second;
    node.key = key;
    node.last_seen = Clock::now();
    if (is_new)
        last_new_node_ = node.last_seen;

    const auto *present = std::get_if<NodePresent>(&message);
    if (present != nullptr) {
        node.protocol_version = present->version;
        if (!first_answer_)
            first_answer_ = node.last_seen;
    }
    // A new node (heard through any message) or an undescribed one that
    // says it is present is asked for its description (protocol.md §6.1);
    // asking again restarts a description that lost a part on the way.
    if (!node.described && (is_new || present != nullptr) &&
        !std::holds_alternative<Description>(message))
        send(target, GetNodeDescription{ key.id, PROTOCOL_VERSION });
    if (const auto *header = std::get_if<Description>(&message)) {
        DescriptionAssembly &assembly = assemblies_[key];
        assembly.header = *header;
        assembly.parts = TargetDescription{};
        assembly.parts.name = header->name;
        assembly.parts.protocol_version = header->protocol_version;
        assembly.parts.bytecode_size = header->bytecode_size;
        assembly.parts.stack_size = header->stack_size;
        assembly.parts.variables_size = header->variables_size;
    } else if (const auto *state = std::get_if<ExecutionStateChanged>(&message)) {
        node.execution = ExecutionState{ state->pc, state->flags };
    } else if (std::optional<uint16_t> pc = stopping_error_pc(message)) {
        // The VM stops at a run-time error (vm.c, as the reference VM does)
        // and reports the error, not its new state.
        node.execution = ExecutionState{ *pc, FLAG_STEP_BY_STEP };
    } else if (auto assembly = assemblies_.find(key); assembly != assemblies_.end()) {
        // Parts arrive in order: variables, local events, natives.
        Description &expected = assembly->second.header;
        TargetDescription &parts = assembly->second.parts;
        if (const auto *variable = std::get_if<NamedVariableDescription>(&message)) {
            if (parts.named_variables.size() < expected.named_variables_count)
                parts.named_variables.push_back(variable->variable);
        } else if (const auto *event = std::get_if<LocalEventDescription>(&message)) {
            if (parts.local_events.size() < expected.local_events_count)
                parts.local_events.push_back(event->event);
        } else if (const auto *function = std::get_if<NativeFunctionDescription>(&message)) {
            if (parts.native_functions.size() < expected.native_functions_count)
                parts.native_functions.push_back(function->function);
        }
    }
    if (auto assembly = assemblies_.find(key);
        assembly != assemblies_.end() &&
        description_complete(assembly->second.header, assembly->second.parts)) {
        uint16_t version = assembly->second.header.protocol_version;
        node.protocol_version = version;
        node.compatible = version >= MIN_PROTOCOL_VERSION && version <= PROTOCOL_VERSION;
        node.description = std::move(assembly->second.parts);
        node.described = true;
        assemblies_.erase(assembly);
    }
    if (std::holds_alternative<Disconnected>(message)) {
        nodes_.erase(key);
        assemblies_.erase(key);
    }
}

void Network::discover(std::optional<Milliseconds> quiet)
{
    const auto start = Clock::now();
    const auto deadline = start + answer_timeout_;
    last_new_node_ = start;
    last_list_nodes_ = start;
    first_answer_.reset();
    send_to_all(ListNodes{ PROTOCOL_VERSION });
    // How long to wait for more nodes once every node that answered is
    // described: twice the first answer's round trip, or a fixed time for
    // nodes that never answer LIST_NODES (before protocol 5).
    auto quiet_period = [&]() -> Milliseconds {
        if (quiet)
            return *quiet;
        if (!first_answer_)
            return DISCOVERY_QUIET_WITHOUT_ANSWER;
        auto round_trip = std::chrono::ceil<Milliseconds>(*first_answer_ - start);
        return std::clamp(2 * round_trip, DISCOVERY_QUIET_MIN, answer_timeout_);
    };
    while (true) {
        auto now = Clock::now();
        bool all_described = std::all_of(
          nodes_.begin(), nodes_.end(), [](const auto &entry) { return entry.second.described; });
        auto quiet_until = last_new_node_ + quiet_period();
        if (!nodes_.empty() && all_described && now >= quiet_until)
            return;
        if (now >= deadline)
            return;
        // Wake up when the quiet period may be over, or at the deadline.
        auto wake = !nodes_.empty() && all_described ? std::min(quiet_until, deadline) : deadline;
        poll(std::chrono::ceil<Milliseconds>(wake - now));
    }
}

void Network::keep_alive()
{
    auto now = Clock::now();
    if (now - last_list_nodes_ < LIST_NODES_PERIOD)
        return;
    last_list_nodes_ = now;
    send_to_all(ListNodes{ PROTOCOL_VERSION });
}

bool Network::is_alive(NodeKey key) const
{
    return Clock::now() - node(key).last_seen <= NODE_SILENCE_LIMIT;
}

std::vector<NodeKey> Network::node_keys() const
{
    std::vector<NodeKey> keys;
    for (const auto &entry : nodes_)
        keys.push_back(entry.first);
    return keys;
}

const Node &Network::node(NodeKey key) const
{
    auto found = nodes_.find(key);
    if (found == nodes_.end())
        throw NetworkError("no node " + std::to_string(key.id) + " on " + target_name(key.target));
    return found->second;
}

Node &Network::known_node(NodeKey key)
{
    auto found = nodes_.find(key);
    if (found == nodes_.end())
        throw NetworkError("no node " + std::to_string(key.id) + " on " + target_name(key.target));
    return found->second;
}

const Node &Network::described_node(NodeKey key) const
{
    const Node &found = node(key);
    if (!found.described)
        throw NetworkError(description_problem(key));
    if (!found.compatible)
        throw NetworkError(found.label() + " speaks protocol " +
                           std::to_string(found.protocol_version) +
                           ", this tool speaks protocols " + std::to_string(MIN_PROTOCOL_VERSION) +
                           " and " + std::to_string(PROTOCOL_VERSION));
    return found;
}

std::vector<NodeKey> Network::select(const std::string &selector) const
{
    std::vector<NodeKey> selected;
    for (const auto &[key, node] : nodes_) {
        if (!node.described || !node.compatible)
            continue;
        bool matches = selector == "all" ||
                       (is_number(selector) && std::to_string(key.id) == selector) ||
                       node.description.name == selector;
        if (matches)
            selected.push_back(key);
    }
    if (selected.empty())
        no_usable_node(selector);
    return selected;
}

void Network::no_usable_node(const std::string &selector) const
{
    // Nodes that answered but cannot be used, and why; a node not described
    // has no name yet, so it may be the one a name selects.
    std::string reasons;
    std::string known;
    for (const auto &[key, node] : nodes_) {
        known += (known.empty() ? "" : ", ") + node.label();
        bool may_match =
          selector == "all" || !is_number(selector) || std::to_string(key.id) == selector;
        if (!may_match)
            continue;
        std::string reason;
        if (node.described && !node.compatible)
            reason = node.label() + " speaks protocol " + std::to_string(node.protocol_version) +
                     ", this tool speaks protocols " + std::to_string(MIN_PROTOCOL_VERSION) +
                     " and " + std::to_string(PROTOCOL_VERSION);
        else if (!node.described)
            reason = description_problem(key);
        if (!reason.empty())
            reasons += (reasons.empty() ? "" : "; ") + reason;
    }
    if (!reasons.empty())
        throw NetworkError("no usable node '" + selector + "' on the network: " + reasons);
    throw NetworkError("no node '" + selector + "' on the network (" +
                       (known.empty() ? std::string("no node answered") : "nodes: " + known) + ")");
}

std::string Network::description_problem(NodeKey key) const
{
    const Node &node = nodes_.at(key);
    std::string who = node.label() + " on " + target_name(key.target);
    if (node.protocol_version > PROTOCOL_VERSION ||
        (node.protocol_version != 0 && node.protocol_version < MIN_PROTOCOL_VERSION))
        return who + " announced protocol " + std::to_string(node.protocol_version) +
               " and did not describe itself (this tool speaks protocols " +
               std::to_string(MIN_PROTOCOL_VERSION) + " and " + std::to_string(PROTOCOL_VERSION) +
               ")";
    auto assembly = assemblies_.find(key);
    if (assembly == assemblies_.end())
        return who + " did not send its description within " +
               std::to_string(answer_timeout_.count()) + " ms";
    const Description &header = assembly->second.header;
    const TargetDescription &parts = assembly->second.parts;
    return who + " (" + header.name + ") did not finish describing itself within " +
           std::to_string(answer_timeout_.count()) +
           " ms: " + std::to_string(parts.named_variables.size()) + " of " +
           std::to_string(header.named_variables_count) + " named variables, " +
           std::to_string(parts.local_events.size()) + " of " +
           std::to_string(header.local_events_count) + " local events, " +
           std::to_string(parts.native_functions.size()) + " of " +
           std::to_string(header.native_functions_count) + " native functions arrived";
}

void Network::timed_out(NodeKey key, const std::string &what) const
{
    std::string who = "node " + std::to_string(key.id);
    if (auto found = nodes_.find(key); found != nodes_.end())
        who = found->second.label();
    throw TimeoutError(who + " on " + target_name(key.target) + " did not answer " + what +
                       " within " + std::to_string(answer_timeout_.count()) + " ms");
}

void Network::exchange(NodeKey key,
                       const std::function<void()> &request,
                       const std::function<void(const Message &)> &collect,
                       const std::function<bool()> &answered,
                       const std::string &what)
{
    // The collector lives only during this exchange, whatever happens.
    struct CollectorScope {
        std::function<void(const ReceivedFrame &)> &slot;
        ~CollectorScope()
        {
            slot = nullptr;
        }
    } scope{ collector_ };
    collector_ = [&](const ReceivedFrame &frame) {
        if (frame.target == key.target && frame.frame.source == key.id && frame.message)
            collect(*frame.message);
    };
    request();
    if (!wait_until(answered, answer_timeout_))
        timed_out(key, what);
}

ExecutionState Network::command_with_state(NodeKey key, const Message &command, const char *what)
{
    described_node(key);
    std::optional<ExecutionState> answer;
    exchange(
      key,
      [&] { send(key.target, command); },
      [&](const Message &message) {
          // The first state after the command is its answer; later ones (a
          // breakpoint hit right after RUN) are news, not the answer.
          const auto *state = std::get_if<ExecutionStateChanged>(&message);
          if (state != nullptr && !answer)
              answer = ExecutionState{ state->pc, state->flags };
      },
      [&] { return answer.has_value(); },
      what);
    return *answer;
}

ExecutionState Network::execution_state(NodeKey key)
{
    return command_with_state(
      key, NodeCommand{ NODE_MSG_GET_EXECUTION_STATE, key.id }, "GET_EXECUTION_STATE");
}

ExecutionState Network::reset(NodeKey key)
{
    return command_with_state(key, NodeCommand{ NODE_MSG_RESET, key.id }, "RESET");
}

ExecutionState Network::pause(NodeKey key)
{
    return command_with_state(key, NodeCommand{ NODE_MSG_PAUSE, key.id }, "PAUSE");
}

ExecutionState Network::stop(NodeKey key)
{
    return command_with_state(key, NodeCommand{ NODE_MSG_STOP, key.id }, "STOP");
}

ExecutionState Network::step(NodeKey key)
{
    ExecutionState state = execution_state(key);
    if (!(state.flags & FLAG_EVENT_ACTIVE))
        return state; // STEP would not be answered: nothing to execute
    return command_with_state(key, NodeCommand{ NODE_MSG_STEP, key.id }, "STEP");
}

ExecutionState Network::run(NodeKey key)
{
    ExecutionState state = execution_state(key);
    if (state.stepping())
        command_with_state(key, NodeCommand{ NODE_MSG_STEP, key.id }, "STEP");
    return command_with_state(key, NodeCommand{ NODE_MSG_RUN, key.id }, "RUN");
}

namespace
{

// Whether `pc` is the entry address of an event handler (bytecode.md §2).
bool is_event_entry(const std::vector<uint16_t> &bytecode, uint16_t pc)
{
    if (bytecode.empty())
        return false;
    size_t table_end = std::min<size_t>(bytecode[0], bytecode.size());
    for (size_t i = 2; i < table_end; i += 2)
        if (bytecode[i] == pc)
            return true;
    return false;
}

} // namespace

ExecutionState Network::step_line(NodeKey key, unsigned max_steps)
{
    const Node &node = described_node(key);
    if (!node.program)
        throw NetworkError(node.label() + ": stepping by line needs the node's program");
    std::shared_ptr<const CompiledProgram> program = node.program;
    ExecutionState state = execution_state(key);
    if (!(state.flags & FLAG_EVENT_ACTIVE))
        return state;
    unsigned line = source_line_of(*program, state.pc);
    for (unsigned steps = 0; steps < max_steps; steps++) {
        state = command_with_state(key, NodeCommand{ NODE_MSG_STEP, key.id }, "STEP");
        if (!(state.flags & FLAG_EVENT_ACTIVE) || source_line_of(*program, state.pc) != line ||
            is_event_entry(program->result.bytecode, state.pc))
            break;
    }
    return state;
}

void Network::upload(NodeKey key, const std::vector<uint16_t> &bytecode)
{
    const Node &node = described_node(key);
    if (bytecode.size() > node.description.bytecode_size)
        throw NetworkError("the program has " + std::to_string(bytecode.size()) +
                           " words of bytecode, " + node.label() + " holds " +
                           std::to_string(node.description.bytecode_size));
    size_t start = 0;
    do {
        size_t count = std::min(MAX_BYTECODE_CHUNK_WORDS, bytecode.size() - start);
        SetBytecode chunk;
        chunk.dest = key.id;
        chunk.start = uint16_t(start);
        chunk.words.assign(bytecode.begin() + long(start), bytecode.begin() + long(start + count));
        command_with_state(key, chunk, "SET_BYTECODE");
        start += count;
    } while (start < bytecode.size());
}

void Network::set_program(NodeKey key, std::shared_ptr<const CompiledProgram> program)
{
    known_node(key).program = std::move(program);
}

std::vector<int16_t> Network::read_variables(NodeKey key, uint16_t start, uint16_t length)
{
    const Node &node = described_node(key);
    if (uint32_t(start) + length > node.description.variables_size)
        throw NetworkError("words " + std::to_string(start) + " to " +
                           std::to_string(uint32_t(start) + length - 1) + " are beyond the " +
                           std::to_string(node.description.variables_size) +
                           " words of variables of " + node.label());
    std::vector<int16_t> values(length, 0);
    std::vector<bool> received(length, false);
    size_t missing = length;
    auto collect = [&](const Message &message) {
        const auto *answer = std::get_if<Variables>(&message);
        if (answer == nullptr)
            return;
        for (size_t i = 0; i < answer->values.size(); i++) {
            size_t address = size_t(answer->start) + i;
            if (address < start || address >= size_t(start) + length)
                continue;
            size_t index = address - start;
            values[index] = answer->values[i];
            if (!received[index]) {
                received[index] = true;
                missing--;
            }
        }
    };
    auto request = [&] {
        for (size_t offset = 0; offset < length; offset += MAX_VARIABLES_WORDS) {
            uint16_t count = uint16_t(std::min<size_t>(MAX_VARIABLES_WORDS, length - offset));
            send(key.target, GetVariables{ key.id, uint16_t(start + offset), count });
        }
    };
    exchange(
      key, request, collect, [&] { return missing == 0; }, "GET_VARIABLES");
    return values;
}

void Network::write_variables(NodeKey key, uint16_t start, const std::vector<int16_t> &values)
{
    const Node &node = described_node(key);
    if (uint32_t(start) + values.size() > node.description.variables_size)
        throw NetworkError("writing " + std::to_string(values.size()) + " words at " +
                           std::to_string(start) + " goes beyond the " +
                           std::to_string(node.description.variables_size) +
                           " words of variables of " + node.label());
    for (size_t offset = 0; offset < values.size(); offset += MAX_SET_VARIABLES_WORDS) {
        size_t count = std::min(MAX_SET_VARIABLES_WORDS, values.size() - offset);
        SetVariables message;
        message.dest = key.id;
        message.start = uint16_t(start + offset);
        message.values.assign(values.begin() + long(offset), values.begin() + long(offset + count));
        send(key.target, message);
    }
}

bool Network::set_breakpoint(NodeKey key, uint16_t pc)
{
    described_node(key);
    std::optional<bool> success;
    exchange(
      key,
      [&] {
          send(key.target, BreakpointCommand{ NODE_MSG_BREAKPOINT_SET, key.id, pc });
      },
      [&](const Message &message) {
          const auto *result = std::get_if<BreakpointSetResult>(&message);
          if (result != nullptr && result->pc == pc)
              success = result->success != 0;
      },
      [&] { return success.has_value(); },
      "BREAKPOINT_SET");
    return *success;
}

void Network::clear_breakpoint(NodeKey key, uint16_t pc)
{
    described_node(key);
    send(key.target, BreakpointCommand{ NODE_MSG_BREAKPOINT_CLEAR, key.id, pc });
}

void Network::clear_all_breakpoints(NodeKey key)
{
    described_node(key);
    send(key.target, NodeCommand{ NODE_MSG_BREAKPOINT_CLEAR_ALL, key.id });
}

void Network::emit(uint16_t event_id, const std::vector<int16_t> &arguments)
{
    if (event_id >= FIRST_SYSTEM_TYPE)
        throw NetworkError("event id " + std::to_string(event_id) + " is not below 0x8000");
    if (arguments.size() > MAX_EVENT_WORDS)
        throw NetworkError("an event carries at most " + std::to_string(MAX_EVENT_WORDS) +
                           " arguments, not " + std::to_string(arguments.size()));
    send_to_all(UserEvent{ event_id, arguments });
}

void Network::write_bytecode(NodeKey key)
{
    described_node(key);
    send(key.target, NodeCommand{ NODE_MSG_WRITE_BYTECODE, key.id });
}

void Network::reboot(NodeKey key)
{
    described_node(key);
    send(key.target, NodeCommand{ NODE_MSG_REBOOT, key.id });
    // It restarts as its flash says and reports no state of its own until
    // asked: the state it had is no longer known.
    nodes_.at(key).execution.reset();
}

} // namespace aseba::client
