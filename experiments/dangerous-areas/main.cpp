// dangerous-areas: the 2007 Aseba paper's Fig. 5 experiment in the simulated
// arena. Runs the paper's controller on every robot of the arena under the
// four conditions (robots' radio on or off, shocks on or off) for a number
// of seeds, and writes the time each robot spent on dangerous colours (CSV)
// and a summary table (docs/experiment.md); plot.py draws the figure.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "experiment.hpp"
#include "report.hpp"

namespace
{

const char usage[] = R"(Usage: dangerous-areas [OPTIONS]

Runs the dangerous-area experiment of the 2007 Aseba paper (its Fig. 5) in
the simulated arena: PROGRAM on every robot, under the four conditions
(communication between robots on/off x shocks on/off) for seeds 1..N, each
run DURATION simulated seconds at full speed with no TCP port open. Each seed
draws the robots' start positions and headings (off the coloured areas), the
same for the four conditions, and seeds the noise. The areas that shock
robots in the arena count as dangerous in every condition; the time a
robot's centre is on one is measured after every 10 ms world step.

Writes OUT/dangerous-areas.csv (one line per run and robot), prints a line
per run and the summary table (Markdown), and with --doc puts the table into
that file between the lines <!-- begin dangerous-areas table --> and
<!-- end dangerous-areas table -->. The figure is drawn from the CSV by
experiments/dangerous-areas/plot.py (matplotlib; `make experiment` runs it).

Options:
  --out DIR         folder of the CSV and the figure (default docs/experiment)
  --doc FILE        Markdown file to put the table in (default: none)
  --seeds N         seeds 1..N for every condition (default 5)
  --duration S      simulated seconds per run (default 60)
  --program FILE    controller, .aesl project or script
                    (default examples/paper-annex.aesl)
  --arena FILE      arena file (docs/arena-format.md) or `default`, the
                    paper's setup (default)
  --shock-period S  knock robots on dangerous areas every S seconds, the
                    first after S seconds on one (default: the arena's,
                    0.25 s in the default arena)
  --starts S        `drawn` (from each seed, the default) or `placed` (where
                    the arena puts the robots: the default arena's ring,
                    the same for every run)
  -h, --help        show this help
)";

struct Options {
    std::string out = "docs/experiment";
    std::string doc;
    unsigned seeds = 5;
    double duration = 60;
    std::string program = "examples/paper-annex.aesl";
    std::string arena = "default";
    double shock_period = 0; // 0: the arena's
    bool drawn_starts = true;
};

[[noreturn]] void fail(const std::string &message)
{
    std::fprintf(stderr, "dangerous-areas: %s\n", message.c_str());
    std::exit(1);
}

Options parse_options(int argc, char **argv)
{
    Options options;
    for (int i = 1; i < argc; i++) {
        std::string argument = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc)
                fail("option " + argument + " needs a value");
            return argv[++i];
        };
        if (argument == "-h" || argument == "--help") {
            std::fputs(usage, stdout);
            std::exit(0);
        } else if (argument == "--out") {
            options.out = value();
        } else if (argument == "--doc") {
            options.doc = value();
        } else if (argument == "--seeds") {
            std::string text = value();
            char *end = nullptr;
            unsigned long seeds = std::strtoul(text.c_str(), &end, 10);
            if (*end != '\0' || seeds < 1 || seeds > 1000)
                fail("--seeds wants a whole number from 1 to 1000, not '" + text + "'");
            options.seeds = unsigned(seeds);
        } else if (argument == "--duration") {
            std::string text = value();
            char *end = nullptr;
            options.duration = std::strtod(text.c_str(), &end);
            if (*end != '\0' || !(options.duration > 0))
                fail("--duration wants a positive number of seconds, not '" + text + "'");
        } else if (argument == "--shock-period") {
            std::string text = value();
            char *end = nullptr;
            options.shock_period = std::strtod(text.c_str(), &end);
            if (*end != '\0' || !(options.shock_period > 0))
                fail("--shock-period wants a positive number of seconds, not '" + text + "'");
        } else if (argument == "--starts") {
            std::string starts = value();
            if (starts != "drawn" && starts != "placed")
                fail("--starts is drawn or placed, not '" + starts + "'");
            options.drawn_starts = starts == "drawn";
        } else if (argument == "--program") {
            options.program = value();
        } else if (argument == "--arena") {
            options.arena = value();
        } else {
            fail("unknown option '" + argument + "' (see --help)");
        }
    }
    return options;
}

