// The debug commands of bytecode.md §6.4 with their EXECUTION_STATE_CHANGED
// answers, breakpoints (§6.3) and the step budget of vm_run (§6.2).

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/assembler.hpp"
#include "tests/support/vm_harness.hpp"

namespace
{

using test_support::VmHarness;
using test_support::VmMessage;

VmMessage state(uint16_t pc, uint16_t flags)
{
    VmMessage message;
    message.kind = VmMessage::STATE;
    message.pc = pc;
    message.flags = flags;
    return message;
}

std::vector<std::string> described(const std::vector<VmMessage> &log)
{
    std::vector<std::string> lines;
    for (const VmMessage &message : log)
        lines.push_back(describe(message));
    return lines;
}

// Compares the log with `expected` and empties it.
void expect_log(VmHarness &harness, const std::vector<VmMessage> &expected)
{
    EXPECT_EQ(described(harness.log), described(expected));
    harness.log.clear();
}

// Event 0 at `zero`, init at `init`; both add to counters.
const char two_events[] = R"(
event 0 zero
event init init
zero:
    LOAD 41             ; at 5
    SMALL_IMMEDIATE 1
    BINARY_ARITHMETIC ADD
    STORE 41
    STOP                ; at 9
init:
    SMALL_IMMEDIATE 5   ; at 10
    STORE 40
    SMALL_IMMEDIATE 6
    STORE 42
    STOP                ; at 14
)";

// Init counts loop iterations in V[40]; each iteration is 5 instructions.
const char endless_loop[] = R"(
event init start
start:
    SMALL_IMMEDIATE 0   ; at 3
    STORE 40
loop:
    LOAD 40             ; at 5
    SMALL_IMMEDIATE 1
    BINARY_ARITHMETIC ADD
    STORE 40
    JUMP loop           ; at 9
)";

constexpr uint16_t STEP_BY_STEP = VM_FLAG_STEP_BY_STEP;
constexpr uint16_t ACTIVE = VM_FLAG_EVENT_ACTIVE;
constexpr uint16_t RUNNING = VM_FLAG_EVENT_RUNNING;

std::vector<uint16_t> words(const char *listing)
{
    return test_support::assemble(listing).words;
}

TEST(DebugCommands, SetBytecodeAnswersInitAddressPausedThenRunStartsIt)
{
    VmHarness harness;
    std::vector<uint16_t> image = words(two_events);
    vm_set_bytecode(&harness.vm, 0, image.data(), static_cast<uint16_t>(image.size()));
    expect_log(harness, { state(10, ACTIVE | STEP_BY_STEP) });
    EXPECT_FALSE(vm_run(&harness.vm, 0)) << "paused after an upload";
    EXPECT_EQ(harness.variables()[40], 0);

    vm_command_run(&harness.vm);
    expect_log(harness, { state(10, ACTIVE) });
    EXPECT_TRUE(vm_run(&harness.vm, 0));
    EXPECT_EQ(harness.variables()[40], 5);
    EXPECT_EQ(harness.vm.flags, 0);
    EXPECT_EQ(harness.vm.pc, 14);
    EXPECT_TRUE(harness.log.empty());
    EXPECT_FALSE(vm_run(&harness.vm, 0)) << "nothing left to run";
}

TEST(DebugCommands, SetBytecodeInPiecesUsesTheStartAddress)
{
    VmHarness harness;
    std::vector<uint16_t> image = words(two_events);
    vm_set_bytecode(&harness.vm, 5, image.data() + 5, static_cast<uint16_t>(image.size() - 5));
    harness.log.clear();
    vm_set_bytecode(&harness.vm, 0, image.data(), 5);
    expect_log(harness, { state(10, ACTIVE | STEP_BY_STEP) });
    for (size_t i = 0; i < image.size(); i++)
        EXPECT_EQ(harness.bytecode()[i], image[i]) << "word " << i;
}

