// Checks the wrapper around the reference compiler against values written in
// the specifications: the worked examples of bytecode.md §10 (every word) and
// the upstream error positions listed in the corpus README §5. If these pass,
// the wrapper feeds the reference the right target and reads its answer right.

#include <gtest/gtest.h>

#include <map>

#include "bytecode_listing.hpp"
#include "corpus.hpp"
#include "reference_oracle.hpp"
#include "require_reference.hpp"
#include "test_targets.hpp"

namespace compiler_tests
{
namespace
{

TEST(ReferenceOracle, WorkedExample1OfBytecodeSpec)
{
    REQUIRE_REFERENCE();
    const char *source = "var count = 0\n"
                         "var v[2] = [10, -3000]\n"
                         "\n"
                         "onevent timer\n"
                         "  count++\n"
                         "  when count > 5 do\n"
                         "    emit alarm v\n"
                         "  end\n";
    aseba::CommonDefinitions definitions;
    definitions.events = { { "alarm", 2 } };
    const reference::ReferenceResult result =
      reference::compile_with_reference(source, dummy_node_target(), definitions);
    ASSERT_TRUE(result.ok) << reference::describe(result.error);
    const std::vector<uint16_t> expected = { 0x0005, 0xfffe, 0x0005, 0xffff, 0x0011, 0x3024, 0x1001,
                                             0x8002, 0x4024, 0x3024, 0x1005, 0xa10c, 0x0005, 0xb000,
                                             0x0025, 0x0002, 0x0000, 0x1000, 0x4024, 0x100a, 0x4025,
                                             0x2000, 0xf448, 0x4026, 0x0000 };
    EXPECT_EQ(result.bytecode, expected)
      << compare_listings(result.bytecode, expected, "reference", "bytecode.md");
    // Named variables take 36 words, then count and v[2] (bytecode.md §10.1).
    EXPECT_EQ(result.allocated_variables, 39u);
}

TEST(ReferenceOracle, WorkedExample2OfBytecodeSpec)
{
    REQUIRE_REFERENCE();
    const char *source = "var buf[4]\n"
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
                         "  callsub clear\n";
    aseba::CommonDefinitions definitions;
    definitions.events = { { "ping", 1 } };
    const reference::ReferenceResult result =
      reference::compile_with_reference(source, dummy_node_target(), definitions);
    ASSERT_TRUE(result.ok) << reference::describe(result.error);
    const std::vector<uint16_t> expected = { 0x0003, 0x0000, 0x0003, 0x3002, 0x1003, 0x8005,
                                             0x3028, 0x6024, 0x0004, 0x3028, 0x1001, 0x8002,
                                             0x1004, 0x8006, 0x4028, 0x1004, 0x1029, 0x1029,
                                             0x1029, 0x1024, 0xc00b, 0xd017, 0x0000, 0x1004,
                                             0x1000, 0x4423, 0x1423, 0x1024, 0xc001, 0xe000 };
    EXPECT_EQ(result.bytecode, expected)
      << compare_listings(result.bytecode, expected, "reference", "bytecode.md");
    EXPECT_EQ(result.allocated_variables, 42u);

    // buf 36..39, i 40, m 41 (bytecode.md §10.2).
    std::map<std::string, std::pair<unsigned, unsigned>> variables;
    for (const auto &variable : result.variables)
        variables[variable.name] = { variable.address, variable.size };
    EXPECT_EQ(variables["buf"], std::make_pair(36u, 4u));
    EXPECT_EQ(variables["i"], std::make_pair(40u, 1u));
    EXPECT_EQ(variables["m"], std::make_pair(41u, 1u));
}

// Rows of the corpus README §5: script, then the error as upstream prints it.
struct ExpectedError {
    const char *script;
    const char *printed;
};

void PrintTo(const ExpectedError &row, std::ostream *out)
{
    *out << row.script;
}

class ReferenceOracleErrors : public testing::TestWithParam<ExpectedError>
{
};

TEST_P(ReferenceOracleErrors, ReportsUpstreamPositionAndMessage)
{
    REQUIRE_REFERENCE();
    const reference::ReferenceResult result = reference::compile_with_reference(
      read_corpus_file(GetParam().script), corpus_target(standard_natives()), corpus_definitions());
    ASSERT_FALSE(result.ok);
    EXPECT_EQ(reference::describe(result.error), GetParam().printed);
}

INSTANTIATE_TEST_SUITE_P(
  CorpusReadme,
  ReferenceOracleErrors,
  testing::Values(
    ExpectedError{ "division-by-zero-static.txt", "Error at Line: 3 Col: 7 : Division by zero" },
    ExpectedError{ "inconsistent-input1.txt",
                   "Error at Line: 5 Col: 0 : Expecting assignment, found    5:4294967295 end "
                   "of stream instead" },
    ExpectedError{ "inconsistent-input2.txt",
                   "Error at Line: 3 Col: 1 : va is not a defined variable, do you mean i?" },
    ExpectedError{ "inconsistent-input4.txt",
                   "Error : Execution stack will overflow, check for any recursive subroutine "
                   "call and cut long mathematical expressions" },
    ExpectedError{ "for-loop-bounds.txt",
                   "Error at Line: 4 Col: 12 : End index cannot be 32767 in increasing loops" },
    ExpectedError{ "out-of-memory-temp1.txt",
                   "Error at Line: 6 Col: 2 : Not enough free space to allocate this tempory "
                   "variable" },
    ExpectedError{ "constdef-collision-1.txt",
                   "Error at Line: 3 Col: 8 : Constant FOO is already defined" },
    ExpectedError{ "literal-hex-overflow2.txt",
                   "Error at Line: 1 Col: 10 : Integer value 32768 out of [-32768;32767] "
                   "range" }),
  [](const testing::TestParamInfo<ExpectedError> &row) {
      return test_identifier(row.param.script);
  });

} // namespace
} // namespace compiler_tests
