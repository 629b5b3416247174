// The load-time verifier (vm/vm_verify.c): what it refuses, where and why,
// what it must accept (every shape of code a compiler emits, and code that
// only fails at run time), and its anchors on every memory size. A refused
// program reports its fault when a host sends RUN, and nothing of it runs.

#include <gtest/gtest.h>

#include <optional>
#include <sstream>

#include "tests/support/assembler.hpp"
#include "tests/support/native_table.hpp"
#include "tests/support/vm_harness.hpp"

namespace
{

using test_support::VmHarness;
using test_support::VmMessage;
using test_support::VmSizes;

VmSizes sizes(uint16_t bytecode, uint16_t variables, uint16_t stack)
{
    VmSizes result;
    result.bytecode = bytecode;
    result.variables = variables;
    result.stack = stack;
    return result;
}

struct Verdict {
    const char *error; // nullptr: accepted
    uint16_t pc;
};

constexpr Verdict accepted = { nullptr, 0 };

// Uploads `listing` and asks it to run; returns what the VM said of it.
Verdict verdict_of(VmHarness &harness, const std::string &listing)
{
    harness.load(test_support::assemble(listing).words);
    vm_command_run(&harness.vm);
    const vm_state &vm = harness.vm;
    std::optional<VmMessage> error;
    for (const VmMessage &message : harness.log)
        if (message.kind == VmMessage::NODE_ERROR)
            error = message;
    if (vm.rejection == nullptr) {
        EXPECT_FALSE(error) << "accepted, yet RUN reported " << describe(*error);
        return accepted;
    }
    // RUN reports the rejection as a run-time error, at its pc, and stops.
    EXPECT_TRUE(error && error->text == vm.rejection && error->pc == vm.rejection_pc);
    EXPECT_EQ(vm.flags, VM_FLAG_STEP_BY_STEP);
    EXPECT_FALSE(vm_run(&harness.vm, 0)) << "a refused program ran";
    return { vm.rejection, vm.rejection_pc };
}

struct Case {
    const char *what;
    std::string listing;
    Verdict expected;
    VmSizes memory = VmSizes(); // bytecode 256, variables 64, stack 32
};

std::ostream &operator<<(std::ostream &out, const Verdict &verdict)
{
    if (verdict.error == nullptr)
        return out << "accepted";
    return out << "refused at " << verdict.pc << ": " << verdict.error;
}

void check_cases(const std::vector<Case> &cases)
{
    for (const Case &c : cases) {
        SCOPED_TRACE(c.what);
        VmHarness harness(c.memory);
        const Verdict got = verdict_of(harness, c.listing);
        const bool same = (got.error == nullptr) == (c.expected.error == nullptr) &&
                          (got.error == nullptr ||
                           (std::string(got.error) == c.expected.error && got.pc == c.expected.pc));
        EXPECT_TRUE(same) << "got " << got << ", expected " << c.expected << "\n" << c.listing;
        EXPECT_TRUE(harness.guards_intact());
    }
}

// Programs start at word 3, after a one-entry event table.
std::string init(const std::string &code)
{
    return "event init start\nstart:\n" + code;
}

const char *const variables_bounds = "out of variables bounds";
const char *const bytecode_bounds = "out of bytecode bounds";
const char *const underflow = "stack underflow";
const char *const invalid_jump = "invalid jump";
const char *const unknown_operator = "unknown operator";
const char *const unknown_native = "unknown native function";

TEST(Verifier, RefusesAddressesOutsideTheVariables)
{
    check_cases({
      { "LOAD past the end", init("LOAD 64\nSTORE 40\nSTOP\n"), { variables_bounds, 3 } },
      { "STORE past the end",
        init("SMALL_IMMEDIATE 5\nSTORE 64\nSTOP\n"),
        { variables_bounds, 4 } },
      { "STORE far", init("SMALL_IMMEDIATE 5\nSTORE 4095\nSTOP\n"), { variables_bounds, 4 } },
      { "LOAD of the last word", init("LOAD 63\nSTORE 0\nSTOP\n"), accepted },
      { "LOAD_INDIRECT array past the end",
        init("SMALL_IMMEDIATE 5\nLOAD_INDIRECT 60 10\nSTORE 40\nSTOP\n"),
        { variables_bounds, 4 } },
      { "STORE_INDIRECT array past the end",
        init("SMALL_IMMEDIATE 1\nSMALL_IMMEDIATE 4\nSTORE_INDIRECT 60 8\nSTOP\n"),
        { variables_bounds, 5 } },
      { "LOAD_INDIRECT array of 65535 words",
        init("SMALL_IMMEDIATE 0\nLOAD_INDIRECT 50 0xFFFF\nSTORE 40\nSTOP\n"),
        { variables_bounds, 4 } },
      { "arrays up to the last word",
        init("SMALL_IMMEDIATE 0\nLOAD_INDIRECT 60 4\nSMALL_IMMEDIATE 3\nSTORE_INDIRECT 0 64\n"
             "STOP\n"),
        accepted },
      { "EMIT of 259 words", init("EMIT 1 0 259\nSTOP\n"), { "emitted event too large", 3 } },
      { "EMIT past the end",
        init("EMIT 1 290 11\nSTOP\n"),
        { variables_bounds, 3 },
        sizes(64, 300, 8) },
      { "EMIT from the end",
        init("EMIT 1 300 1\nSTOP\n"),
        { variables_bounds, 3 },
        sizes(64, 300, 8) },
      { "EMIT wrapping around", init("EMIT 1 0xFFFF 2\nSTOP\n"), { variables_bounds, 3 } },
      { "EMIT of nothing at the end", init("EMIT 1 64 0\nSTOP\n"), accepted },
    });
}

TEST(Verifier, RefusesUnknownInstructionsOperatorsAndNatives)
{
    check_cases({
      { "opcode 0xF",
        init("SMALL_IMMEDIATE 1\nSTORE 40\n.word 0xF000\nSTOP\n"),
        { "unknown bytecode", 5 } },
      { "opcode 0xF with operand", init(".word 0xFFFF\n"), { "unknown bytecode", 3 } },
      { "unary NOT (compiler-only)",
        init("SMALL_IMMEDIATE 1\nUNARY_ARITHMETIC NOT\nSTORE 40\nSTOP\n"),
        { unknown_operator, 4 } },
      { "unary 4",
        init("SMALL_IMMEDIATE 1\nUNARY_ARITHMETIC 4\nSTORE 40\nSTOP\n"),
        { unknown_operator, 4 } },
      { "binary 18",
        init("SMALL_IMMEDIATE 1\nSMALL_IMMEDIATE 2\nBINARY_ARITHMETIC 18\nSTORE 40\nSTOP\n"),
        { unknown_operator, 5 } },
      { "binary 255",
        init("SMALL_IMMEDIATE 1\nSMALL_IMMEDIATE 2\nBINARY_ARITHMETIC 255\nSTORE 40\nSTOP\n"),
        { unknown_operator, 5 } },
      { "branch 18",
        init("SMALL_IMMEDIATE 1\nSMALL_IMMEDIATE 2\nCONDITIONAL_BRANCH 18 end\nend: STOP\n"),
        { unknown_operator, 5 } },
      { "operator bits 11..8 are ignored, as upstream",
        init("SMALL_IMMEDIATE 1\nSMALL_IMMEDIATE 2\n.word 0x8F02\nSTORE 40\nSTOP\n"),
        accepted },
      { "native past the table", init("NATIVE_CALL 12\nSTOP\n"), { unknown_native, 3 } },
      { "native far past the table", init("NATIVE_CALL 4095\nSTOP\n"), { unknown_native, 3 } },
    });
}

TEST(Verifier, RefusesANativeThatTakesMoreWordsThanTheVmPasses)
{
    static const char description[] = {
        VM_MAX_NATIVE_ARGUMENTS + 1, 'g', 'r', 'e', 'e', 'd', 'y', '\x1F', '\x11', 'x', '\0'
    };
    static const vm_native natives[] = { { [](vm_state *, const int16_t *) {}, description } };
    static const test_support::OneModuleTable table(natives, 1);
    VmHarness harness(VmSizes(), 1, table);
    std::string pushes;
    for (int i = 0; i <= VM_MAX_NATIVE_ARGUMENTS; i++)
        pushes += "SMALL_IMMEDIATE 0\n";
    const Verdict got = verdict_of(harness, init(pushes + "NATIVE_CALL 0\nSTOP\n"));
    EXPECT_STREQ(got.error, unknown_native);
    EXPECT_EQ(got.pc, 3 + VM_MAX_NATIVE_ARGUMENTS + 1);
}

TEST(Verifier, RefusesEveryPopOfAValueTheCodeDidNotPush)
{
    check_cases({
      { "STORE", init("STORE 40\nSTOP\n"), { underflow, 3 } },
      { "BINARY_ARITHMETIC",
        init("SMALL_IMMEDIATE 1\nBINARY_ARITHMETIC ADD\nSTOP\n"),
        { underflow, 4 } },
      { "UNARY_ARITHMETIC", init("UNARY_ARITHMETIC SUB\nSTOP\n"), { underflow, 3 } },
      { "LOAD_INDIRECT", init("LOAD_INDIRECT 40 2\nSTOP\n"), { underflow, 3 } },
      { "STORE_INDIRECT",
        init("SMALL_IMMEDIATE 0\nSTORE_INDIRECT 40 2\nSTOP\n"),
        { underflow, 4 } },
      { "CONDITIONAL_BRANCH",
        init("SMALL_IMMEDIATE 0\nCONDITIONAL_BRANCH EQUAL end\nend: STOP\n"),
        { underflow, 4 } },
      { "NATIVE_CALL",
        init("SMALL_IMMEDIATE 40\nSMALL_IMMEDIATE 41\nNATIVE_CALL 0\nSTOP\n"),
        { underflow, 5 } },
      // A subroutine starts with an empty stack of its own: the return
      // address below it is not the subroutine's to pop.
      { "a subroutine popping its return address",
        init("SUB_CALL sub\nSTOP\nsub: STORE 50\nLOAD 50\nSUB_RET\n"),
        { underflow, 5 } },
      { "code after STOP starts empty",
        "event init start\nevent 0 after\nstart: SMALL_IMMEDIATE 1\nSTOP\n"
        "after: STORE 40\nSTOP\n",
        { underflow, 7 } },
    });
}

TEST(Verifier, RefusesJumpsThatDoNotLandOnAnInstructionWithAnEmptyStack)
{
    check_cases({
      { "JUMP with a value on the stack",
        init("SMALL_IMMEDIATE 1\nJUMP end\nend: STOP\n"),
        { invalid_jump, 4 } },
      { "branch leaving a value",
        init("SMALL_IMMEDIATE 1\nSMALL_IMMEDIATE 1\nSMALL_IMMEDIATE 1\n"
             "CONDITIONAL_BRANCH EQUAL end\nSTORE 40\nend: STOP\n"),
        { invalid_jump, 6 } },
      { "SUB_RET leaving a value",
        init("SUB_CALL sub\nSTOP\nsub: SMALL_IMMEDIATE 1\nSUB_RET\n"),
        { invalid_jump, 6 } },
      { "JUMP into the operand of LARGE_IMMEDIATE",
        init("JUMP 2\nLARGE_IMMEDIATE 0\nSTORE 40\nSTOP\n"),
        { invalid_jump, 3 } },
      { "branch into its own operand word",
        init("SMALL_IMMEDIATE 1\nSMALL_IMMEDIATE 1\nCONDITIONAL_BRANCH EQUAL 1\nSTOP\n"),
        { invalid_jump, 5 } },
      { "JUMP where a value is on the stack",
        init("JUMP inside\nSTOP\nSMALL_IMMEDIATE 1\ninside: STORE 40\nSTOP\n"),
        { invalid_jump, 3 } },
      { "JUMP into the event table", init("JUMP -3\n"), { invalid_jump, 3 } },
      { "SUB_CALL into an expression",
        init("SUB_CALL 8\nSTOP\nsub: SMALL_IMMEDIATE 1\nSMALL_IMMEDIATE 2\nBINARY_ARITHMETIC ADD\n"
             "STORE 40\nSUB_RET\n"),
        { invalid_jump, 3 } },
      { "an event address inside an instruction",
        "event init 5\nSMALL_IMMEDIATE 1\nLARGE_IMMEDIATE 0x4028\nSTOP\n",
        { invalid_jump, 2 } },
      { "an event address inside the table",
        "event init 1\nevent 0 start\nstart: STOP\n",
        { invalid_jump, 2 } },
      { "a backward branch to a loop head",
        init("SMALL_IMMEDIATE 0\nSTORE 40\nloop: LOAD 40\nSMALL_IMMEDIATE 3\n"
             "CONDITIONAL_BRANCH SMALLER_THAN done\nLOAD 40\nSMALL_IMMEDIATE 1\n"
             "BINARY_ARITHMETIC ADD\nSTORE 40\nJUMP loop\ndone: STOP\n"),
        accepted },
    });
}

TEST(Verifier, RefusesCodeThatLeavesTheBytecode)
{
    check_cases({
      { "JUMP forward past the end",
        init("JUMP 2047\n"),
        { bytecode_bounds, 3 },
        sizes(64, 64, 8) },
      { "JUMP backward below 0", init("JUMP -2048\n"), { bytecode_bounds, 3 }, sizes(64, 64, 8) },
      { "branch past the end",
        init("SMALL_IMMEDIATE 1\nSMALL_IMMEDIATE 1\nCONDITIONAL_BRANCH EQUAL 100\nSTOP\n"),
        { bytecode_bounds, 5 },
        sizes(64, 64, 8) },
      { "SUB_CALL past the end",
        init("SUB_CALL 4095\n"),
        { bytecode_bounds, 3 },
        sizes(64, 64, 8) },
      { "falling off the end",
        init("SMALL_IMMEDIATE 1\nSTORE 40\n"),
        { bytecode_bounds, 4 },
        sizes(5, 64, 8) },
      { "a table larger than the bytecode",
        ".raw\n.word 9 0xFFFF 3 0\n",
        { bytecode_bounds, 0 },
        sizes(8, 64, 8) },
      { "an event address past the end",
        ".raw\n.word 3 0xFFFF 100\n",
        { bytecode_bounds, 2 },
        sizes(8, 64, 8) },
    });
}

TEST(Verifier, AcceptsWhatOnlyRunTimeValuesMakeFail)
{
    // These stay run-time errors, reported when reached (programs/*.asm):
    // recursion (stack overflow), SUB_RET outside a call, indexes, division.
    check_cases({
      { "recursion", init("SUB_CALL sub\nSTOP\nsub: SUB_CALL sub\nSUB_RET\n"), accepted },
      { "SUB_RET in an event", init("SUB_RET\n"), accepted },
      { "an index from a variable",
        init("LOAD 2\nLOAD_INDIRECT 40 4\nSTORE 50\nSTOP\n"),
        accepted },
      { "division by a variable",
        init("SMALL_IMMEDIATE 1\nLOAD 2\nBINARY_ARITHMETIC DIV\nSTORE 50\nSTOP\n"),
        accepted },
      { "a push beyond a small stack",
        init("SMALL_IMMEDIATE 1\nSMALL_IMMEDIATE 2\nSMALL_IMMEDIATE 3\nBINARY_ARITHMETIC ADD\n"
             "BINARY_ARITHMETIC ADD\nSTORE 40\nSTOP\n"),
        accepted,
        sizes(64, 64, 2) },
    });
}

TEST(Verifier, LooksOnlyAtCodeThatCanRun)
{
    check_cases({
      { "an empty bytecode", ".raw\n", accepted, sizes(0, 64, 8) },
      { "no event table", ".raw\n.word 0\n", accepted },
      { "a table with no entries", ".raw\n.word 1 0xF000\n", accepted },
      { "a handler address of 0 (not handled)", ".raw\n.word 3 0xFFFF 0 0xF000\n", accepted },
      // An older, longer program may follow the new one: it never runs.
      { "words after the last instruction",
        init("SMALL_IMMEDIATE 1\nSTORE 40\nSTOP\n.word 0xF000 0x4FFF 0x9800\n"),
        accepted },
      { "dead code after STOP with values left",
        init("STOP\nSMALL_IMMEDIATE 1\nSMALL_IMMEDIATE 2\nSTOP\n"),
        accepted },
      { "a subroutine never called", init("STOP\nsub: LOAD 40\nSTORE 41\nSUB_RET\n"), accepted },
    });
}

// Jumps are checked by walking from the anchor before their target; anchors
// live in the stack memory, so every stack size must give the same verdicts.
TEST(Verifier, GivesTheSameVerdictsWhateverTheStackSize)
{
    // A long program whose jumps reach far back and far forward, with long
    // expressions (the stack is not empty for dozens of words, across
    // anchored positions), and one bad target at the very end or inside an
    // expression; and its good twin.
    std::ostringstream code;
    code << "event init start\nevent 0 other\nstart:\n";
    for (int i = 0; i < 60; i++) {
        code << "L" << i << ": LOAD 40\nSMALL_IMMEDIATE " << i << "\nCONDITIONAL_BRANCH EQUAL L"
             << (i * 7) % 60 << "\nLARGE_IMMEDIATE 7\nSTORE 41\n";
        if (i % 20 == 10) {
            for (int j = 0; j < 30; j++)
                code << (j == 15 ? "middle" + std::to_string(i) + ": " : "")
                     << "SMALL_IMMEDIATE 1\n";
            for (int j = 0; j < 29; j++)
                code << "BINARY_ARITHMETIC ADD\n";
            code << "STORE 42\n";
        }
    }
    code << "STOP\nother: JUMP last\nlast:\n";
    const std::string good = code.str() + "STOP\n";
    const std::string bad = code.str() + "JUMP 2\nLARGE_IMMEDIATE 1\nSTOP\n";
    const uint16_t bad_pc = static_cast<uint16_t>(test_support::assemble(bad).words.size() - 4);
    const std::string into_expression = code.str() + "JUMP middle30\n";
    const uint16_t into_pc =
      static_cast<uint16_t>(test_support::assemble(into_expression).words.size() - 1);
    for (uint16_t stack : { 0, 1, 2, 3, 7, 32, 500, 1000 }) {
        SCOPED_TRACE("stack " + std::to_string(stack));
        check_cases({ { "good", good, accepted, sizes(1000, 64, stack) },
                      { "bad", bad, { invalid_jump, bad_pc }, sizes(1000, 64, stack) },
                      { "into an expression",
                        into_expression,
                        { invalid_jump, into_pc },
                        sizes(1000, 64, stack) } });
    }
}

// A program arrives in chunks, the first ones incomplete: uploads are
// answered as upstream answers them, whatever the verdict, and a refused
// program reports its fault when asked to run or to step, never running.
TEST(Verifier, AnswersUploadsAsUpstreamAndRefusesToRunOrStep)
{
    VmHarness harness;
    harness.load({}); // an empty node
    const auto words = test_support::assemble(init("LOAD 40\nSTORE 41\nLOAD 99\nSTOP\n")).words;
    vm_set_bytecode(&harness.vm, 0, words.data(), static_cast<uint16_t>(words.size()));
    ASSERT_EQ(harness.log.size(), 1u);
    EXPECT_EQ(describe(harness.log[0]), "state pc=3 flags=3") << "init prepared, paused";
    EXPECT_STREQ(harness.vm.rejection, variables_bounds);

    harness.log.clear();
    vm_command_step(&harness.vm);
    ASSERT_EQ(harness.log.size(), 2u);
    EXPECT_EQ(describe(harness.log[0]), "error node_specific pc=5 \"out of variables bounds\"");
    EXPECT_EQ(describe(harness.log[1]), "state pc=5 flags=2");
    EXPECT_EQ(harness.variables()[41], 0) << "nothing ran";
    EXPECT_FALSE(vm_run(&harness.vm, 0));
}

// The first reset of a program clears the was-true bits of the branches it
// reaches (bytecode.md §5.1), and only of them.
TEST(Verifier, ClearsTheWasTrueBitsOfTheCode)
{
    VmHarness harness;
    harness.load(test_support::assemble(init("LOAD 40\nSMALL_IMMEDIATE 0\n"
                                             "CONDITIONAL_BRANCH BIGGER_THAN end when was_true\n"
                                             "end: STOP\n.word 0xA30C\n"))
                   .words);
    EXPECT_EQ(harness.bytecode()[5], 0xA10C);
    EXPECT_EQ(harness.bytecode()[8], 0xA30C) << "a word after the code is not an instruction";
}

} // namespace
