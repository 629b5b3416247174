// Every recursive walk of the compiler is bounded: inputs built to nest or
// chain far beyond what a program needs (the 20,000 `elseif`s among
// them) end in a clear error, never in a crash of the compiler's own stack.
// Each case names the construct, how often it repeats, and the start of the
// error it must give.

#include <gtest/gtest.h>

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

} // namespace
} // namespace aseba::unit
