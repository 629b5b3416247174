#include "tests/vm/reference_node.hpp"

#include <algorithm>
#include <csetjmp>
#include <cstring>
#include <map>
#include <stdexcept>

// Debian builds the library with ASEBA_ASSERT: it calls AsebaAssert.
#define ASEBA_ASSERT 1
extern "C" {
#include <aseba/common/consts.h>
#include <aseba/vm/vm.h>
}

namespace vm_tests
{

using test_support::VmMessage;

struct ReferenceNode::State {
    AsebaVMState vm;
    std::jmp_buf on_assert; // where AsebaAssert returns to
};

namespace
{

// The reference's glue functions are global: they find their node here.
std::map<const AsebaVMState *, ReferenceNode *> &nodes()
{
    static std::map<const AsebaVMState *, ReferenceNode *> registry;
    return registry;
}

std::map<const AsebaVMState *, ReferenceNode::State *> &states()
{
    static std::map<const AsebaVMState *, ReferenceNode::State *> registry;
    return registry;
}

ReferenceNode &node_of(const AsebaVMState *vm)
{
    auto found = nodes().find(vm);
    if (found == nodes().end())
        throw std::logic_error("reference VM without a node");
    return *found->second;
}

uint16_t word_at(const uint8_t *bytes, size_t index)
{
    return static_cast<uint16_t>(bytes[2 * index] | (bytes[2 * index + 1] << 8));
}

// Calls into the reference so that one of its assertions comes back here
// as `asserted` rather than ending the process.
template<typename Call>
void guarded(ReferenceNode &node, ReferenceNode::State *state, Call call)
{
    if (setjmp(state->on_assert) == 0)
        call();
    else
        node.asserted = true;
}

int16_t pop(AsebaVMState *vm)
{
    return vm->stack[vm->sp--];
}

// As vm_variables(): `length` words from `address`, or NULL after an error.
int16_t *reference_variables(AsebaVMState *vm, uint16_t address, uint16_t length)
{
    if (address >= vm->variablesSize || length > vm->variablesSize - address) {
        AsebaVMEmitNodeSpecificError(vm, "out of variables bounds");
        return nullptr;
    }
    return vm->variables + address;
}

} // namespace

ReferenceNode::ReferenceNode(const test_support::VmSizes &sizes, uint16_t node_id)
  : sizes_(sizes)
  , bytecode_(sizes.bytecode)
  , variables_(sizes.variables)
  , stack_(sizes.stack)
  , state_(new State)
{
    std::memset(&state_->vm, 0, sizeof state_->vm);
    AsebaVMState &vm = state_->vm;
    vm.nodeId = node_id;
    vm.bytecodeSize = sizes.bytecode;
    vm.bytecode = bytecode_.data();
    vm.variablesSize = sizes.variables;
    vm.variables = variables_.data();
    vm.stackSize = sizes.stack;
    vm.stack = stack_.data();
    nodes()[&vm] = this;
    states()[&vm] = state_;
    AsebaVMInit(&vm);
}

ReferenceNode::~ReferenceNode()
{
    nodes().erase(&state_->vm);
    states().erase(&state_->vm);
    delete state_;
}

void ReferenceNode::debug_message(uint16_t type, std::vector<uint16_t> payload)
{
    payload.insert(payload.begin(), state_->vm.nodeId); // the destination
    guarded(*this, state_, [&] {
        AsebaVMDebugMessage(
          &state_->vm, type, payload.data(), static_cast<uint16_t>(payload.size()));
    });
}

void ReferenceNode::set_bytecode(uint16_t start, const std::vector<uint16_t> &words)
{
    std::vector<uint16_t> payload{ start };
    payload.insert(payload.end(), words.begin(), words.end());
    debug_message(ASEBA_MESSAGE_SET_BYTECODE, payload);
}

void ReferenceNode::reset()
{
    debug_message(ASEBA_MESSAGE_RESET, {});
}

void ReferenceNode::run_command()
{
    debug_message(ASEBA_MESSAGE_RUN, {});
}

void ReferenceNode::pause()
{
    debug_message(ASEBA_MESSAGE_PAUSE, {});
}

void ReferenceNode::step()
{
    debug_message(ASEBA_MESSAGE_STEP, {});
}

void ReferenceNode::stop()
{
    debug_message(ASEBA_MESSAGE_STOP, {});
}

void ReferenceNode::get_execution_state()
{
    debug_message(ASEBA_MESSAGE_GET_EXECUTION_STATE, {});
}

void ReferenceNode::breakpoint_set(uint16_t pc)
{
    debug_message(ASEBA_MESSAGE_BREAKPOINT_SET, { pc });
}

void ReferenceNode::breakpoint_clear(uint16_t pc)
{
    debug_message(ASEBA_MESSAGE_BREAKPOINT_CLEAR, { pc });
}

void ReferenceNode::breakpoint_clear_all()
{
    debug_message(ASEBA_MESSAGE_BREAKPOINT_CLEAR_ALL, {});
}

void ReferenceNode::receive_event(uint16_t event,
                                  uint16_t source,
                                  const std::vector<int16_t> &payload)
{
    const uint16_t paused_in_event = ASEBA_VM_STEP_BY_STEP_MASK | ASEBA_VM_EVENT_ACTIVE_MASK;
    if ((state_->vm.flags & paused_in_event) == paused_in_event)
        return;
    variables_[VM_NAMED_SOURCE] = static_cast<int16_t>(source);
    size_t count = std::min<size_t>(payload.size(), sizes_.args);
    std::copy(payload.begin(), payload.begin() + count, variables_.begin() + VM_NAMED_ARGS);
    setup_event(event);
}

uint16_t ReferenceNode::setup_event(uint16_t event)
{
    uint16_t address = 0;
    guarded(*this, state_, [&] { address = AsebaVMSetupEvent(&state_->vm, event); });
    return address;
}

bool ReferenceNode::run(uint16_t step_budget)
{
    uint16_t result = 0;
    guarded(*this, state_, [&] { result = AsebaVMRun(&state_->vm, step_budget); });
    return result != 0;
}

uint16_t ReferenceNode::pc() const
{
    return state_->vm.pc;
}

int16_t ReferenceNode::sp() const
{
    return state_->vm.sp;
}

uint16_t ReferenceNode::flags() const
{
    return state_->vm.flags;
}

} // namespace vm_tests

