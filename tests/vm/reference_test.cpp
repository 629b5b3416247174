// Differential tests against Debian's reference VM (libasebavm 1.6.99): the
// same bytecode, initial variables, commands and events go to both VMs, and
// after every step their messages (emits, errors with payloads, kills,
// EXECUTION_STATE_CHANGED), variables, pc, sp and flags must agree. Programs
// avoid what bytecode.md §11 lists as deliberate differences.

#include <map>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "tests/support/assembler.hpp"
#include "tests/support/vm_harness.hpp"
#include "tests/vm/random_program.hpp"
#include "tests/vm/reference_node.hpp"

namespace
{

using test_support::VmHarness;
using test_support::VmMessage;
using vm_tests::RandomProgramLayout;
using vm_tests::ReferenceNode;

constexpr unsigned PROGRAM_COUNT = 2000;
constexpr unsigned ACTIONS_PER_PROGRAM = 24;
constexpr uint32_t SEED = 20261122;

test_support::VmSizes layout_sizes()
{
    test_support::VmSizes sizes;
    sizes.bytecode = RandomProgramLayout::BYTECODE;
    sizes.variables = RandomProgramLayout::VARIABLES;
    sizes.stack = RandomProgramLayout::STACK;
    sizes.args = RandomProgramLayout::ARGS;
    return sizes;
}

// Both VMs, driven in lockstep.
class TwoVms
{
  public:
    TwoVms()
      : ours(layout_sizes())
      , theirs(layout_sizes())
    {
    }

    VmHarness ours;
    ReferenceNode theirs;
    std::vector<std::string> trace;           // the commands so far, for failure reports
    std::map<VmMessage::Kind, unsigned> seen; // messages of each kind, for coverage