TEST(DebugCommands, SetBytecodeIgnoresWordsBeyondTheBytecode)
{
    test_support::VmSizes sizes;
    sizes.bytecode = 16;
    VmHarness harness(sizes);
    std::vector<uint16_t> image(40, 0x1001);
    image[0] = 1;
    vm_set_bytecode(&harness.vm, 10, image.data(), static_cast<uint16_t>(image.size()));
    vm_set_bytecode(&harness.vm, 200, image.data(), static_cast<uint16_t>(image.size()));
    EXPECT_TRUE(harness.guards_intact());
    EXPECT_EQ(harness.bytecode()[15], 0x1001);
}

TEST(DebugCommands, ResetWithoutInitAnswersTheStalePcStopped)
{
    VmHarness harness;
    harness.load(words(two_events));
    vm_command_run(&harness.vm);
    vm_run(&harness.vm, 0); // init ends on its STOP at 14
    harness.log.clear();

    // The same handlers without init: pc keeps its old value.
    std::vector<uint16_t> image = words("event 0 zero\nzero: STOP\n");
    vm_set_bytecode(&harness.vm, 0, image.data(), static_cast<uint16_t>(image.size()));
    expect_log(harness, { state(14, STEP_BY_STEP) });
    vm_reset(&harness.vm);
    expect_log(harness, { state(14, STEP_BY_STEP) });
}

TEST(DebugCommands, ResetKillsTheActiveEventSilentlyAndPreparesInit)
{
    VmHarness harness;
    harness.load(words(endless_loop));
    vm_command_run(&harness.vm);
    vm_run(&harness.vm, 100);
    harness.log.clear();
    ASSERT_EQ(harness.vm.flags, ACTIVE);

    vm_reset(&harness.vm);
    expect_log(harness, { state(3, ACTIVE | STEP_BY_STEP) });
    EXPECT_EQ(harness.vm.sp, -1);
}

TEST(DebugCommands, StopAbandonsTheEventAndAnswersPcAndTwo)
{
    VmHarness harness;
    harness.load(words(endless_loop));
    vm_command_run(&harness.vm);
    vm_run(&harness.vm, 7); // 2 setup instructions + 5: back at the loop start
    harness.log.clear();
    ASSERT_EQ(harness.vm.pc, 5);

    vm_command_stop(&harness.vm);
    expect_log(harness, { state(5, STEP_BY_STEP) });
    EXPECT_FALSE(vm_run(&harness.vm, 10));
    vm_command_run(&harness.vm);
    expect_log(harness, { state(5, 0) });
    EXPECT_FALSE(vm_run(&harness.vm, 10)) << "the event was abandoned";
    EXPECT_EQ(harness.variables()[40], 1);
}

TEST(DebugCommands, PauseAnswersTheFlagsAndStopsRunning)
{
    VmHarness harness;
    harness.load(words(endless_loop));
    vm_command_run(&harness.vm);
    vm_run(&harness.vm, 12);
    harness.log.clear();
    ASSERT_EQ(harness.vm.pc, 5);

    vm_command_pause(&harness.vm);
    expect_log(harness, { state(5, ACTIVE | STEP_BY_STEP) });
    EXPECT_FALSE(vm_run(&harness.vm, 10));
    EXPECT_EQ(harness.variables()[40], 2);
    vm_report_state(&harness.vm);
    expect_log(harness, { state(5, ACTIVE | STEP_BY_STEP) });

    vm_command_run(&harness.vm);
    expect_log(harness, { state(5, ACTIVE) });
    EXPECT_TRUE(vm_run(&harness.vm, 5));
    EXPECT_EQ(harness.variables()[40], 3);
}

TEST(DebugCommands, PauseWhileIdleAnswersTwo)
{
    VmHarness harness;
    harness.load(words(two_events));
    vm_command_run(&harness.vm);
    vm_run(&harness.vm, 0);
    harness.log.clear();
    vm_command_pause(&harness.vm);
    expect_log(harness, { state(14, STEP_BY_STEP) });
}

