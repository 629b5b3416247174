// The dangerous-area experiment (experiments/dangerous-areas): its switches
// (shocks, robots' radio), its measurement of the time on dangerous colours
// against times worked out from the geometry and the hardware's wheel speed,
// its repeatability, and its report's arithmetic.

#include <gtest/gtest.h>

#include <cmath>

#include "experiments/dangerous-areas/experiment.hpp"
#include "experiments/dangerous-areas/report.hpp"
#include "tools/emulator/arena_simulation.hpp"

using namespace aseba::arena;
using namespace aseba::experiment;

namespace
{

constexpr double arena_side = 100;
constexpr double disc_radius = 14;
const Color red{ 1, 0.3, 0.3 }, green{ 0.3, 1, 0.3 };
constexpr Condition both_on{ .communication = true, .shocks = true };
constexpr Condition both_off{ .communication = false, .shocks = false };
// Well above one world step's rounding.
constexpr double step_tolerance = 1e-9;

GroundArea disc(double x, double y, Color color, double shock_period)
{
    GroundArea area;
    area.shape = GroundArea::Shape::disc;
    area.x = x;
    area.y = y;
    area.radius = disc_radius;
    area.color = color;
    area.shock_period = shock_period;
    return area;
}

// A red shock disc on the left, a green one on the right, no wheel noise.
Arena two_discs()
{
    Arena arena;
    arena.width = arena_side;
    arena.height = arena_side;
    arena.wheel_noise = 0;
    arena.areas = { disc(25, 50, red, 0.5), disc(75, 50, green, 0) };
    return arena;
}

} // namespace

TEST(DangerousAreas, ShockAreasAreTheDangerousOnesEvenWithShocksOff)
{
    Arena arena = two_discs();
    EXPECT_EQ(dangerous_areas(arena), (std::vector<bool>{ true, false }));
    Arena calm = arena_for(arena, both_off);
    EXPECT_EQ(calm.areas[0].shock_period, 0);
    EXPECT_EQ(arena_for(arena, both_on).areas[0].shock_period, 0.5);
    EXPECT_EQ(area_at(arena, 25, 50), 0);
    EXPECT_EQ(area_at(arena, 75, 50 + disc_radius - 1), 1);
    EXPECT_EQ(area_at(arena, 50, 50), -1);
}

TEST(DangerousAreas, StillRobotsCountTheWholeRunWhereTheyStand)
{
    // No program: the robots stand still where the arena puts them.
    Arena arena = two_discs();
    arena.robots = { { 1, 25, 50, 0 }, { 2, 75, 50, 0 }, { 3, 50, 50, 0 } };
    const double seconds = 3;
    for (Condition condition : { both_on, both_off }) {
        RunResult run = run_condition(arena, condition, 1, seconds, {});
        ASSERT_EQ(run.robots.size(), 3u);
        EXPECT_NEAR(run.robots[0].seconds_on_dangerous, seconds, step_tolerance);
        EXPECT_NEAR(run.robots[0].seconds_on_area[0], seconds, step_tolerance);
        EXPECT_EQ(run.robots[1].seconds_on_dangerous, 0);
        EXPECT_NEAR(run.robots[1].seconds_on_area[1], seconds, step_tolerance);
        EXPECT_EQ(run.robots[2].seconds_on_dangerous, 0);
        EXPECT_EQ(run.robots[2].seconds_on_area, (std::vector<double>{ 0, 0 }));
        EXPECT_EQ(run.robots[2].node_id, 3);
    }
}

TEST(DangerousAreas, CrossingTheDiscAtFullSpeedTakesItsDiameterOverTheSpeed)
{
    // A robot 10 cm left of the red disc drives right through its centre.
    Arena arena = two_discs();
    arena.robots = { { 1, 25 - disc_radius - 10, 50, 0 } };
    RunResult run =
      run_condition(arena, both_off, 1, 4, compile_for_epuck("tests/arena/data/forward.aesl"));
    // 1000 steps/s, 12.8 cm per 1000 steps (hardware §3.6).
    const double expected = 2 * disc_radius / 12.8;
    EXPECT_NEAR(run.robots[0].seconds_on_dangerous, expected, 0.03 * expected);
}

TEST(DangerousAreas, ShocksOffMeansNoKnocks)
{
    Arena arena = two_discs();
    arena.robots = { { 1, 25, 50, 0 } };
    for (Condition condition : { both_on, both_off }) {
        ArenaSimulation simulation(arena_for(arena, condition), 1, {});
        int knocked_steps = 0;
        for (int step = 0; step < 200; step++) { // 2 s, 4 knocks when on
            simulation.step();
            // 768 counts per g; the knock is 2 g backward (+Y).
            knocked_steps += simulation.firmware(0).variables.named.acc[1] > 768;
        }
        EXPECT_EQ(knocked_steps > 0, condition.shocks);
    }
}