    // Empty when both agree; else what differs. Clears both logs.
    std::string differences();
};

std::string TwoVms::differences()
{
    std::ostringstream out;
    std::vector<std::string> a, b;
    for (const VmMessage &message : ours.log) {
        a.push_back(describe(message));
        seen[message.kind]++;
    }
    for (const VmMessage &message : theirs.log)
        b.push_back(describe(message));
    if (a != b) {
        out << "messages differ:\n  ours:";
        for (const std::string &line : a)
            out << "\n    " << line;
        out << "\n  reference:";
        for (const std::string &line : b)
            out << "\n    " << line;
        out << "\n";
    }
    ours.log.clear();
    theirs.log.clear();
    if (theirs.asserted)
        out << "the reference asserted (reason " << theirs.assert_reason << ")\n";
    for (uint16_t i = 0; i < RandomProgramLayout::VARIABLES; i++) {
        if (ours.variables()[i] != theirs.variables()[i])
            out << "V[" << i << "]: ours " << ours.variables()[i] << ", reference "
                << theirs.variables()[i] << "\n";
    }
    if (ours.vm.pc != theirs.pc())
        out << "pc: ours " << ours.vm.pc << ", reference " << theirs.pc() << "\n";
    if (ours.vm.sp != theirs.sp())
        out << "sp: ours " << ours.vm.sp << ", reference " << theirs.sp() << "\n";
    if (ours.vm.flags != theirs.flags())
        out << "flags: ours " << ours.vm.flags << ", reference " << theirs.flags() << "\n";
    for (size_t i = 0; i < theirs.bytecode().size(); i++) {
        if (ours.bytecode()[i] != theirs.bytecode()[i]) {
            out << "B[" << i << "]: ours " << ours.bytecode()[i] << ", reference "
                << theirs.bytecode()[i] << "\n";
            break;
        }
    }
    if (!ours.guards_intact())
        out << "our VM wrote outside its arrays\n";
    return out.str();
}

// One random command to both VMs; returns its description.
std::string random_action(TwoVms &vms, std::mt19937 &random, uint16_t image_size)
{
    auto uniform = [&](int low, int high) {
        return std::uniform_int_distribution<int>(low, high)(random);
    };
    std::ostringstream what;
    int roll = uniform(1, 100);
    vm_state *vm = &vms.ours.vm;
    if (roll <= 35) {
        static const uint16_t budgets[] = { 0, 0, 1, 2, 3, 5, 17, 100, 1000 };
        uint16_t budget = budgets[uniform(0, std::size(budgets) - 1)];
        what << "run " << budget;
        bool a = vm_run(vm, budget);
        bool b = vms.theirs.run(budget);
        if (a != b)
            what << " [returned " << a << " vs reference " << b << "]";
    } else if (roll <= 55) {
        uint16_t event = uniform(0, 3) == 0 ? vm_tests::random_program_unhandled_event
                                            : static_cast<uint16_t>(uniform(0, 1));
        uint16_t source = static_cast<uint16_t>(uniform(0, 65535));
        std::vector<int16_t> payload(uniform(0, 12));
        for (int16_t &word : payload)
            word = static_cast<int16_t>(uniform(-32768, 32767));
        what << "receive " << event << " (" << payload.size() << " words)";
        vm_receive_event(vm, event, source, payload.data(), static_cast<uint16_t>(payload.size()));
        vms.theirs.receive_event(event, source, payload);
    } else if (roll <= 62) {
        // A local event, set up by the node glue when not paused in an event.
        const uint16_t paused_in_event = VM_FLAG_STEP_BY_STEP | VM_FLAG_EVENT_ACTIVE;
        what << "local event";
        if ((vm->flags & paused_in_event) != paused_in_event) {
            uint16_t a = vm_setup_event(vm, 0xFFFE);
            uint16_t b = vms.theirs.setup_event(0xFFFE);
            if (a != b)
                what << " [address " << a << " vs reference " << b << "]";
        }
    } else if (roll <= 72) {
        what << "RUN";
        vm_command_run(vm);
        vms.theirs.run_command();
    } else if (roll <= 75) {
        what << "PAUSE";
        vm_command_pause(vm);
        vms.theirs.pause();
    } else if (roll <= 83) {
        what << "STEP";
        vm_command_step(vm);
        vms.theirs.step();
    } else if (roll <= 85) {
        what << "STOP";
        vm_command_stop(vm);
        vms.theirs.stop();
    } else if (roll <= 87) {
        what << "RESET";
        vm_reset(vm);
        vms.theirs.reset();
    } else if (roll <= 89) {
        what << "GET_EXECUTION_STATE";
        vm_report_state(vm);
        vms.theirs.get_execution_state();
    } else if (roll <= 96) {
        uint16_t pc = static_cast<uint16_t>(uniform(19, image_size - 1));
        what << "BREAKPOINT_SET " << pc;
        bool a = vm_breakpoint_set(vm, pc);
        vms.theirs.breakpoint_results.clear();
        vms.theirs.breakpoint_set(pc);
        bool b = vms.theirs.breakpoint_results.size() == 1 && vms.theirs.breakpoint_results[0];
        if (a != b)
            what << " [result " << a << " vs reference " << b << "]";
    } else if (roll <= 98) {
        uint16_t pc = vm->breakpoint_count > 0
                        ? vm->breakpoints[uniform(0, vm->breakpoint_count - 1)]
                        : static_cast<uint16_t>(uniform(0, image_size));
        what << "BREAKPOINT_CLEAR " << pc;
        vm_breakpoint_clear(vm, pc);
        vms.theirs.breakpoint_clear(pc);
    } else {
        what << "BREAKPOINT_CLEAR_ALL";
        vm_breakpoint_clear_all(vm);
        vms.theirs.breakpoint_clear_all();
    }
    return what.str();
}

TEST(ReferenceVm, RandomProgramsBehaveAlike)
{
    std::mt19937 random(SEED);
    std::map<VmMessage::Kind, unsigned> seen;
    unsigned compared = 0, breakpoint_hits = 0;
    unsigned failures = 0;
    for (unsigned n = 0; n < PROGRAM_COUNT && failures < 3; n++) {
        // The failing native also has its own test (HandMadeBytecodeBehavesAlike).
        vm_tests::RandomProgramOptions options;
        options.failing_native = true;
        std::string listing = vm_tests::random_program(random, options);
        std::vector<uint16_t> image = test_support::assemble(listing).words;
        if (image.size() > RandomProgramLayout::BYTECODE)
            continue;
        TwoVms vms;
        for (uint16_t i = 10; i < RandomProgramLayout::VARIABLES; i++) {
            int16_t value =
              static_cast<int16_t>(std::uniform_int_distribution<int>(-40, 40)(random));
            vms.ours.variables()[i] = value;
            vms.theirs.variables()[i] = value;
        }
        vms.trace.push_back("SET_BYTECODE (" + std::to_string(image.size()) + " words)");
        vm_set_bytecode(&vms.ours.vm, 0, image.data(), static_cast<uint16_t>(image.size()));
        vms.theirs.set_bytecode(0, image);
        std::string difference = vms.differences();
        for (unsigned a = 0; a < ACTIONS_PER_PROGRAM && difference.empty(); a++) {
            vms.trace.push_back(random_action(vms, random, static_cast<uint16_t>(image.size())));
            for (const VmMessage &message : vms.ours.log)
                if (message.kind == VmMessage::STATE && message.flags == 7)
                    breakpoint_hits++;
            difference = vms.differences();
        }
        for (auto [kind, count] : vms.seen)
            seen[kind] += count;
        compared++;
        if (!difference.empty()) {
            failures++;
            std::ostringstream report;
            report << "program " << n << ":\n" << difference << "commands:";
            for (const std::string &line : vms.trace)
                report << "\n  " << line;
            report << "\nlisting:\n" << listing;
            ADD_FAILURE() << report.str();
        }
    }
    EXPECT_GE(compared, PROGRAM_COUNT * 9 / 10);
    // The programs must reach what they are meant to compare.
    EXPECT_GT(seen[VmMessage::EMIT], PROGRAM_COUNT / 2);
    EXPECT_GT(seen[VmMessage::ARRAY_ACCESS], PROGRAM_COUNT / 20);
    EXPECT_GT(seen[VmMessage::DIVISION_BY_ZERO], PROGRAM_COUNT / 50);
    EXPECT_GT(seen[VmMessage::KILLED], PROGRAM_COUNT / 20);
    EXPECT_GT(seen[VmMessage::STATE], PROGRAM_COUNT);
    EXPECT_GT(breakpoint_hits, PROGRAM_COUNT / 20);
    std::cout << "compared " << compared << " programs; messages: " << seen[VmMessage::EMIT]
              << " emits, " << seen[VmMessage::ARRAY_ACCESS] << " array errors, "
              << seen[VmMessage::DIVISION_BY_ZERO] << " divisions by zero, "
              << seen[VmMessage::KILLED] << " kills, " << seen[VmMessage::NODE_ERROR]
              << " node errors, " << seen[VmMessage::STATE] << " states (" << breakpoint_hits
              << " breakpoint hits)\n";
}

// Runs `listing` on both VMs: upload, RUN, run; then `then` on both.
std::string run_both(const std::string &listing, uint16_t budget = 0)
{
    std::vector<uint16_t> image = test_support::assemble(listing).words;
    TwoVms vms;
    vm_set_bytecode(&vms.ours.vm, 0, image.data(), static_cast<uint16_t>(image.size()));
    vms.theirs.set_bytecode(0, image);
    vm_command_run(&vms.ours.vm);
    vms.theirs.run_command();
    std::string difference = vms.differences();
    vm_run(&vms.ours.vm, budget);
    vms.theirs.run(budget);
    difference += vms.differences();
    vm_run(&vms.ours.vm, budget);
    vms.theirs.run(budget);
    return difference + vms.differences();
}

// The spec's hand-made cases that were verified against upstream (§10 end).
TEST(ReferenceVm, HandMadeBytecodeBehavesAlike)
{
    const char *const listings[] = {
        // CONDITIONAL_BRANCH with DIV by zero
        "event init s\ns: SMALL_IMMEDIATE 5\nSMALL_IMMEDIATE 0\n"
        "CONDITIONAL_BRANCH DIV f\nSMALL_IMMEDIATE 1\nSTORE 40\nf: STOP\n",
        // SMALL_IMMEDIATE -2048, LARGE_IMMEDIATE with operand bits
        "event init s\ns: .word 0x1800\nSTORE 40\n.word 0x2FFF 1234\nSTORE 41\nSTOP\n",
        // a negative index reported as 65535
        "event init s\ns: SMALL_IMMEDIATE 1\nSMALL_IMMEDIATE -1\nSTORE_INDIRECT 40 3\nSTOP\n",
        // EMIT 0xFFF of length 0
        "event init s\ns: EMIT 0xFFF 0 0\nSTOP\n",
        // STOP with operand bits, SUB_RET with operand bits
        "event init s\ns: SUB_CALL t\n.word 0x0123\nt: .word 0xE456\n",
        // a `when` that becomes true
        "event init s\ns: SMALL_IMMEDIATE 1\nSMALL_IMMEDIATE 1\n"
        "CONDITIONAL_BRANCH EQUAL f when\nEMIT 1 0 1\nf: STOP\n",
        // a failing native: where is pc afterwards?
        "event init s\ns: SMALL_IMMEDIATE 1\nNATIVE_CALL 2\nSMALL_IMMEDIATE 2\nSTORE 40\nSTOP\n",
    };
    for (const char *listing : listings) {
        SCOPED_TRACE(listing);
        EXPECT_EQ(run_both(listing), "");
    }
}

// Clearing EVENT_RUNNING during a run (native 4 does it, as an interrupt may)
// ends the run after the current instruction (bytecode.md §6, §6.2).
TEST(ReferenceVm, ClearingEventRunningEndsTheRunAlike)
{
    EXPECT_EQ(run_both("event init s\ns: SMALL_IMMEDIATE 1\nSTORE 40\nNATIVE_CALL 4\n"
                       "SMALL_IMMEDIATE 2\nSTORE 41\nSTOP\n",
                       100),
              "");
}

} // namespace
