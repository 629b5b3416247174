// The project's own formats and the relaxations beyond the reference: the
// 2007 paper's dialect, target descriptions in JSON, .aesl projects, the
// disassembler and the error rendering.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tools/compiler/aesl.hpp"
#include "tools/compiler/disassembler.hpp"
#include "tools/compiler/error_format.hpp"
#include "tools/compiler/target_json.hpp"
#include "unit_support.hpp"

namespace aseba::unit
{
namespace
{

std::string read_file(const std::string &path)
{
    std::ifstream file(path, std::ios::binary);
    std::ostringstream content;
    content << file.rdbuf();
    return content.str();
}

TEST(PaperDialect, AnnexCompilesForEpuck)
{
    std::string source = read_file("examples/paper-annex.aseba");
    ASSERT_FALSE(source.empty()) << "needs examples/paper-annex.aseba";
    CommonDefinitions definitions;
    definitions.events = { { "bad", 1 } };
    CompileResult result = compile(source, epuck_target(), definitions);
    ASSERT_TRUE(result.ok) << result.error.position.line << ":" << result.error.position.column
                           << ": " << result.error.message;
    EXPECT_LE(result.bytecode.size(), epuck_target().bytecode_size);
}

TEST(PaperDialect, LateVariableInitialiserAssignsWhereItStands)
{
    // `var y = 5` after a statement is `y = 5` at that point (after x = 1)
    CompileResult late = compile_for_dummy("var x\nx = 1\nvar y = 5\n");
    CompileResult early = compile_for_dummy("var x\nvar y\nx = 1\ny = 5\n");
    ASSERT_TRUE(late.ok) << late.error.message;
    ASSERT_TRUE(early.ok);
    EXPECT_EQ(late.bytecode, early.bytecode);
}

TEST(PaperDialect, VecIsTheOldNameOfMath)
{
    CompileResult old_name = compile_for_dummy("var a[3]\nvar m\ncall vec.stat(a, m, m, m)\n");
    CompileResult new_name = compile_for_dummy("var a[3]\nvar m\ncall math.stat(a, m, m, m)\n");
    ASSERT_TRUE(old_name.ok) << old_name.error.message;
    EXPECT_EQ(old_name.bytecode, new_name.bytecode);
}

TEST(TargetJson, ReadsWhatItWrites)
{
    TargetDescription epuck = epuck_target();
    TargetReadResult read = read_target_json(write_target_json(epuck));
    ASSERT_TRUE(read.ok) << read.error;
    EXPECT_EQ(read.target.name, epuck.name);
    EXPECT_EQ(read.target.variables_size, epuck.variables_size);
    ASSERT_EQ(read.target.named_variables.size(), epuck.named_variables.size());
    ASSERT_EQ(read.target.native_functions.size(), epuck.native_functions.size());
    EXPECT_EQ(read.target.native_functions[10].parameters[3].name, "shift");
}

TEST(TargetJson, StandardNativesShorthandAndErrors)
{
    TargetReadResult read = read_target_json(R"({
        "name": "tiny", "bytecode_size": 100, "variables_size": 40, "stack_size": 16,
        "variables": [{"name": "id"}, {"name": "source"}, {"name": "args", "size": 4}],
        "local_events": [{"name": "tick"}],
        "natives": [{"name": "_led", "parameters": [{"name": "on", "size": 1}]}, "standard"]
    })");
    ASSERT_TRUE(read.ok) << read.error;
    ASSERT_EQ(read.target.native_functions.size(), 31u);
    EXPECT_EQ(read.target.native_functions[1].name, "math.copy");
    EXPECT_EQ(read.target.named_variables[2].size, 4);
    // math.fill is now native 2: the index follows the description order
    CompileResult result = compile("var a[2]\ncall math.fill(a, 1)\n", read.target, {});
    ASSERT_TRUE(result.ok) << result.error.message;
    EXPECT_EQ(result.bytecode[result.bytecode[0] + 5], 0xc002);