// --- the glue the reference library calls -------------------------------------

using test_support::VmMessage;
using vm_tests::ReferenceNode;

extern "C" {

void AsebaSendMessage(AsebaVMState *vm, uint16_t id, const void *data, uint16_t size)
{
    ReferenceNode &node = vm_tests::node_of(vm);
    const uint8_t *bytes = static_cast<const uint8_t *>(data);
    VmMessage message;
    switch (id) {
    case ASEBA_MESSAGE_ARRAY_ACCESS_OUT_OF_BOUNDS:
        message.kind = VmMessage::ARRAY_ACCESS;
        message.pc = vm_tests::word_at(bytes, 0);
        message.size = vm_tests::word_at(bytes, 1);
        message.index = vm_tests::word_at(bytes, 2);
        break;
    case ASEBA_MESSAGE_DIVISION_BY_ZERO:
        message.kind = VmMessage::DIVISION_BY_ZERO;
        message.pc = vm_tests::word_at(bytes, 0);
        break;
    case ASEBA_MESSAGE_EVENT_EXECUTION_KILLED:
        message.kind = VmMessage::KILLED;
        message.pc = vm_tests::word_at(bytes, 0);
        break;
    case ASEBA_MESSAGE_NODE_SPECIFIC_ERROR:
        message.kind = VmMessage::NODE_ERROR;
        message.pc = vm_tests::word_at(bytes, 0);
        message.text.assign(reinterpret_cast<const char *>(bytes + 3), bytes[2]);
        break;
    case ASEBA_MESSAGE_EXECUTION_STATE_CHANGED:
        message.kind = VmMessage::STATE;
        message.pc = vm_tests::word_at(bytes, 0);
        message.flags = vm_tests::word_at(bytes, 1);
        break;
    case ASEBA_MESSAGE_BREAKPOINT_SET_RESULT:
        node.breakpoint_results.push_back(vm_tests::word_at(bytes, 1) != 0);
        return;
    default:
        if (id >= 0x8000)
            throw std::logic_error("unexpected message from the reference VM");
        message.kind = VmMessage::EMIT;
        message.pc = id;
        for (size_t i = 0; i < size / 2u; i++)
            message.payload.push_back(static_cast<int16_t>(vm_tests::word_at(bytes, i)));
    }
    node.log.push_back(message);
}

// The natives of tests/support/vm_harness.hpp, on the reference's stack.
void AsebaNativeFunction(AsebaVMState *vm, uint16_t id)
{
    using vm_tests::pop;
    using vm_tests::reference_variables;
    switch (id) {
    case test_support::NATIVE_SUBTRACT: {
        uint16_t dest = pop(vm), a = pop(vm), b = pop(vm);
        int16_t *d = reference_variables(vm, dest, 1);
        int16_t *x = reference_variables(vm, a, 1);
        int16_t *y = reference_variables(vm, b, 1);
        if (d && x && y)
            *d = static_cast<int16_t>(*x - *y);
        break;
    }
    case test_support::NATIVE_FILL: {
        uint16_t dest = pop(vm), value = pop(vm), size = pop(vm);
        int16_t *d = reference_variables(vm, dest, size);
        int16_t *v = reference_variables(vm, value, 1);
        for (uint16_t i = 0; d && v && i < size; i++)
            d[i] = *v;
        break;
    }
    case test_support::NATIVE_REACH: {
        uint16_t address = pop(vm), length = pop(vm);
        int16_t *first = reference_variables(vm, address, length);
        for (uint16_t i = 0; first && i < length; i++)
            first[i] = 7;
        break;
    }
    case test_support::NATIVE_YIELD: vm->flags &= ~ASEBA_VM_EVENT_RUNNING_MASK; break;
    case test_support::NATIVE_STAT: throw std::logic_error("stat is not used with the reference");
    default: AsebaVMEmitNodeSpecificError(vm, test_support::test_native_failure_text); break;
    }
}

void AsebaAssert(AsebaVMState *vm, AsebaAssertReason reason)
{
    ReferenceNode &node = vm_tests::node_of(vm);
    node.assert_reason = reason;
    std::longjmp(vm_tests::states().at(vm)->on_assert, 1);
}

void AsebaSendVariables(AsebaVMState *, uint16_t, uint16_t) {}
void AsebaSendDescription(AsebaVMState *) {}
void AsebaWriteBytecode(AsebaVMState *) {}
void AsebaResetIntoBootloader(AsebaVMState *) {}
void AsebaPutVmToSleep(AsebaVMState *) {}

} // extern "C"
