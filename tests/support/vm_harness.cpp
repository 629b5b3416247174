#include "tests/support/vm_harness.hpp"

#include <algorithm>
#include <sstream>

#include "tests/support/native_table.hpp"

// Under AddressSanitizer the guard words are also poisoned, so that a read
// outside the VM's arrays is caught as well as a write (gcc and clang name
// the feature differently).
#if defined(__SANITIZE_ADDRESS__)
#define HARNESS_POISONS_GUARDS 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HARNESS_POISONS_GUARDS 1
#endif
#endif
#ifdef HARNESS_POISONS_GUARDS
#include <sanitizer/asan_interface.h>
#endif

namespace test_support
{

const char test_native_failure_text[] = "test failure";

namespace
{

VmHarness &harness_of(void *context)
{
    return *static_cast<VmHarness *>(context);
}

VmMessage make_message(VmMessage::Kind kind)
{
    VmMessage message;
    message.kind = kind;
    return message;
}

void record(void *context, VmMessage message)
{
    harness_of(context).log.push_back(std::move(message));
}

void on_emit(void *context, uint16_t event, const int16_t *payload, uint16_t count)
{
    VmMessage message = make_message(VmMessage::EMIT);
    message.pc = event;
    message.payload.assign(payload, payload + count);
    record(context, message);
}

void on_state(void *context, uint16_t pc, uint16_t flags)
{
    VmMessage message = make_message(VmMessage::STATE);
    message.pc = pc;
    message.flags = flags;
    record(context, message);
}

void on_killed(void *context, uint16_t pc)
{
    VmMessage message = make_message(VmMessage::KILLED);
    message.pc = pc;
    record(context, message);
}

void on_array_access(void *context, uint16_t pc, uint16_t size, uint16_t index)
{
    VmMessage message = make_message(VmMessage::ARRAY_ACCESS);
    message.pc = pc;
    message.size = size;
    message.index = index;
    record(context, message);
}

void on_division_by_zero(void *context, uint16_t pc)
{
    VmMessage message = make_message(VmMessage::DIVISION_BY_ZERO);
    message.pc = pc;
    record(context, message);
}

void on_node_error(void *context, uint16_t pc, const char *text)
{
    VmMessage message = make_message(VmMessage::NODE_ERROR);
    message.pc = pc;
    message.text = text;
    record(context, message);
}

// The VM's word reports, each to its record (and a count that does not
// match its type to an error record, which no test expects).
void on_report(void *context, uint16_t type, const uint16_t *words, uint16_t count)
{
    if (type == VM_REPORT_EXECUTION_STATE_CHANGED && count == 2)
        on_state(context, words[0], words[1]);
    else if (type == VM_REPORT_EVENT_EXECUTION_KILLED && count == 1)
        on_killed(context, words[0]);
    else if (type == VM_REPORT_ARRAY_ACCESS_OUT_OF_BOUNDS && count == 3)
        on_array_access(context, words[0], words[1], words[2]);
    else if (type == VM_REPORT_DIVISION_BY_ZERO && count == 1)
        on_division_by_zero(context, words[0]);
    else
        on_node_error(context, count > 0 ? words[0] : 0, "unexpected report");
}

const vm_callbacks harness_callbacks = { on_emit, on_report, on_node_error };

void native_subtract(vm_state *vm, const int16_t *arguments)
{
    int16_t *dest = vm_variables(vm, static_cast<uint16_t>(arguments[0]), 1);
    int16_t *a = vm_variables(vm, static_cast<uint16_t>(arguments[1]), 1);
    int16_t *b = vm_variables(vm, static_cast<uint16_t>(arguments[2]), 1);
    if (dest && a && b)
        *dest = static_cast<int16_t>(*a - *b);
}

void native_fail(vm_state *vm, const int16_t *)
{
    vm_error_node_specific(vm, test_native_failure_text);
}

void native_fill(vm_state *vm, const int16_t *arguments)
{
    uint16_t size = static_cast<uint16_t>(arguments[2]);
    int16_t *dest = vm_variables(vm, static_cast<uint16_t>(arguments[0]), size);
    int16_t *value = vm_variables(vm, static_cast<uint16_t>(arguments[1]), 1);
    for (uint16_t i = 0; dest && value && i < size; i++)
        dest[i] = *value;
}

void native_reach(vm_state *vm, const int16_t *arguments)
{
    uint16_t length = static_cast<uint16_t>(arguments[1]);
    int16_t *first = vm_variables(vm, static_cast<uint16_t>(arguments[0]), length);
    for (uint16_t i = 0; first && i < length; i++)
        first[i] = 7;
}

void native_yield(vm_state *vm, const int16_t *)
{
    vm->flags &= static_cast<uint16_t>(~VM_FLAG_EVENT_RUNNING);
}

void native_stat(vm_state *vm, const int16_t *arguments)
{
    uint16_t size = static_cast<uint16_t>(arguments[4]);
    const int16_t *source = vm_variables(vm, static_cast<uint16_t>(arguments[0]), size);
    int16_t *outputs[3];
    for (int i = 0; i < 3; i++)
        outputs[i] = vm_variables(vm, static_cast<uint16_t>(arguments[1 + i]), 1);
    if (!source || !outputs[0] || !outputs[1] || !outputs[2] || size == 0)
        return;
    int32_t low = source[0], high = source[0], sum = 0;
    for (uint16_t i = 0; i < size; i++) {
        low = std::min<int32_t>(low, source[i]);
        high = std::max<int32_t>(high, source[i]);
        sum += source[i];
    }
    *outputs[0] = static_cast<int16_t>(low);
    *outputs[1] = static_cast<int16_t>(high);
    *outputs[2] = static_cast<int16_t>(sum / size);
}

// Described by their stack words and names alone (a packed description, vm.h).
const vm_native subtract_native = { native_subtract, "\x03test.subtract" };
const vm_native fill_native = { native_fill, "\x03test.fill" };
const vm_native fail_native = { native_fail, "\x00test.fail" };
const vm_native reach_native = { native_reach, "\x02test.reach" };
const vm_native yield_native = { native_yield, "\x00test.yield" };
const vm_native stat_native = { native_stat, "\x05test.stat" };
const vm_native natives_list[TEST_NATIVE_COUNT] = { subtract_native, fill_native,  fail_native,
                                                    reach_native,    yield_native, fail_native,
                                                    fail_native,     fail_native,  fail_native,
                                                    fail_native,     fail_native,  stat_native };
const OneModuleTable natives_table(natives_list, TEST_NATIVE_COUNT);

template<typename T>
void fill_guards(std::vector<T> &words, size_t guard, uint16_t pattern)
{
    for (size_t i = 0; i < guard; i++) {
        words[i] = static_cast<T>(pattern);
        words[words.size() - 1 - i] = static_cast<T>(pattern);
    }
}

// Marks the guard words at both ends of `words` as out of bounds (true) or
// readable again, when AddressSanitizer is there to watch them.
template<typename T>
void poison_guards(const std::vector<T> &words, size_t guard, bool poisoned)
{
#ifdef HARNESS_POISONS_GUARDS
    const size_t bytes = guard * sizeof(T);
    const T *last_guard = words.data() + words.size() - guard;
    if (poisoned) {
        ASAN_POISON_MEMORY_REGION(words.data(), bytes);
        ASAN_POISON_MEMORY_REGION(last_guard, bytes);
    } else {
        ASAN_UNPOISON_MEMORY_REGION(words.data(), bytes);
        ASAN_UNPOISON_MEMORY_REGION(last_guard, bytes);
    }
#else
    (void)words;
    (void)guard;
    (void)poisoned;
#endif
}

template<typename T>
bool guards_hold(const std::vector<T> &words, size_t guard, uint16_t pattern)
{
    for (size_t i = 0; i < guard; i++) {
        if (static_cast<uint16_t>(words[i]) != pattern ||
            static_cast<uint16_t>(words[words.size() - 1 - i]) != pattern)
            return false;
    }
    return true;
}

} // namespace

std::string describe(const VmMessage &message)
{
    std::ostringstream out;
    switch (message.kind) {
    case VmMessage::EMIT:
        out << "emit " << message.pc << " [";
        for (size_t i = 0; i < message.payload.size(); i++)
            out << (i ? ", " : "") << message.payload[i];
        out << "]";
        break;
    case VmMessage::STATE: out << "state pc=" << message.pc << " flags=" << message.flags; break;
    case VmMessage::KILLED: out << "killed pc=" << message.pc; break;
    case VmMessage::ARRAY_ACCESS:
        out << "error array_access pc=" << message.pc << " size=" << message.size
            << " index=" << message.index;
        break;
    case VmMessage::DIVISION_BY_ZERO: out << "error division_by_zero pc=" << message.pc; break;
    case VmMessage::NODE_ERROR:
        out << "error node_specific pc=" << message.pc << " \"" << message.text << "\"";
        break;
    }
    return out.str();
}

const vm_native_table &test_native_table()
{
    return natives_table.table();
}

VmHarness::VmHarness(const VmSizes &sizes, uint16_t node_id, const vm_native_table &natives)
  : sizes_(sizes)
  , bytecode_(sizes.bytecode + 2 * GUARD_WORDS)
  , variables_(sizes.variables + 2 * GUARD_WORDS)
  , stack_(sizes.stack + 2 * GUARD_WORDS)
{
    fill_guards(bytecode_, GUARD_WORDS, GUARD_PATTERN);
    fill_guards(variables_, GUARD_WORDS, GUARD_PATTERN);
    fill_guards(stack_, GUARD_WORDS, GUARD_PATTERN);
    poison_all_guards(true);
    vm_memory memory = { bytecode(), sizes.bytecode, variables(), sizes.variables,
                         stack(),    sizes.stack,    sizes.args };
    vm_init(&vm, &memory, node_id, &natives, &harness_callbacks, this);
}

void VmHarness::load(const std::vector<uint16_t> &words)
{
    vm_set_bytecode(&vm, 0, words.data(), static_cast<uint16_t>(words.size()));
    log.clear();
}

VmHarness::~VmHarness()
{
    poison_all_guards(false);
}

void VmHarness::poison_all_guards(bool poisoned) const
{
    poison_guards(bytecode_, GUARD_WORDS, poisoned);
    poison_guards(variables_, GUARD_WORDS, poisoned);
    poison_guards(stack_, GUARD_WORDS, poisoned);
}

bool VmHarness::guards_intact() const
{
    poison_all_guards(false);
    bool intact = guards_hold(bytecode_, GUARD_WORDS, GUARD_PATTERN) &&
                  guards_hold(variables_, GUARD_WORDS, GUARD_PATTERN) &&
                  guards_hold(stack_, GUARD_WORDS, GUARD_PATTERN);
    poison_all_guards(true);
    return intact;
}

} // namespace test_support
