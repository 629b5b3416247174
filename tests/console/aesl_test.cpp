// .aesl projects read and written (tools/compiler/aesl.hpp) as aesl.md
// describes them: the writer's layout is Studio's own (§4), what it writes
// reads back equal, and no input crashes the reader (a deeply nested file
// once overflowed the stack of the hand-written reader).

#include <gtest/gtest.h>

#include <string>

#include "tools/compiler/aesl.hpp"

using namespace aseba;

namespace
{

void expect_same_project(const AeslProject &read, const AeslProject &written)
{
    ASSERT_EQ(read.definitions.events.size(), written.definitions.events.size());
    for (size_t i = 0; i < read.definitions.events.size(); i++) {
        EXPECT_EQ(read.definitions.events[i].name, written.definitions.events[i].name);
        EXPECT_EQ(read.definitions.events[i].size, written.definitions.events[i].size);
    }
    ASSERT_EQ(read.definitions.constants.size(), written.definitions.constants.size());
    for (size_t i = 0; i < read.definitions.constants.size(); i++) {
        EXPECT_EQ(read.definitions.constants[i].name, written.definitions.constants[i].name);
        EXPECT_EQ(read.definitions.constants[i].value, written.definitions.constants[i].value);
    }
    EXPECT_EQ(read.show_keywords, written.show_keywords);
    ASSERT_EQ(read.nodes.size(), written.nodes.size());
    for (size_t i = 0; i < read.nodes.size(); i++) {
        EXPECT_EQ(read.nodes[i].name, written.nodes[i].name);
        EXPECT_EQ(read.nodes[i].node_id, written.nodes[i].node_id);
        EXPECT_EQ(read.nodes[i].source, written.nodes[i].source);
        EXPECT_EQ(read.nodes[i].tools_plugins, written.nodes[i].tools_plugins);
    }
}

// The project of aesl.md §4.
AeslProject specification_example()
{
    AeslProject project;
    project.definitions.events = { { "alarm", 2 }, { "go", 0 } };
    project.definitions.constants = { { "LIMIT", 5 } };
    AeslNode node;
    node.name = "dummynode-0";
    node.node_id = 1;
    node.source = "var count = 0\nvar v[2] = [10, -3000]\n\nonevent timer\n  count++\n"
                  "  when count > LIMIT do\n    emit alarm v\n  end\n\nonevent go\n"
                  "  if count < 0 then\n    count = 0\n  end";
    project.nodes.push_back(node);
    return project;
}

} // namespace

// aesl.md §4 is the file Studio writes for this project, byte for byte but
// for the attribute order (Qt's hash order; the writer uses the one shown
// there) and `>`, which Studio leaves as it is and XML allows either way.
TEST(AeslWriter, WritesTheLayoutOfStudio)
{
    const std::string expected = R"(<!DOCTYPE aesl-source>
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

onevent timer
  count++
  when count &gt; LIMIT do
    emit alarm v
  end

onevent go
  if count &lt; 0 then
    count = 0
  end</node>


</network>
)";
    EXPECT_EQ(write_aesl(specification_example()), expected);
}

TEST(AeslWriter, ReadsBackWhatItWrites)
{
    AeslProject project = specification_example();
    project.definitions.constants.push_back({ "NEGATIVE", -32768 });
    project.show_keywords = false;
    AeslNode second;
    second.name = "e-puck";
    second.node_id = 65535;
    second.source = "# quotes \" and ' and & and ]]> and a tab\t\nvar x = 1\n";
    second.tools_plugins = "<toolsPlugins><ThymioVisualProgramming><vplroot "
                           "xml-format-version=\"1\"/></ThymioVisualProgramming></toolsPlugins>";
    project.nodes.push_back(second);
    AeslNode empty;
    empty.name = "silent";
    project.nodes.push_back(empty);

    std::string text = write_aesl(project);
    AeslReadResult read = read_aesl(text);
    ASSERT_TRUE(read.ok) << read.error << "\n" << text;
    expect_same_project(read.project, project);
    // Writing what was read gives the same text again.
    EXPECT_EQ(write_aesl(read.project), text);
}

TEST(AeslWriter, RefusesWhatNoReaderTakesBack)
{
    AeslProject project;
    project.definitions.events = { { "huge", 259 } };
    EXPECT_THROW(write_aesl(project), std::invalid_argument);
    project.definitions.events = { { "", 1 } };
    EXPECT_THROW(write_aesl(project), std::invalid_argument);
    project.definitions.events.clear();
    AeslNode node;
    node.name = "n";
    node.tools_plugins = "<notPlugins/>";
    project.nodes.push_back(node);
    EXPECT_THROW(write_aesl(project), std::invalid_argument);
}

// Where the program text starts is where compile errors point in the file.
TEST(AeslReader, ProgramPositionsAndTextPieces)
{
    AeslReadResult read = read_aesl("<!DOCTYPE aesl-source>\n<network>\n"
                                    "  <node name=\"a\" nodeId=\"3\">var x = 1\n"
                                    "x = 2<![CDATA[ # <raw> & ]]>&#65;&amp;</node>\n"
                                    "</network>\n");
    ASSERT_TRUE(read.ok) << read.error;
    ASSERT_EQ(read.project.nodes.size(), 1u);
    const AeslNode &node = read.project.nodes[0];
    EXPECT_EQ(node.node_id, 3);
    EXPECT_EQ(node.first_line, 3u);
    EXPECT_EQ(node.first_column, 28u);
    EXPECT_EQ(node.source, "var x = 1\nx = 2 # <raw> & A&");
}

TEST(AeslReader, ErrorsNameTheirLine)
{
    AeslReadResult read = read_aesl("<network>\n<event name=\"a\" size=\"1\"/>\n"
                                    "<event name=\"b\" size=\"259\"/>\n</network>");
    EXPECT_FALSE(read.ok);
    EXPECT_EQ(read.error_line, 3u);
    EXPECT_NE(read.error.find("size"), std::string::npos) << read.error;

    read = read_aesl("<network>\n<node name=\"n\">\nvar a\n<oops></node>\n</network>");
    EXPECT_FALSE(read.ok);
    EXPECT_EQ(read.error_line, 4u) << read.error;

    read = read_aesl("<project/>");
    EXPECT_FALSE(read.ok);
    EXPECT_NE(read.error.find("<network>"), std::string::npos) << read.error;

    read = read_aesl("<network/><network/>");
    EXPECT_FALSE(read.ok);

    read = read_aesl("<network><constant name=\"c\" value=\"-32769\"/></network>");
    EXPECT_FALSE(read.ok);
    read = read_aesl("<network><node nodeId=\"1\">x</node></network>");
    EXPECT_FALSE(read.ok);
    EXPECT_NE(read.error.find("name"), std::string::npos) << read.error;
}

// 50,000 nested elements crashed the hand-written reader (unbounded
// recursion); they are now an ordinary document, or an ordinary error.
TEST(AeslReader, DeepNestingIsNoCrash)
{
    constexpr int depth = 50000;
    std::string open, close;
    for (int i = 0; i < depth; i++) {
        open += "<a>";
        close += "</a>";
    }
    AeslReadResult read =
      read_aesl("<network><node name=\"n\">var x\n" + open + close + "</node></network>");
    ASSERT_TRUE(read.ok) << read.error;
    EXPECT_EQ(read.project.nodes.at(0).source, "var x\n");

    read = read_aesl("<network><node name=\"n\">" + open + "</node></network>");
    EXPECT_FALSE(read.ok);
}