TEST(DebugCommands, StepExecutesOneInstructionAndAnswers)
{
    VmHarness harness;
    harness.load(words(two_events));
    vm_command_step(&harness.vm); // SMALL_IMMEDIATE 5
    expect_log(harness, { state(11, ACTIVE | STEP_BY_STEP) });
    vm_command_step(&harness.vm); // STORE 40
    expect_log(harness, { state(12, ACTIVE | STEP_BY_STEP) });
    EXPECT_EQ(harness.variables()[40], 5);
    EXPECT_EQ(harness.variables()[42], 0);
    vm_command_step(&harness.vm);
    vm_command_step(&harness.vm);
    vm_command_step(&harness.vm); // STOP
    expect_log(harness,
               { state(13, ACTIVE | STEP_BY_STEP),
                 state(14, ACTIVE | STEP_BY_STEP),
                 state(14, STEP_BY_STEP) });
    EXPECT_EQ(harness.variables()[42], 6);

    // No active event: nothing executes and nothing is answered.
    vm_command_step(&harness.vm);
    EXPECT_TRUE(harness.log.empty());
    EXPECT_FALSE(vm_step(&harness.vm));
    EXPECT_EQ(harness.vm.pc, 14);
}

TEST(DebugCommands, EventWhilePausedAndIdleIsPreparedForStepping)
{
    VmHarness harness;
    harness.load(words(two_events));
    vm_command_stop(&harness.vm);
    harness.log.clear();
    EXPECT_EQ(vm_setup_event(&harness.vm, 0), 5);
    expect_log(harness, { state(5, ACTIVE | STEP_BY_STEP) });
    EXPECT_EQ(vm_setup_event(&harness.vm, 7), 0) << "not handled";
    EXPECT_TRUE(harness.log.empty());
    vm_command_step(&harness.vm);
    expect_log(harness, { state(6, ACTIVE | STEP_BY_STEP) });
    // A network event is dropped while paused inside a handler (§6.4, §7).
    int16_t payload[] = { 3 };
    vm_receive_event(&harness.vm, 0, 9, payload, 1);
    EXPECT_TRUE(harness.log.empty());
    EXPECT_EQ(harness.vm.pc, 6);
    EXPECT_EQ(harness.variables()[VM_NAMED_SOURCE], 0);
}

TEST(DebugCommands, SetupEventKillsTheActiveOneWithItsPc)
{
    VmHarness harness;
    harness.load(words(two_events));
    vm_command_step(&harness.vm);
    vm_command_step(&harness.vm);
    harness.log.clear();
    EXPECT_EQ(vm_setup_event(&harness.vm, 0), 5);
    expect_log(harness,
               { [] {
                    VmMessage killed;
                    killed.kind = VmMessage::KILLED;
                    killed.pc = 12;
                    return killed;
                }(),
                 state(5, ACTIVE | STEP_BY_STEP) });
}

// --- breakpoints (§6.3) -------------------------------------------------------

TEST(Breakpoints, SixteenFitTheSeventeenthIsRejected)
{
    VmHarness harness;
    for (uint16_t i = 0; i < VM_MAX_BREAKPOINTS; i++)
        EXPECT_TRUE(vm_breakpoint_set(&harness.vm, static_cast<uint16_t>(20 + i))) << i;
    EXPECT_FALSE(vm_breakpoint_set(&harness.vm, 100));
    vm_breakpoint_clear(&harness.vm, 25);
    EXPECT_TRUE(vm_breakpoint_set(&harness.vm, 100)) << "clearing made room";
    EXPECT_FALSE(vm_breakpoint_set(&harness.vm, 101));
    vm_breakpoint_clear_all(&harness.vm);
    for (uint16_t i = 0; i < VM_MAX_BREAKPOINTS; i++)
        EXPECT_TRUE(vm_breakpoint_set(&harness.vm, 7)) << "duplicates are accepted";
}

