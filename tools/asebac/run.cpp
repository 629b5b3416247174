// The host VM session of `asebac run`.

#include "run.hpp"

#include <algorithm>
#include <sstream>

#include "tools/compiler/target_presets.hpp"

extern "C" {
#include "robots/epuck/epuck_natives.h"
#include "nat_standard.h"
#include "vm.h"
#include "vm_opcodes.h"
}

namespace aseba
{

namespace
{

constexpr uint16_t NODE_ID = 1;
constexpr uint16_t HOST_SOURCE = 0;             // `source` of events sent by `asebac run`
constexpr unsigned long MAX_VM_BUDGET = 0xFFFF; // vm_run takes 16-bit budgets

std::string json_string(const std::string &text)
{
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\')
            out += '\\';
        if (static_cast<unsigned char>(c) >= 0x20)
            out += c;
    }
    return out + "\"";
}

// What the VM reported while running.
struct Session {
    const CommonDefinitions *definitions = nullptr;
    std::vector<std::string> emitted;
    std::vector<std::string> errors;
    std::string current_event;

    void add_error(const std::string &what, uint16_t pc, const std::string &details)
    {
        errors.push_back("{\"event\": " + json_string(current_event) + ", \"error\": " +
                         json_string(what) + ", \"pc\": " + std::to_string(pc) + details + "}");
    }
};

void on_emit(void *context, uint16_t event, const int16_t *payload, uint16_t count)
{
    auto &session = *static_cast<Session *>(context);
    std::string name = event < session.definitions->events.size()
                         ? session.definitions->events[event].name
                         : std::to_string(event);
    std::string text = "{\"event\": " + json_string(name) + ", \"args\": [";
    for (uint16_t i = 0; i < count; ++i)
        text += (i ? ", " : "") + std::to_string(payload[i]);
    session.emitted.push_back(text + "]}");
}

void on_killed(void *context, uint16_t pc)
{
    static_cast<Session *>(context)->add_error("event killed", pc, "");
}

void on_array_access(void *context, uint16_t pc, uint16_t size, uint16_t index)
{
    static_cast<Session *>(context)->add_error("array access out of bounds",
                                               pc,
                                               ", \"size\": " + std::to_string(size) +
                                                 ", \"index\": " + std::to_string(index));
}

void on_division_by_zero(void *context, uint16_t pc)
{
    static_cast<Session *>(context)->add_error("division by zero", pc, "");
}

void on_node_error(void *context, uint16_t pc, const char *message)
{
    static_cast<Session *>(context)->add_error(message, pc, "");
}

// The VM's word reports (vm.h), state changes left out.
void on_report(void *context, uint16_t type, const uint16_t *words, uint16_t count)
{
    if (type == VM_REPORT_EVENT_EXECUTION_KILLED && count == 1)
        on_killed(context, words[0]);
    else if (type == VM_REPORT_ARRAY_ACCESS_OUT_OF_BOUNDS && count == 3)
        on_array_access(context, words[0], words[1], words[2]);
    else if (type == VM_REPORT_DIVISION_BY_ZERO && count == 1)
        on_division_by_zero(context, words[0]);
}

const vm_callbacks CALLBACKS = { on_emit, on_report, on_node_error };

// Runs the active event for at most `budget` steps; false if it is still active.
bool run_event(vm_state &vm, unsigned long budget)
{
    unsigned long done = 0;
    while (vm_is_event_active(&vm) && (vm.flags & VM_FLAG_STEP_BY_STEP) == 0 && done < budget) {
        unsigned long slice = std::min(budget - done, MAX_VM_BUDGET);
        vm_run(&vm, static_cast<uint16_t>(slice));
        done += slice;
    }
    return !vm_is_event_active(&vm) || (vm.flags & VM_FLAG_STEP_BY_STEP) != 0;
}

} // namespace