void write_file(const std::string &path, const std::string &text)
{
    std::ofstream file(path, std::ios::binary);
    file << text;
    if (!file)
        fail("cannot write " + path);
}

} // namespace

int main(int argc, char **argv)
{
    using namespace aseba::experiment;
    Options options = parse_options(argc, argv);

    aseba::arena::Arena arena;
    std::vector<uint16_t> bytecode;
    try {
        arena = options.arena == "default" ? aseba::arena::default_arena()
                                           : aseba::arena::read_arena_file(options.arena);
        bytecode = compile_for_epuck(options.program);
    } catch (const std::exception &error) {
        fail(error.what());
    }
    bool any_dangerous = false;
    for (aseba::arena::GroundArea &area : arena.areas) {
        if (area.shock_period > 0 && options.shock_period > 0)
            area.shock_period = options.shock_period;
        any_dangerous |= area.shock_period > 0;
    }
    if (!any_dangerous)
        fail("the arena has no area with a shock: nothing is dangerous");

    const std::vector<Condition> conditions = all_conditions();
    const size_t total = conditions.size() * options.seeds;
    std::vector<RunResult> runs;
    using clock = std::chrono::steady_clock;
    for (const Condition &condition : conditions) {
        for (uint32_t seed = 1; seed <= options.seeds; seed++) {
            auto start = clock::now();
            aseba::arena::Arena seeded = arena;
            try {
                if (options.drawn_starts)
                    aseba::arena::draw_start_positions(seeded, seed);
            } catch (const std::exception &error) {
                fail(error.what());
            }
            RunResult run = run_condition(seeded, condition, seed, options.duration, bytecode);
            double wall = std::chrono::duration<double>(clock::now() - start).count();
            double sum = 0;
            unsigned events = 0;
            for (const RobotTimes &robot : run.robots) {
                sum += robot.seconds_on_dangerous;
                events += robot.events_emitted;
            }
            runs.push_back(run);
            std::printf("run %2zu/%zu: %-20s seed %u: %5.1f s on dangerous colours per robot, "
                        "%u events emitted (%.1f s wall)\n",
                        runs.size(),
                        total,
                        condition_name(condition).c_str(),
                        unsigned(seed),
                        sum / double(run.robots.size()),
                        events,
                        wall);
            std::fflush(stdout);
        }
    }

    std::error_code error;
    std::filesystem::create_directories(options.out, error);
    if (error)
        fail("cannot create " + options.out + ": " + error.message());
    const std::string csv_path = options.out + "/dangerous-areas.csv";
    write_file(csv_path, csv_text(runs, area_names(arena)));
    const std::string table = markdown_table(summarize(runs), options.duration);
    std::printf(
      "\n%s\nwrote %s (the figure: /usr/bin/python3 experiments/dangerous-areas/plot.py %s "
      "FIGURE.svg)\n",
      table.c_str(),
      csv_path.c_str(),
      csv_path.c_str());

    if (!options.doc.empty()) {
        std::ifstream file(options.doc, std::ios::binary);
        std::stringstream text;
        text << file.rdbuf();
        if (!file)
            fail("cannot read " + options.doc);
        std::string document = text.str();
        if (!replace_block(document, "dangerous-areas table", table))
            fail(options.doc + " has no <!-- begin dangerous-areas table --> ... "
                               "<!-- end dangerous-areas table --> block");
        write_file(options.doc, document);
        std::printf("updated the table in %s\n", options.doc.c_str());
    }
    return 0;
}
