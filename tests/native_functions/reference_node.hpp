// Debian's Aseba VM library (the oracle) set up like OurNode: its natives
// pop their arguments from the VM stack and report errors as messages.
#pragma once

#include <cstdint>
#include <vector>

extern "C" {
#include <aseba/vm/natives.h>
#include <aseba/vm/vm.h>
#include <aseba/common/consts.h>
}

// The reference's integer helpers, exported by its natives.c but not declared
// in its headers.
extern "C" {
int16_t aseba_sin(int16_t angle);
int16_t aseba_cos(int16_t angle);
int16_t aseba_sqrt(int16_t value);
int16_t aseba_atan2(int16_t y, int16_t x);
}

// One message the reference sent through AsebaSendMessage.
struct ReferenceMessage {
    uint16_t type;
    std::vector<uint16_t> payload_words;
    std::vector<uint8_t> payload_bytes;
};

class ReferenceNode
{
  public:
    static constexpr uint16_t call_pc = 321; // as OurNode's

    explicit ReferenceNode(uint16_t variables_size);
    ~ReferenceNode();
    ReferenceNode(const ReferenceNode &) = delete;
    ReferenceNode &operator=(const ReferenceNode &) = delete;

    // Pushes the words so that the native pops them in the given order, then
    // calls it inside a running event; checks it popped them all.
    void call(AsebaNativeFunctionPointer native, const std::vector<int16_t> &popped_words);

    bool stopped() const
    {
        return (vm.flags & ASEBA_VM_EVENT_ACTIVE_MASK) == 0;
    }

    std::vector<int16_t> variables;
    std::vector<ReferenceMessage> messages;
    AsebaVMState vm;

  private:
    std::vector<uint16_t> bytecode_;
    std::vector<int16_t> stack_;
};