TEST(DangerousAreas, RadioOffKeepsRobotsFromHearingEachOther)
{
    // Robot 1 emits `ping 42` every 100 ms; a robot that hears it shows 42.
    Arena arena = two_discs();
    arena.robots = { { 1, 50, 20, 0 }, { 2, 50, 80, 0 } };
    const std::vector<uint16_t> ping = compile_for_epuck("tests/arena/data/ping.aesl");
    for (bool radio : { true, false }) {
        ArenaSimulation simulation(arena, 1, ping);
        simulation.network().relay_robot_events(radio);
        simulation.run_for(1);
        EXPECT_EQ(simulation.firmware(1).variables.named.leds[0], radio ? 42 : 0)
          << "radio " << radio;
    }
    // The robot still emits with its radio cut: about ten pings a second.
    for (Condition condition : { both_on, both_off }) {
        RunResult run = run_condition(arena, condition, 1, 1, ping);
        EXPECT_NEAR(run.robots[0].events_emitted, 10, 1);
        EXPECT_EQ(run.robots[1].events_emitted, 0u);
    }
}

TEST(DangerousAreas, SameSeedSameNumbers)
{
    const std::vector<uint16_t> annex = compile_for_epuck("examples/paper-annex.aesl");
    const double seconds = 5;
    RunResult first = run_condition(default_arena(), both_on, 3, seconds, annex);
    RunResult second = run_condition(default_arena(), both_on, 3, seconds, annex);
    ASSERT_EQ(first.robots.size(), second.robots.size());
    for (size_t i = 0; i < first.robots.size(); i++) {
        EXPECT_EQ(first.robots[i].seconds_on_dangerous, second.robots[i].seconds_on_dangerous);
        EXPECT_EQ(first.robots[i].seconds_on_area, second.robots[i].seconds_on_area);
        EXPECT_EQ(first.robots[i].events_emitted, second.robots[i].events_emitted);
    }
}

// The annex written with locals and subroutines (docs/language.md) runs in
// the arena as the original: the arena's time does not depend on how many VM
// instructions a handler takes (each finishes within one firmware pass), so
// the numbers are the same to the last step, alarms included.
TEST(DangerousAreas, AnnexWithLocalsDoesWhatTheAnnexDoes)
{
    const double seconds = 10;
    RunResult original = run_condition(
      default_arena(), both_on, 1, seconds, compile_for_epuck("examples/paper-annex.aesl"));
    RunResult locals = run_condition(
      default_arena(), both_on, 1, seconds, compile_for_epuck("examples/paper-annex-locals.aesl"));
    ASSERT_EQ(original.robots.size(), locals.robots.size());
    unsigned alarms = 0;
    for (size_t i = 0; i < original.robots.size(); i++) {
        EXPECT_EQ(original.robots[i].seconds_on_dangerous, locals.robots[i].seconds_on_dangerous);
        EXPECT_EQ(original.robots[i].seconds_on_area, locals.robots[i].seconds_on_area);
        EXPECT_EQ(original.robots[i].events_emitted, locals.robots[i].events_emitted);
        alarms += original.robots[i].events_emitted;
    }
    EXPECT_GT(alarms, 0u) << "a run without alarms would not compare parts C to E";
}

TEST(DangerousAreasReport, SummaryIsTheMeanAndSpreadOfTheRunMeans)
{
    // Two runs of two robots: run means 1 and 3, so mean 2 and s.d. √2.
    auto run = [](uint32_t seed, double a, double b) {
        RunResult result;
        result.condition = both_on;
        result.seed = seed;
        result.robots = { { .node_id = 1, .seconds_on_dangerous = a, .seconds_on_area = { a } },
                          { .node_id = 2, .seconds_on_dangerous = b, .seconds_on_area = { b } } };
        return result;
    };
    std::vector<ConditionSummary> summaries = summarize({ run(1, 0.5, 1.5), run(2, 2, 4) });
    ASSERT_EQ(summaries.size(), 1u);
    EXPECT_DOUBLE_EQ(summaries[0].mean, 2);
    EXPECT_DOUBLE_EQ(summaries[0].standard_deviation, std::sqrt(2.0));
    EXPECT_DOUBLE_EQ(summaries[0].minimum, 1);
    EXPECT_DOUBLE_EQ(summaries[0].maximum, 3);

    std::string csv = csv_text({ run(1, 0.5, 1.5) }, { "red" });
    EXPECT_EQ(csv,
              "condition,communication,shocks,seed,node_id,seconds_on_dangerous,"
              "seconds_on_red,events_emitted\n"
              "shocks+communication,on,on,1,1,0.50,0.50,0\n"
              "shocks+communication,on,on,1,2,1.50,1.50,0\n");
}

TEST(DangerousAreasReport, AreaNamesComeFromTheirStrongestColour)
{
    Arena arena = two_discs();
    EXPECT_EQ(area_names(arena), (std::vector<std::string>{ "red", "green" }));
    arena.areas.push_back(disc(50, 80, red, 0));
    EXPECT_EQ(area_names(arena), (std::vector<std::string>{ "red1", "green", "red3" }));
}

TEST(DangerousAreasReport, TableGoesBetweenItsMarkers)
{
    std::string document = "# Title\n<!-- begin t -->\nold\n<!-- end t -->\nafter\n";
    ASSERT_TRUE(replace_block(document, "t", "new\n"));
    EXPECT_EQ(document, "# Title\n<!-- begin t -->\nnew\n<!-- end t -->\nafter\n");
    std::string unmarked = "nothing here\n";
    EXPECT_FALSE(replace_block(unmarked, "t", "new\n"));
}
