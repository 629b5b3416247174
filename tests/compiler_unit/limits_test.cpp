// Every recursive walk of the compiler is bounded: inputs built to nest or
// chain far beyond what a program needs (the 20,000 `elseif`s among
// them) end in a clear error, never in a crash of the compiler's own stack.
// Each case names the construct, how often it repeats, and the start of the
// error it must give.

#include <gtest/gtest.h>

#include "tools/compiler/target_json.hpp"
#include "unit_support.hpp"

namespace aseba::unit
{
namespace
{

struct DeepInput {
    const char *name;
    std::string source;
    const char *error_start;
};

std::string repeat(const std::string &text, int count)
{
    std::string result;
    for (int i = 0; i < count; ++i)
        result += text;
    return result;
}

constexpr int DEEP = 20000;  // far beyond the nesting limit
constexpr int LONG = 100000; // far beyond the expression limit

std::vector<DeepInput> deep_inputs()
{
    const std::string nests = "This program nests too deeply";
    return {
        { "elseif_chain",
          "var x\nif x == 0 then\n" + repeat("elseif x == 1 then\n", DEEP) + "end\n",
          "This program nests too deeply" },
        { "nested_if",
          "var x\n" + repeat("if x == 0 then\n", DEEP) + repeat("end\n", DEEP),
          "This program nests too deeply" },
        { "nested_while",
          "var x\n" + repeat("while x == 0 do\n", DEEP) + repeat("end\n", DEEP),
          "This program nests too deeply" },
        { "parentheses",
          "var x\nx = " + repeat("(", LONG) + "1" + repeat(")", LONG) + "\n",
          "This program nests too deeply" },
        { "unary_minus",
          "var x\nx = " + repeat("- ", LONG) + "x\n",
          "This program nests too deeply" },
        { "not",
          "var x\nif " + repeat("not ", LONG) + "x == 1 then\nend\n",
          "This program nests too deeply" },
        { "tuples",
          "var x[1]\nx = " + repeat("[", LONG) + "1" + repeat("]", LONG) + "\n",
          "This program nests too deeply" },
        { "indexes",
          "var a[2]\na[0] = " + repeat("a[", DEEP) + "0" + repeat("]", DEEP) + "\n",
          "This program nests too deeply" },
        { "calls",
          "var x\nx = " + repeat("f(", DEEP) + "1" + repeat(")", DEEP) +
            "\nsub f(v)\n    return v\n",
          "This program nests too deeply" },
        { "sum", "var x\nx = x" + repeat(" + x", LONG) + "\n", "This expression is too long" },
        { "conjunction",
          "var x\nif x == 1" + repeat(" and x == 1", DEEP) + " then\nend\n",
          "This expression is too long" },
        { "callsub_chain",
          [] {
              std::string text = "callsub s0\n";
              for (int i = 0; i < DEEP; ++i)
                  text +=
                    "sub s" + std::to_string(i) + "\n    callsub s" + std::to_string(i + 1) + "\n";
              return text + "sub s" + std::to_string(DEEP) + "\n";
          }(),
          "Execution stack will overflow" },
        { "call_chain",
          [] {
              std::string text = "var x\nx = f0(1)\n";
              for (int i = 0; i < DEEP; ++i)
                  text += "sub f" + std::to_string(i) + "(v)\n    return f" +
                          std::to_string(i + 1) + "(v)\n";
              return text + "sub f" + std::to_string(DEEP) + "(v)\n    return v\n";
          }(),
          "Not enough variable memory for the locals" }, // one frame after the other
        { "recursion_cycle",
          [] {
              std::string text;
              for (int i = 0; i < DEEP; ++i)
                  text += "sub s" + std::to_string(i) + "\n    callsub s" +
                          std::to_string((i + 1) % DEEP) + "\n";
              return text;
          }(),
          "Recursion is not allowed: sub s0 calls sub s1, which calls sub s2" },
        { "locals",
          [] {
              std::string text = "onevent timer\n";
              for (int i = 0; i < DEEP; ++i)
                  text += "    local a" + std::to_string(i) + "\n";
              return text;
          }(),
          "Not enough variable memory for the locals" },
        { "long_tuple",
          "var x[] = [" + repeat("1, ", LONG) + "1]\n",
          "No more free variable space" },
        { "too_long",
          "var x\n" + repeat("x = 1 # padding to make the text long\n", 40000),
          "This program is " },
    };
}

TEST(CompilerLimits, DeepInputsEndInAClearError)
{
    for (const DeepInput &input : deep_inputs()) {
        CompileResult result = compile_for_dummy(input.source);
        ASSERT_FALSE(result.ok) << input.name;
        EXPECT_EQ(result.error.message.rfind(input.error_start, 0), 0u)
          << input.name << ": " << result.error.message.substr(0, 300);
    }
}

// Just inside the limits, the same constructs compile.
TEST(CompilerLimits, InsideTheLimitsTheyCompile)
{
    std::string elseifs =
      "var x\nif x == 0 then\n" + repeat("elseif x == 1 then\n x = 1\n", 60) + "end\n";
    EXPECT_TRUE(compile_for_dummy(elseifs).ok) << compile_for_dummy(elseifs).error.message;
    std::string parentheses = "var x\nx = " + repeat("(", 250) + "1" + repeat(")", 250) + "\n";
    EXPECT_TRUE(compile_for_dummy(parentheses).ok);
    std::string calls =
      "var x\nx = " + repeat("f(", 30) + "1" + repeat(")", 30) + "\nsub f(v)\n    return v\n";
    EXPECT_TRUE(compile_for_dummy(calls).ok) << compile_for_dummy(calls).error.message;
}

// What the bytecode can encode (spec bytecode.md): NATIVE_CALL names its
// native in a 12-bit operand, so 4,096 natives at most; local event i has id
// 0xFFFE - i, which must stay above the global events' ids (below 0x8000),
// so 32,767 local events at most. A description beyond is refused, whether
// it comes from a file or from a node on the network, rather than compiled
// into calls of the wrong native (the issue: `call n4097(x)` became
// NATIVE_CALL 1) or handlers of a global event (`onevent e39000` got id
// 0x67a6).
struct DescriptionSize {
    const char *name;
    size_t natives;
    size_t local_events;
    const char *program; // for that target
    bool accepted;
    uint16_t expected_word; // accepted: the native call, or the handler's event id
};

const DescriptionSize description_sizes[] = {
    { "last_native", 4096, 0, "call n4095()\n", true, 0xCFFF },
    { "one_native_too_many", 4097, 0, "call n4096()\n", false, 0 },
    { "last_local_event", 0, 32767, "var x\nonevent e32766\nx = 1\n", true, 0x8000 },
    { "one_local_event_too_many", 0, 32768, "var x\nonevent e32767\nx = 1\n", false, 0 },
};

TargetDescription sized_target(const DescriptionSize &size)
{
    TargetDescription target = dummy_target();
    target.native_functions.clear();
    for (size_t i = 0; i < size.natives; i++)
        target.native_functions.push_back({ "n" + std::to_string(i), "", {} });
    target.local_events.clear();
    for (size_t i = 0; i < size.local_events; i++)
        target.local_events.push_back({ "e" + std::to_string(i), "" });
    return target;
}

TEST(DescriptionLimits, TheCompilerRefusesWhatTheBytecodeCannotEncode)
{
    for (const DescriptionSize &size : description_sizes) {
        SCOPED_TRACE(size.name);
        CompileResult result = compile(size.program, sized_target(size), {});
        ASSERT_EQ(result.ok, size.accepted) << result.error.message;
        if (size.accepted) {
            // The native call is the first word of code; the handler's event
            // id the first of the event table's pairs (the init code is empty).
            uint16_t word = size.natives > 0 ? code_of(result).front() : result.bytecode.at(1);
            EXPECT_EQ(word, size.expected_word);
        } else {
            EXPECT_EQ(result.error.message.rfind("Broken target description: ", 0), 0u)
              << result.error.message;
        }
    }
}

TEST(DescriptionLimits, ADescriptionFileBeyondThemNamesTheLimit)
{
    for (const DescriptionSize &size : description_sizes) {
        SCOPED_TRACE(size.name);
        TargetReadResult read = read_target_json(write_target_json(sized_target(size)));
        EXPECT_EQ(read.ok, size.accepted) << read.error;
        if (!size.accepted) {
            const char *array = size.natives > 0 ? "natives: " : "local_events: ";
            EXPECT_EQ(read.error.rfind(array, 0), 0u) << read.error;
            EXPECT_NE(read.error.find(size.natives > 0 ? "4096" : "32767"), std::string::npos)
              << read.error;
        }
    }
}

} // namespace
} // namespace aseba::unit