TEST(Breakpoints, BeyondTheBytecodeAreRejected)
{
    VmHarness harness; // 256 words of bytecode
    EXPECT_FALSE(vm_breakpoint_set(&harness.vm, 256));
    EXPECT_FALSE(vm_breakpoint_set(&harness.vm, 0xFFFF));
    EXPECT_TRUE(vm_breakpoint_set(&harness.vm, 255));
    EXPECT_TRUE(vm_breakpoint_set(&harness.vm, 0));
}

TEST(Breakpoints, HitBeforeTheFirstInstructionOfAHandler)
{
    VmHarness harness;
    harness.load(words(two_events));
    ASSERT_TRUE(vm_breakpoint_set(&harness.vm, 10));
    vm_command_run(&harness.vm);
    harness.log.clear();
    EXPECT_TRUE(vm_run(&harness.vm, 0));
    expect_log(harness, { state(10, ACTIVE | STEP_BY_STEP | RUNNING) });
    EXPECT_EQ(harness.vm.pc, 10);
    EXPECT_EQ(harness.vm.sp, -1);
    EXPECT_EQ(harness.variables()[40], 0) << "nothing executed";
    EXPECT_FALSE(vm_run(&harness.vm, 0)) << "paused on the breakpoint";

    // RUN alone stops again on the same breakpoint: STEP, then RUN.
    vm_command_run(&harness.vm);
    harness.log.clear();
    EXPECT_TRUE(vm_run(&harness.vm, 0));
    expect_log(harness, { state(10, ACTIVE | STEP_BY_STEP | RUNNING) });
    vm_command_step(&harness.vm);
    expect_log(harness, { state(11, ACTIVE | STEP_BY_STEP | RUNNING) });
    vm_command_run(&harness.vm);
    expect_log(harness, { state(11, ACTIVE | RUNNING) });
    EXPECT_TRUE(vm_run(&harness.vm, 0));
    EXPECT_TRUE(harness.log.empty());
    EXPECT_EQ(harness.variables()[40], 5);
    EXPECT_EQ(harness.variables()[42], 6);
    EXPECT_EQ(harness.vm.flags, 0);
}

TEST(Breakpoints, HitInsideALoopEveryIteration)
{
    VmHarness harness;
    harness.load(words(endless_loop));
    ASSERT_TRUE(vm_breakpoint_set(&harness.vm, 8)); // STORE 40
    vm_command_run(&harness.vm);
    harness.log.clear();
    for (int iteration = 1; iteration <= 3; iteration++) {
        SCOPED_TRACE(iteration);
        EXPECT_TRUE(vm_run(&harness.vm, 0));
        expect_log(harness, { state(8, ACTIVE | STEP_BY_STEP | RUNNING) });
        EXPECT_EQ(harness.variables()[40], iteration - 1) << "STORE not yet executed";
        vm_command_step(&harness.vm);
        EXPECT_EQ(harness.variables()[40], iteration);
        vm_command_run(&harness.vm);
        harness.log.clear();
    }
    // Cleared: the loop runs until the budget ends it.
    vm_breakpoint_clear(&harness.vm, 8);
    EXPECT_TRUE(vm_run(&harness.vm, 50));
    EXPECT_TRUE(harness.log.empty());
    EXPECT_EQ(harness.variables()[40], 13);
}

TEST(Breakpoints, ClearRemovesOnlyTheFirstMatchAndKeepsTheOthers)
{
    VmHarness harness;
    harness.load(words(endless_loop));
    ASSERT_TRUE(vm_breakpoint_set(&harness.vm, 6));
    ASSERT_TRUE(vm_breakpoint_set(&harness.vm, 8));
    ASSERT_TRUE(vm_breakpoint_set(&harness.vm, 6));
    ASSERT_TRUE(vm_breakpoint_set(&harness.vm, 9));
    vm_breakpoint_clear(&harness.vm, 6); // one copy of 6 remains
    vm_breakpoint_clear(&harness.vm, 8);
    vm_breakpoint_clear(&harness.vm, 77); // not set: nothing happens
    vm_command_run(&harness.vm);
    harness.log.clear();

    std::vector<uint16_t> hits;
    for (int i = 0; i < 4; i++) {
        vm_run(&harness.vm, 0);
        hits.push_back(harness.vm.pc);
        vm_command_step(&harness.vm);
        vm_command_run(&harness.vm);
    }
    EXPECT_EQ(hits, (std::vector<uint16_t>{ 6, 9, 6, 9 }));

    vm_breakpoint_clear_all(&harness.vm);
    harness.log.clear();
    EXPECT_TRUE(vm_run(&harness.vm, 100));
    EXPECT_TRUE(harness.log.empty());
}

