// Code generation against the listings of language.md §7-§10 and
// bytecode.md §9-§10, word for word. Expected words are the specification's
// (or, where noted, the reference compiler's) — never our own output.

#include <gtest/gtest.h>

#include "unit_support.hpp"

namespace aseba::unit
{
namespace
{

using Words = std::vector<uint16_t>;

TEST(Codegen, EmptyProgramIsOneWord)
{
    CompileResult result = compile_for_dummy("");
    ASSERT_TRUE(result.ok) << result.error.message;
    EXPECT_EQ(result.bytecode, Words{ 0x0001 });
}

TEST(Codegen, BytecodeExample1)
{
    CompileResult result = compile_for_dummy("var count = 0\n"
                                             "var v[2] = [10, -3000]\n"
                                             "\n"
                                             "onevent timer\n"
                                             "  count++\n"
                                             "  when count > 5 do\n"
                                             "    emit alarm v\n"
                                             "  end\n",
                                             { { "alarm", 2 } });
    ASSERT_TRUE(result.ok) << result.error.message;
    EXPECT_EQ(result.bytecode,
              (Words{ 0x0005, 0xfffe, 0x0005, 0xffff, 0x0011, 0x3024, 0x1001, 0x8002, 0x4024,
                      0x3024, 0x1005, 0xa10c, 0x0005, 0xb000, 0x0025, 0x0002, 0x0000, 0x1000,
                      0x4024, 0x100a, 0x4025, 0x2000, 0xf448, 0x4026, 0x0000 }));
    EXPECT_EQ(result.allocated_variables, 39);
}

TEST(Codegen, BytecodeExample2)
{
    CompileResult result = compile_for_dummy("var buf[4]\n"
                                             "var i\n"
                                             "var m\n"
                                             "\n"
                                             "sub clear\n"
                                             "  call math.fill(buf, 0)\n"
                                             "\n"
                                             "onevent ping\n"
                                             "  buf[i] = args[0] / 3\n"
                                             "  i = (i + 1) % 4\n"
                                             "  call math.stat(buf, m, m, m)\n"
                                             "  callsub clear\n",
                                             { { "ping", 1 } });
    ASSERT_TRUE(result.ok) << result.error.message;
    EXPECT_EQ(
      result.bytecode,
      (Words{ 0x0003, 0x0000, 0x0003, 0x3002, 0x1003, 0x8005, 0x3028, 0x6024, 0x0004, 0x3028,
              0x1001, 0x8002, 0x1004, 0x8006, 0x4028, 0x1004, 0x1029, 0x1029, 0x1029, 0x1024,
              0xc00b, 0xd017, 0x0000, 0x1004, 0x1000, 0x4423, 0x1423, 0x1024, 0xc001, 0xe000 }));
}

TEST(Codegen, IfElseifElse)
{
    // language.md §8.3, a at 36, b at 37
    CompileResult result = compile_for_dummy(
      "var a\nvar b\nif a == 1 then b = 1 elseif a == 2 then b = 2 else b = 3 end\n");
    ASSERT_TRUE(result.ok) << result.error.message;
    EXPECT_EQ(code_of(result),
              (Words{ 0x3024,
                      0x1001,
                      0xa00a,
                      0x0005,
                      0x1001,
                      0x4025,
                      0x900a,
                      0x3024,
                      0x1002,
                      0xa00a,
                      0x0005,
                      0x1002,
                      0x4025,
                      0x9003,
                      0x1003,
                      0x4025,
                      0x0000 }));
}

struct ElseJumpCase {
    const char *statement;
    bool has_jump; // the reference's words end with JUMP 1 before STOP
};

class ElseJump : public ::testing::TestWithParam<ElseJumpCase>
{
};

TEST_P(ElseJump, FollowsTheReference)
{
    // an empty `else`, or an `elseif` folded to an empty block, keeps its
    // jump; an `elseif` that disappears entirely does not (reference words)
    CompileResult result = compile_for_dummy(std::string("var a\nvar b\n") + GetParam().statement);
    ASSERT_TRUE(result.ok) << result.error.message;
    Words expected{ 0x3024, 0x1001, 0xa00a, 0x0004, 0x1001, 0x4025 };
    if (GetParam().has_jump) {
        expected[3] = 0x0005;
        expected.push_back(0x9001);
    }
    expected.push_back(0x0000);
    EXPECT_EQ(code_of(result), expected) << GetParam().statement;
}

INSTANTIATE_TEST_SUITE_P(
  Reference,
  ElseJump,
  ::testing::Values(
    ElseJumpCase{ "if a == 1 then b = 1 elseif 1 == 1 then else b = 2 end", true },
    ElseJumpCase{ "if a == 1 then b = 1 elseif a == 2 then end", false },
    ElseJumpCase{ "if a == 1 then b = 1 else end", true },
    ElseJumpCase{ "if a == 1 then b = 1 elseif 0 == 1 then b = 2 elseif a == 3 then end", false }));

TEST(Codegen, IndirectLoadAndStore)
{
    // language.md §8.1: b[i] = a[i+1]
    CompileResult result = compile_for_dummy("var a[3]\nvar b[3]\nvar i\nb[i] = a[i+1]\n");
    ASSERT_TRUE(result.ok) << result.error.message;
    EXPECT_EQ(code_of(result),
              (Words{ 0x302a, 0x1001, 0x8002, 0x5024, 0x0003, 0x302a, 0x6027, 0x0003, 0x0000 }));
}

TEST(Codegen, EmitThroughTemporary)
{
    // language.md §8.6: emit three [x, 2, x+1], temporary at 1057
    CompileResult result = compile_for_dummy("var x\nemit three [x, 2, x+1]\n", { { "three", 3 } });
    ASSERT_TRUE(result.ok) << result.error.message;
    EXPECT_EQ(code_of(result),
              (Words{ 0x3024,
                      0x4421,
                      0x1002,
                      0x4422,
                      0x3024,
                      0x1001,
                      0x8002,
                      0x4423,
                      0xb000,
                      0x0421,
                      0x0003,
                      0x0000 }));
}

TEST(Codegen, NativeCallWithLiteral)
{
    // language.md §8.7: call math.fill(a, 7) with a[4] at 36
    CompileResult result = compile_for_dummy("var a[4]\ncall math.fill(a, 7)\n");
    ASSERT_TRUE(result.ok) << result.error.message;
    EXPECT_EQ(code_of(result), (Words{ 0x1004, 0x1007, 0x4423, 0x1423, 0x1024, 0xc001, 0x0000 }));
}

TEST(Codegen, NativeCallTemplateSizes)
{
    // bytecode.md §9: deque.get(a, b[0:1], i)
    CompileResult result =
      compile_for_dummy("var a[4]\nvar b[4]\nvar m\nvar i\ncall deque.get(a, b[0:1], i)\n");
    ASSERT_TRUE(result.ok) << result.error.message;
    EXPECT_EQ(code_of(result), (Words{ 0x1002, 0x1004, 0x102d, 0x1028, 0x1024, 0xc016, 0x0000 }));
}

TEST(Codegen, TemporariesOfBothPhases)
{
    // language.md §7: emit temporary 1058-1059, then the vector one 1055-1057
    CompileResult result =
      compile_for_dummy("var a[3]\nvar b[3]\na = a + b\nemit two [1, 2]\n", { { "two", 2 } });
    ASSERT_TRUE(result.ok) << result.error.message;
    EXPECT_EQ(code_of(result),
              (Words{ 0x3024, 0x3027, 0x8002, 0x441f, 0x3025, 0x3028, 0x8002, 0x4420, 0x3026,
                      0x3029, 0x8002, 0x4421, 0x341f, 0x4024, 0x3420, 0x4025, 0x3421, 0x4026,
                      0x1001, 0x4422, 0x1002, 0x4423, 0xb000, 0x0422, 0x0002, 0x0000 }));
}

struct FoldingCase {
    const char *expression;
    Words words; // of the immediate pushing the folded value
};

class ConstantFolding : public ::testing::TestWithParam<FoldingCase>
{
};

TEST_P(ConstantFolding, FoldsIn32Bits)
{
    // language.md §9 rule 1: 32-bit wrap, shift counts modulo 32, small/large
    // immediate chosen on the 32-bit value
    CompileResult result = compile_for_dummy(std::string("var a\na = ") + GetParam().expression);
    ASSERT_TRUE(result.ok) << result.error.message;
    Words expected = GetParam().words;
    expected.push_back(0x4024);
    expected.push_back(0x0000);
    EXPECT_EQ(code_of(result), expected) << GetParam().expression;
}

INSTANTIATE_TEST_SUITE_P(LanguageSection9,
                         ConstantFolding,
                         ::testing::Values(FoldingCase{ "0x7fff + 1", { 0x2000, 0x8000 } },
                                           FoldingCase{ "200 * 200", { 0x2000, 0x9c40 } },
                                           FoldingCase{ "1 << 16", { 0x2000, 0x0000 } },
                                           FoldingCase{ "256 * 256 * 256 * 256", { 0x1000 } },
                                           FoldingCase{ "16384 * 16384 * 16 + 3", { 0x1003 } },
                                           FoldingCase{ "32767 * 32767 * 4", { 0x2000, 0x0004 } },
                                           FoldingCase{ "1 << 32", { 0x1001 } },
                                           FoldingCase{ "1 << 33", { 0x1002 } },
                                           FoldingCase{ "1 << 31", { 0x2000, 0x0000 } },
                                           FoldingCase{ "1 << -1", { 0x2000, 0x0000 } },
                                           FoldingCase{ "-1 >> 40", { 0x1fff } },
                                           FoldingCase{ "-2047", { 0x1801 } },
                                           FoldingCase{ "-2048", { 0x2000, 0xf800 } },
                                           FoldingCase{ "-0xFFFF", { 0x1001 } },
                                           FoldingCase{ "-32768", { 0x2000, 0x8000 } }));

TEST(Codegen, StrengthReductionAndNeutralElements)
{
    // §9 rules 3 and 5: x * 2 -> x << 1, x / 4 -> x >> 2, x + 0 -> x
    CompileResult result = compile_for_dummy("var a\na = a * 2\na = a / 4\na = a + 0\n");
    ASSERT_TRUE(result.ok) << result.error.message;
    EXPECT_EQ(
      code_of(result),
      (Words{
        0x3024, 0x1001, 0x8000, 0x4024, 0x3024, 0x1002, 0x8001, 0x4024, 0x3024, 0x4024, 0x0000 }));
}

TEST(Codegen, IndexFoldedByAbsorbingElement)
{
    // §9 rule 8: a[i*0 + 2] is a direct load of a + 2
    CompileResult result = compile_for_dummy("var a[3]\nvar i\nvar x\nx = a[i*0 + 2]\n");
    ASSERT_TRUE(result.ok) << result.error.message;
    EXPECT_EQ(code_of(result), (Words{ 0x3026, 0x4028, 0x0000 }));
}

TEST(Codegen, DecreasingForLoop)
{
    // the reference compiler's words for this loop (§8.5 expansion)
    CompileResult result = compile_for_dummy("var a\nfor a in 5:0 step -2 do\na=1\nend\n");
    ASSERT_TRUE(result.ok) << result.error.message;
    EXPECT_EQ(code_of(result),
              (Words{ 0x1005,
                      0x4024,
                      0x3024,
                      0x1000,
                      0xa00d,
                      0x0009,
                      0x1001,
                      0x4024,
                      0x3024,
                      0x1ffe,
                      0x8002,
                      0x4024,
                      0x9ff6,
                      0x0000 }));
}

TEST(Codegen, StackCheckFormula)
{
    // §11.3: a = a+(a+(a+(a+a))) needs 5 stack words
    TargetDescription target = dummy_target();
    const char *source = "var a\na = a+(a+(a+(a+a)))\n";
    target.stack_size = 4;
    CompileResult small = compile(source, target, {});
    EXPECT_FALSE(small.ok);
    // unlike the reference, the error says where and how much
    EXPECT_TRUE(small.error.has_position);
    EXPECT_EQ(small.error.position.line, 2u);
    EXPECT_EQ(small.error.message,
              "Execution stack will overflow: this statement needs 5 words of stack, the target "
              "has 4: cut long mathematical expressions");
    target.stack_size = 5;
    EXPECT_TRUE(compile(source, target, {}).ok);
}

} // namespace
} // namespace aseba::unit
