#include "reference_node.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

// The reference natives are only called directly here, but its VM object,
// which holds AsebaVMEmitNodeSpecificError, needs the whole glue interface
// ("functions implemented outside" in its vm.h). Messages go to the node
// being called; the rest must never be reached.
namespace
{
ReferenceNode *current_node = nullptr;

// No exception may cross the reference's C frames: stop loudly instead.
[[noreturn]] void unexpected(const char *what)
{
    std::fprintf(stderr, "reference VM called %s\n", what);
    std::abort();
}
} // namespace

extern "C" {
void AsebaSendMessage(AsebaVMState *, uint16_t id, const void *data, uint16_t size)
{
    if (current_node == nullptr)
        unexpected("AsebaSendMessage outside a call");
    ReferenceMessage message{ id, {}, {} };
    const auto *bytes = static_cast<const uint8_t *>(data);
    message.payload_bytes.assign(bytes, bytes + size);
    for (uint16_t i = 0; i + 1 < size; i += 2) {
        uint16_t word;
        std::memcpy(&word, bytes + i, sizeof word);
        message.payload_words.push_back(word);
    }
    current_node->messages.push_back(message);
}

void AsebaSendVariables(AsebaVMState *, uint16_t, uint16_t)
{
    unexpected("AsebaSendVariables");
}

void AsebaSendDescription(AsebaVMState *)
{
    unexpected("AsebaSendDescription");
}

void AsebaNativeFunction(AsebaVMState *, uint16_t)
{
    unexpected("AsebaNativeFunction");
}

void AsebaWriteBytecode(AsebaVMState *)
{
    unexpected("AsebaWriteBytecode");
}

void AsebaResetIntoBootloader(AsebaVMState *)
{
    unexpected("AsebaResetIntoBootloader");
}

void AsebaPutVmToSleep(AsebaVMState *)
{
    unexpected("AsebaPutVmToSleep");
}

// Debian builds its VM with assertions; the natives never assert, the
// interpreter (unused here) might.
void AsebaAssert(AsebaVMState *, int)
{
    unexpected("AsebaAssert");
}
}

namespace
{
constexpr uint16_t bytecode_words = 16;
constexpr uint16_t stack_words = 32;
} // namespace

ReferenceNode::ReferenceNode(uint16_t variables_size)
  : variables(variables_size)
  , bytecode_(bytecode_words)
  , stack_(stack_words)
{
    std::memset(&vm, 0, sizeof vm);
    vm.nodeId = 1;
    vm.bytecodeSize = bytecode_words;
    vm.bytecode = bytecode_.data();
    vm.variablesSize = variables_size;
    vm.variables = variables.data();
    vm.stackSize = stack_words;
    vm.stack = stack_.data();
    vm.sp = -1;
}

ReferenceNode::~ReferenceNode() = default;

void ReferenceNode::call(AsebaNativeFunctionPointer native,
                         const std::vector<int16_t> &popped_words)
{
    vm.variables = variables.data();
    vm.sp = -1;
    for (auto word = popped_words.rbegin(); word != popped_words.rend(); ++word)
        stack_[++vm.sp] = *word;
    vm.pc = call_pc;
    vm.flags = ASEBA_VM_EVENT_ACTIVE_MASK | ASEBA_VM_EVENT_RUNNING_MASK;
    current_node = this;
    native(&vm);
    current_node = nullptr;
    if (vm.sp != -1)
        throw std::logic_error("reference native left " + std::to_string(vm.sp + 1) +
                               " words on the stack");
}