TEST(Breakpoints, StepIgnoresThem)
{
    VmHarness harness;
    harness.load(words(two_events));
    ASSERT_TRUE(vm_breakpoint_set(&harness.vm, 10));
    ASSERT_TRUE(vm_breakpoint_set(&harness.vm, 11));
    vm_command_step(&harness.vm);
    vm_command_step(&harness.vm);
    EXPECT_EQ(harness.vm.pc, 12);
    EXPECT_EQ(harness.variables()[40], 5);
}

// --- the step budget (§6.2) ---------------------------------------------------

TEST(StepBudget, ARunEndsAfterExactlyTheBudgetAndGoesOnAtTheNextCall)
{
    VmHarness harness;
    harness.load(words(endless_loop));
    vm_command_run(&harness.vm);
    harness.log.clear();

    // 2 setup instructions, then 5 per iteration.
    EXPECT_TRUE(vm_run(&harness.vm, 1000));
    EXPECT_EQ(harness.variables()[40], (1000 - 2) / 5); // 199 iterations + 3 instructions
    EXPECT_EQ(harness.vm.pc, 8);                        // LOAD, SMALL_IMMEDIATE, ADD done
    EXPECT_EQ(harness.vm.sp, 0);
    EXPECT_EQ(harness.vm.flags, ACTIVE);
    EXPECT_TRUE(vm_run(&harness.vm, 1000));
    EXPECT_EQ(harness.variables()[40], (2000 - 2) / 5);
    EXPECT_EQ(harness.vm.pc, 5 + (2000 - 2) % 5);
    for (int i = 0; i < 10; i++)
        vm_run(&harness.vm, 1);
    EXPECT_EQ(harness.variables()[40], (2010 - 2) / 5);
    EXPECT_TRUE(vm_run(&harness.vm, 65535));
    EXPECT_EQ(harness.variables()[40], (2010 + 65535 - 2) / 5);
    EXPECT_TRUE(harness.log.empty()) << "a spent budget is not reported";
}

TEST(StepBudget, ZeroRunsATerminatingHandlerToItsEnd)
{
    // 20000 iterations of 7 instructions: more than 65535 instructions.
    const char counting[] = R"(
event init start
start:
    SMALL_IMMEDIATE 0
    STORE 40
loop:
    LOAD 40
    LARGE_IMMEDIATE 20000
    CONDITIONAL_BRANCH SMALLER_THAN done
    LOAD 40
    SMALL_IMMEDIATE 1
    BINARY_ARITHMETIC ADD
    STORE 40
    JUMP loop
done:
    STOP
)";
    VmHarness harness;
    harness.load(words(counting));
    vm_command_run(&harness.vm);
    EXPECT_TRUE(vm_run(&harness.vm, 0));
    EXPECT_EQ(harness.variables()[40], 20000);
    EXPECT_EQ(harness.vm.flags, 0);
}

TEST(StepBudget, RunAndStepReturnWhetherAnEventWasActive)
{
    VmHarness harness;
    EXPECT_FALSE(vm_run(&harness.vm, 0)) << "no bytecode yet";
    EXPECT_FALSE(vm_step(&harness.vm));
    harness.load(words(two_events));
    EXPECT_FALSE(vm_run(&harness.vm, 0)) << "paused";
    EXPECT_TRUE(vm_step(&harness.vm)) << "stepping works while paused";
    vm_command_run(&harness.vm);
    EXPECT_TRUE(vm_run(&harness.vm, 0));
    EXPECT_FALSE(vm_run(&harness.vm, 0));
}

} // namespace
