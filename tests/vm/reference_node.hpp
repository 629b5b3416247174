// Debian's reference VM (libasebavm, upstream 1.6.99) behind the same
// interface as tests/support/vm_harness.hpp, so that a test can drive both
// VMs with the same commands and compare what they say. Only tests use it.
//
// The reference reaches its node through global glue functions
// (AsebaSendMessage, AsebaNativeFunction, ...); they are defined in
// reference_node.cpp and find the ReferenceNode that owns the VM.

#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tests/support/vm_harness.hpp"

namespace vm_tests
{

class ReferenceNode
{
  public:
    explicit ReferenceNode(const test_support::VmSizes &sizes, uint16_t node_id = 1);
    ~ReferenceNode();
    ReferenceNode(const ReferenceNode &) = delete;
    ReferenceNode &operator=(const ReferenceNode &) = delete;

    // Messages in the harness' form; BREAKPOINT_SET_RESULT answers apart.
    std::vector<test_support::VmMessage> log;
    std::vector<bool> breakpoint_results;
    // Set when the reference hit one of its debug assertions (AsebaAssert).
    bool asserted = false;
    int assert_reason = 0;

    // The debug commands, sent as the protocol messages the reference parses.
    void set_bytecode(uint16_t start, const std::vector<uint16_t> &words);
    void reset();
    void run_command();
    void pause();
    void step();
    void stop();
    void get_execution_state();
    void breakpoint_set(uint16_t pc);
    void breakpoint_clear(uint16_t pc);
    void breakpoint_clear_all();

    // The node glue of bytecode.md §7 for a user event from the network.
    void receive_event(uint16_t event, uint16_t source, const std::vector<int16_t> &payload);
    uint16_t setup_event(uint16_t event);
    bool run(uint16_t step_budget);

    uint16_t pc() const;
    int16_t sp() const;
    uint16_t flags() const;
    int16_t *variables()
    {
        return variables_.data();
    }
    const std::vector<uint16_t> &bytecode() const
    {
        return bytecode_;
    }

    // Storage of the reference's AsebaVMState (opaque here).
    struct State;

  private:
    void debug_message(uint16_t type, std::vector<uint16_t> payload);

    test_support::VmSizes sizes_;
    std::vector<uint16_t> bytecode_;
    std::vector<int16_t> variables_;
    std::vector<int16_t> stack_;
    State *state_;
};

} // namespace vm_tests