bool execute_program(const CompileResult &compiled,
                     const TargetDescription &target,
                     const CommonDefinitions &definitions,
                     const std::vector<EventToSend> &events,
                     unsigned long step_budget,
                     RunOutcome &outcome,
                     std::string &error)
{
    // the target's natives, found by name among the host's implementations:
    // the standard ones and the e-puck's (the firmware's own table)
    std::vector<vm_native> natives;
    for (const auto &function : target.native_functions) {
        const vm_native *found = nullptr;
        for (const vm_native_table *table : { &nat_standard_table, &epuck_native_table })
            for (uint16_t i = 0; i < vm_native_count(table) && found == nullptr; ++i)
                if (function.name == native_function(*table, i).name)
                    found = vm_native_at(table, i);
        if (found == nullptr) {
            error = "native function " + function.name + " has no implementation on the host";
            return false;
        }
        natives.push_back(*found);
    }
    // Run, not described: no dictionary needed.
    const vm_native_module module{ natives.data(), static_cast<uint16_t>(natives.size()) };
    const vm_native_module *const modules[] = { &module };
    vm_native_table table{ modules, 1, nullptr };

    std::vector<uint16_t> bytecode(target.bytecode_size, 0);
    std::vector<int16_t> variables(target.variables_size, 0);
    std::vector<int16_t> stack(target.stack_size, 0);
    uint16_t args_size = target.named_variables.size() > VM_NAMED_ARGS
                           ? target.named_variables[VM_NAMED_ARGS].size
                           : 0;
    vm_memory memory{ bytecode.data(),  target.bytecode_size,
                      variables.data(), target.variables_size,
                      stack.data(),     target.stack_size,
                      args_size };
    Session session;
    session.definitions = &definitions;
    vm_state vm;
    vm_init(&vm, &memory, NODE_ID, &table, &CALLBACKS, &session);
    if (!target.named_variables.empty()) // `id` comes first by convention (bytecode.md §7)
        variables[0] = static_cast<int16_t>(NODE_ID);

    std::vector<std::string> &unfinished = outcome.unfinished;
    session.current_event = "init";
    vm_set_bytecode(
      &vm, 0, compiled.bytecode.data(), static_cast<uint16_t>(compiled.bytecode.size()));
    vm_command_run(&vm);
    if (!run_event(vm, step_budget))
        unfinished.push_back("init");
    for (const auto &event : events) {
        session.current_event = event.name;
        vm.flags &= static_cast<uint16_t>(~VM_FLAG_STEP_BY_STEP); // go on after an error
        bool sent = false;
        for (size_t i = 0; i < definitions.events.size() && !sent; ++i) {
            if (definitions.events[i].name == event.name) {
                vm_receive_event(&vm,
                                 static_cast<uint16_t>(i),
                                 HOST_SOURCE,
                                 event.arguments.data(),
                                 static_cast<uint16_t>(event.arguments.size()));
                sent = true;
            }
        }
        for (size_t i = 0; i < target.local_events.size() && !sent; ++i) {
            if (target.local_events[i].name == event.name) {
                if (target.named_variables.size() > VM_NAMED_SOURCE) // firmware convention
                    variables[VM_NAMED_SOURCE] = static_cast<int16_t>(NODE_ID);
                vm_setup_event(&vm, static_cast<uint16_t>(VM_EVENT_LOCAL_FIRST - i));
                sent = true;
            }
        }
        if (!sent) {
            error = "unknown event " + event.name;
            return false;
        }
        if (!run_event(vm, step_budget))
            unfinished.push_back(event.name);
    }

    outcome.memory = variables;
    outcome.emitted = session.emitted;
    outcome.errors = session.errors;
    return true;
}

bool run_program(const CompileResult &compiled,
                 const TargetDescription &target,
                 const CommonDefinitions &definitions,
                 const std::vector<EventToSend> &events,
                 unsigned long step_budget,
                 std::string &report,
                 std::string &error)
{
    RunOutcome outcome;
    if (!execute_program(compiled, target, definitions, events, step_budget, outcome, error))
        return false;
    const std::vector<int16_t> &variables = outcome.memory;
    std::ostringstream out;
    out << "{\n  \"variables\": {";
    bool first = true;
    for (const auto &variable : compiled.variables) {
        out << (first ? "\n" : ",\n") << "    " << json_string(variable.name) << ": ";
        first = false;
        if (variable.size == 1) {
            out << variables[variable.address];
            continue;
        }
        out << "[";
        for (uint16_t i = 0; i < variable.size; ++i)
            out << (i ? ", " : "") << variables[variable.address + i];
        out << "]";
    }
    out << "\n  },\n  \"emitted\": [";
    for (size_t i = 0; i < outcome.emitted.size(); ++i)
        out << (i ? ",\n    " : "\n    ") << outcome.emitted[i];
    out << (outcome.emitted.empty() ? "" : "\n  ") << "],\n  \"errors\": [";
    for (size_t i = 0; i < outcome.errors.size(); ++i)
        out << (i ? ",\n    " : "\n    ") << outcome.errors[i];
    out << (outcome.errors.empty() ? "" : "\n  ") << "],\n  \"unfinished\": [";
    for (size_t i = 0; i < outcome.unfinished.size(); ++i)
        out << (i ? ", " : "") << json_string(outcome.unfinished[i]);
    out << "]\n}\n";
    report = out.str();
    return true;
}

} // namespace aseba