    EXPECT_FALSE(read_target_json("{\"name\": \"x\"}").ok);
    EXPECT_FALSE(read_target_json("[1, 2").ok);
    EXPECT_FALSE(read_target_json("{\"name\": \"x\", \"bytecode_size\": 1.5}").ok);
}

TEST(Aesl, ReadsTheSpecificationExample)
{
    AeslReadResult read = read_aesl(R"(<!DOCTYPE aesl-source>
<network>


<!--list of global events-->
<event size="2" name="alarm"/>
<event size="0" name="go"/>


<!--list of constants-->
<constant value="5" name="LIMIT"/>


<!--show keywords state-->
<keywords flag="true"/>


<!--node dummynode-0-->
<node nodeId="1" name="dummynode-0">var count = 0
var v[2] = [10, -3000]
if count &lt; LIMIT then count = 1 end
</node>


</network>
)");
    ASSERT_TRUE(read.ok) << read.error;
    const AeslProject &project = read.project;
    ASSERT_EQ(project.definitions.events.size(), 2u);
    EXPECT_EQ(project.definitions.events[0].name, "alarm");
    EXPECT_EQ(project.definitions.events[0].size, 2);
    ASSERT_EQ(project.definitions.constants.size(), 1u);
    EXPECT_EQ(project.definitions.constants[0].value, 5);
    ASSERT_EQ(project.nodes.size(), 1u);
    EXPECT_EQ(project.nodes[0].name, "dummynode-0");
    EXPECT_EQ(project.nodes[0].node_id, 1);
    EXPECT_EQ(project.nodes[0].first_line, 19u);
    EXPECT_NE(project.nodes[0].source.find("if count < LIMIT"), std::string::npos);
    EXPECT_TRUE(compile(project.nodes[0].source, dummy_target(), project.definitions).ok);
}

TEST(Aesl, MalformedFilesAreErrors)
{
    EXPECT_FALSE(read_aesl("").ok);
    EXPECT_FALSE(read_aesl("<network><event name=\"a\" size=\"x\"/></network>").ok);
    EXPECT_FALSE(read_aesl("<network><node name=\"n\">text").ok);
    EXPECT_FALSE(read_aesl("<network><event name=\"a\" size=\"300\"/></network>").ok);
}

TEST(Disassembler, NamesFromTheOpcodeLists)
{
    std::vector<uint16_t> bytecode{ 0x0003, 0xffff, 0x0003, 0x2000, 0xf448, 0xa10c,
                                    0x0005, 0x6024, 0x0004, 0x9ffe, 0xe000 };
    std::vector<DisassembledInstruction> code = disassemble(bytecode);
    ASSERT_EQ(code.size(), 5u);
    EXPECT_EQ(code[0].text, "LARGE_IMMEDIATE -3000");
    EXPECT_EQ(code[1].address, 5);
    EXPECT_EQ(code[1].text, "CONDITIONAL_BRANCH when > else 5 (-> 10)");
    EXPECT_EQ(code[2].text, "STORE_INDIRECT 36 size 4");
    EXPECT_EQ(code[3].text, "JUMP -2 (-> 7)");
    EXPECT_EQ(code[4].text, "SUB_RET");
    // a cut instruction is shown, never read past the end
    EXPECT_EQ(disassemble({ 0x0001, 0x2000 }).at(0).text, "LARGE_IMMEDIATE (truncated)");
}

TEST(ErrorFormat, FileLineColumnSourceAndCaret)
{
    CompileError error{ true, { 2, 7 }, "Size error! Size of array1 = 3 ; size of array2 = 1" };
    EXPECT_EQ(format_error("x.aseba", "var a[3]\nx = a + 1\n", error),
              "x.aseba:2:7: error: Size error! Size of array1 = 3 ; size of array2 = 1\n"
              "  x = a + 1\n"
              "        ^\n");
}

TEST(Robustness, DeepNestingIsAnErrorNotACrash)
{
    std::string deep = "var x\nx = " + std::string(100000, '(') + "1" + std::string(100000, ')');
    CompileResult result = compile_for_dummy(deep);
    EXPECT_FALSE(result.ok);
    std::string blocks = "var x\n";
    for (int i = 0; i < 5000; ++i)
        blocks += "if x == 1 then\n";
    EXPECT_FALSE(compile_for_dummy(blocks).ok);
    std::string chain = "var x\nx = x";
    for (int i = 0; i < 20000; ++i)
        chain += " + x";
    EXPECT_FALSE(compile_for_dummy(chain).ok);
}

} // namespace
} // namespace aseba::unit
