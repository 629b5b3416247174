// The IDE's project against aesl.md: Studio's example file, node matching
// (§2.2) and what is written back.

#include <gtest/gtest.h>

#include "tools/ide/workspace.hpp"

namespace
{

using aseba::ide::NodeKey;
using aseba::ide::Workspace;

// aesl.md §4, as Studio writes it.
const char *const STUDIO_EXAMPLE = R"(<!DOCTYPE aesl-source>
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
  when count > LIMIT do
    emit alarm v
  end

onevent go
  if count &lt; 0 then
    count = 0
  end</node>


</network>
)";

TEST(Workspace, OpensStudiosExample)
{
    Workspace workspace;
    workspace.open("example.aesl", STUDIO_EXAMPLE);
    ASSERT_EQ(workspace.definitions.events.size(), 2u);
    EXPECT_EQ(workspace.definitions.events[0].name, "alarm");
    EXPECT_EQ(workspace.definitions.events[0].size, 2);
    EXPECT_EQ(workspace.definitions.events[1].name, "go");
    ASSERT_EQ(workspace.definitions.constants.size(), 1u);
    EXPECT_EQ(workspace.definitions.constants[0].value, 5);
    ASSERT_EQ(workspace.waiting.size(), 1u);
    EXPECT_EQ(workspace.waiting[0].name, "dummynode-0");
    EXPECT_NE(workspace.waiting[0].source.find("if count < 0 then"), std::string::npos);
}

TEST(Workspace, AMalformedProjectNamesTheFileAndLineAndChangesNothing)
{
    Workspace workspace;
    workspace.open("example.aesl", STUDIO_EXAMPLE);
    Workspace before = workspace;
    try {
        workspace.open("broken.aesl",
                       "<!DOCTYPE aesl-source>\n<network>\n<event name=\"x\" size=\"1\">\n");
        FAIL() << "a broken file was accepted";
    } catch (const aseba::ide::ProjectError &error) {
        EXPECT_EQ(std::string(error.what()).rfind("broken.aesl:", 0), 0u) << error.what();
    }
    EXPECT_EQ(workspace.waiting.size(), before.waiting.size());
    EXPECT_EQ(workspace.definitions.events.size(), before.definitions.events.size());
}

TEST(Workspace, ARobotGetsTheProgramOfItsIdElseTheFirstOfItsName)
{
    Workspace workspace;
    workspace.open("group.aesl", R"(<!DOCTYPE aesl-source><network>
<node nodeId="1" name="e-puck">one</node>
<node nodeId="2" name="e-puck">two</node>
<node nodeId="9" name="thymio-II">thymio</node></network>)");
    // As Studio, by name, preferring the same id (aesl.md §2.2).
    EXPECT_TRUE(workspace.match(NodeKey{ 0, 2 }, "e-puck"));
    EXPECT_EQ(workspace.scripts[(NodeKey{ 0, 2 })], "two");
    // A robot with no program of its own gets the first of its name, as
    // asebamassloader loads it into every robot of that name.
    EXPECT_TRUE(workspace.match(NodeKey{ 0, 5 }, "e-puck"));
    EXPECT_EQ(workspace.scripts[(NodeKey{ 0, 5 })], "one");
    EXPECT_FALSE(workspace.match(NodeKey{ 0, 7 }, "dummynode"));
    // A robot that has a script keeps it.
    workspace.scripts[(NodeKey{ 0, 6 })] = "mine";
    EXPECT_FALSE(workspace.match(NodeKey{ 0, 6 }, "e-puck"));
    EXPECT_EQ(workspace.scripts[(NodeKey{ 0, 6 })], "mine");
    // "one" and "two" were taken; the Thymio's program waits for a Thymio.
    ASSERT_EQ(workspace.waiting.size(), 1u);
    EXPECT_EQ(workspace.waiting[0].name, "thymio-II");
}

TEST(Workspace, AProjectOfOneProgramGoesToTheWholeSwarm)
{
    Workspace workspace;
    workspace.open("annex.aesl", R"(<!DOCTYPE aesl-source><network>
<node nodeId="1" name="e-puck">controller</node></network>)");
    std::map<NodeKey, std::string> robots;
    for (uint16_t id = 1; id <= 6; id++)
        robots[NodeKey{ 0, id }] = "e-puck";
    EXPECT_EQ(workspace.assign(robots).size(), 6u);
    for (uint16_t id = 1; id <= 6; id++)
        EXPECT_EQ(workspace.scripts[(NodeKey{ 0, id })], "controller") << "robot " << id;
    EXPECT_TRUE(workspace.waiting.empty());
}

TEST(Workspace, WhatIsSavedReadsBackTheSameAndKeepsTheWaitingPrograms)
{
    Workspace workspace;
    workspace.open("example.aesl", STUDIO_EXAMPLE);
    workspace.definitions.constants.push_back({ "NEGATIVE", -40 });
    workspace.scripts[NodeKey{ 0, 3 }] = "var a = NEGATIVE\n# < & > are escaped\nemit go";
    workspace.scripts[NodeKey{ 0, 4 }] = ""; // an empty tab is not saved, as in Studio
    std::string text =
      workspace.to_aesl({ { NodeKey{ 0, 3 }, "e-puck" }, { NodeKey{ 0, 4 }, "e-puck" } });

    EXPECT_EQ(text.rfind("<!DOCTYPE aesl-source>\n<network>", 0), 0u) << text;
    // Events and constants come before every node (massloader reads in order).
    EXPECT_LT(text.find("<constant"), text.find("<node"));
    aseba::AeslReadResult read = aseba::read_aesl(text);
    ASSERT_TRUE(read.ok) << read.error;
    ASSERT_EQ(read.project.definitions.events.size(), 2u);
    EXPECT_EQ(read.project.definitions.events[0].name, "alarm");
    EXPECT_EQ(read.project.definitions.events[0].size, 2);
    ASSERT_EQ(read.project.definitions.constants.size(), 2u);
    EXPECT_EQ(read.project.definitions.constants[1].value, -40);
    ASSERT_EQ(read.project.nodes.size(), 2u);
    EXPECT_EQ(read.project.nodes[0].name, "e-puck");
    EXPECT_EQ(read.project.nodes[0].node_id, 3);
    EXPECT_EQ(read.project.nodes[0].source, "var a = NEGATIVE\n# < & > are escaped\nemit go");
    EXPECT_EQ(read.project.nodes[1].name, "dummynode-0"); // still waiting for its robot
    EXPECT_EQ(read.project.nodes[1].source, workspace.waiting[0].source);
}

} // namespace
