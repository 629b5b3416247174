// The dangerous-area experiment's outputs: the CSV of every robot's times
// and the per-condition summary as a Markdown table. The figure is drawn
// from the CSV by plot.py (matplotlib).

#pragma once

#include <string>
#include <vector>

#include "experiment.hpp"

namespace aseba::experiment
{

// A name for each area of `arena` from its strongest colour channel ("red",
// "green", "blue"), with its number appended when two would share a name.
std::vector<std::string> area_names(const arena::Arena &arena);

// One line per run and robot: condition, communication, shocks, seed, the
// run's duration, node id, seconds on dangerous areas, seconds on each area
// (`area_names`) and user events emitted, after a header line.
std::string csv_text(const std::vector<RunResult> &runs,
                     const std::vector<std::string> &area_names);

// A condition's figures: each run's mean over its robots of the seconds on
// dangerous areas, and their mean, standard deviation, minimum and maximum.
struct ConditionSummary {
    Condition condition;
    std::vector<double> run_means;
    std::vector<std::vector<double>> robot_seconds; // each run's robots
    double mean = 0;
    double standard_deviation = 0; // of the run means (n - 1)
    double minimum = 0;
    double maximum = 0;
};

// The summaries of the conditions present in `runs`, in all_conditions order.
std::vector<ConditionSummary> summarize(const std::vector<RunResult> &runs);

// The summaries as a Markdown table; `seconds` is the runs' duration.
std::string markdown_table(const std::vector<ConditionSummary> &summaries, double seconds);

// Puts `block` between the lines `<!-- begin NAME -->` and `<!-- end NAME
// -->` of `document`, replacing what was there; false when the markers are
// missing.
bool replace_block(std::string &document, const std::string &name, const std::string &block);

} // namespace aseba::experiment
