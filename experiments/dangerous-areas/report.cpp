// The dangerous-area experiment's CSV and table (see report.hpp).

#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>

namespace aseba::experiment
{
namespace
{

// printf into a std::string.
template<typename... Arguments>
std::string format(const char *pattern, Arguments... arguments)
{
    int length = std::snprintf(nullptr, 0, pattern, arguments...);
    std::string text(size_t(length) + 1, '\0');
    std::snprintf(text.data(), text.size(), pattern, arguments...);
    text.pop_back();
    return text;
}

double mean_of(const std::vector<double> &values)
{
    return std::accumulate(values.begin(), values.end(), 0.0) / double(values.size());
}

} // namespace

std::vector<std::string> area_names(const arena::Arena &arena)
{
    std::vector<std::string> names;
    std::map<std::string, int> uses;
    for (const arena::GroundArea &area : arena.areas) {
        const arena::Color &c = area.color;
        std::string name = c.red >= c.green && c.red >= c.blue ? "red"
                           : c.green >= c.blue                 ? "green"
                                                               : "blue";
        names.push_back(name);
        uses[name]++;
    }
    for (size_t i = 0; i < names.size(); i++)
        if (uses[names[i]] > 1)
            names[i] += std::to_string(i + 1);
    return names;
}

std::string csv_text(const std::vector<RunResult> &runs, const std::vector<std::string> &area_names)
{
    std::string text = "condition,communication,shocks,seed,duration,node_id,seconds_on_dangerous";
    for (const std::string &name : area_names)
        text += ",seconds_on_" + name;
    text += ",events_emitted\n";
    for (const RunResult &run : runs) {
        for (const RobotTimes &robot : run.robots) {
            text += format("%s,%s,%s,%u,%g,%u,%.2f",
                           condition_name(run.condition).c_str(),
                           run.condition.communication ? "on" : "off",
                           run.condition.shocks ? "on" : "off",
                           unsigned(run.seed),
                           run.seconds,
                           unsigned(robot.node_id),
                           robot.seconds_on_dangerous);
            for (double seconds : robot.seconds_on_area)
                text += format(",%.2f", seconds);
            text += format(",%u\n", robot.events_emitted);
        }
    }
    return text;
}

std::vector<ConditionSummary> summarize(const std::vector<RunResult> &runs)
{
    std::vector<ConditionSummary> summaries;
    for (const Condition &condition : all_conditions()) {
        ConditionSummary summary;
        summary.condition = condition;
        for (const RunResult &run : runs) {
            if (run.condition.communication != condition.communication ||
                run.condition.shocks != condition.shocks || run.robots.empty())
                continue;
            std::vector<double> seconds;
            for (const RobotTimes &robot : run.robots)
                seconds.push_back(robot.seconds_on_dangerous);
            summary.run_means.push_back(mean_of(seconds));
            summary.robot_seconds.push_back(seconds);
        }
        if (summary.run_means.empty())
            continue;
        const std::vector<double> &means = summary.run_means;
        summary.mean = mean_of(means);
        double squares = 0;
        for (double value : means)
            squares += (value - summary.mean) * (value - summary.mean);
        summary.standard_deviation =
          means.size() > 1 ? std::sqrt(squares / double(means.size() - 1)) : 0;
        summary.minimum = *std::min_element(means.begin(), means.end());
        summary.maximum = *std::max_element(means.begin(), means.end());
        summaries.push_back(summary);
    }
    return summaries;
}

std::string markdown_table(const std::vector<ConditionSummary> &summaries, double seconds)
{
    std::string text = "| condition | communication | shocks | runs | seconds on dangerous "
                       "colour per robot, mean | standard deviation over runs | min–max of "
                       "run means | share of the run |\n"
                       "|---|---|---|---:|---:|---:|---:|---:|\n";
    for (const ConditionSummary &summary : summaries)
        text += format("| %s | %s | %s | %zu | %.1f | %.1f | %.1f–%.1f | %.1f %% |\n",
                       condition_name(summary.condition).c_str(),
                       summary.condition.communication ? "on" : "off",
                       summary.condition.shocks ? "on" : "off",
                       summary.run_means.size(),
                       summary.mean,
                       summary.standard_deviation,
                       summary.minimum,
                       summary.maximum,
                       100 * summary.mean / seconds);
    return text;
}

bool replace_block(std::string &document, const std::string &name, const std::string &block)
{
    const std::string begin = "<!-- begin " + name + " -->\n";
    const std::string end = "<!-- end " + name + " -->";
    size_t begin_at = document.find(begin);
    if (begin_at == std::string::npos)
        return false;
    size_t content_at = begin_at + begin.size();
    size_t end_at = document.find(end, content_at);
    if (end_at == std::string::npos)
        return false;
    document.replace(content_at, end_at - content_at, block);
    return true;
}

} // namespace aseba::experiment
