// The dangerous-area experiment's CSV, table and figure (see report.hpp).

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

std::string escape_xml(const std::string &text)
{
    std::string escaped;
    for (char c : text) {
        switch (c) {
        case '&': escaped += "&amp;"; break;
        case '<': escaped += "&lt;"; break;
        case '>': escaped += "&gt;"; break;
        case '"': escaped += "&quot;"; break;
        default: escaped += c;
        }
    }
    return escaped;
}

// The smallest 1, 2 or 5 times a power of ten that cuts [0, top] into at
// most `ticks` steps.
double tick_step(double top, int ticks)
{
    double power = std::pow(10.0, std::floor(std::log10(top / ticks)));
    for (double factor : { 1.0, 2.0, 5.0, 10.0 })
        if (factor * power * ticks >= top)
            return factor * power;
    return 10 * power;
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
    std::string text = "condition,communication,shocks,seed,node_id,seconds_on_dangerous";
    for (const std::string &name : area_names)
        text += ",seconds_on_" + name;
    text += ",events_emitted\n";
    for (const RunResult &run : runs) {
        for (const RobotTimes &robot : run.robots) {
            text += format("%s,%s,%s,%u,%u,%.2f",
                           condition_name(run.condition).c_str(),
                           run.condition.communication ? "on" : "off",
                           run.condition.shocks ? "on" : "off",
                           unsigned(run.seed),
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

std::string svg_figure(const std::vector<ConditionSummary> &summaries,
                       double seconds,
                       const std::string &title)
{
    constexpr double width = 760, height = 470;
    constexpr double left = 80, right = 20, top = 60, bottom = 70;
    constexpr double plot_width = width - left - right, plot_height = height - top - bottom;
    constexpr int most_ticks = 8;
    constexpr double bar_share = 0.6; // of a condition's slot
    const char *bar_colors[] = { "#4c72b0", "#dd8452", "#55a868", "#c44e52" };

    double highest = 1;
    for (const ConditionSummary &summary : summaries) {
        highest = std::max(highest, summary.mean + summary.standard_deviation);
        for (const auto &run : summary.robot_seconds)
            for (double value : run)
                highest = std::max(highest, value);
    }
    const double step = tick_step(highest, most_ticks);
    const double axis_top = std::ceil(highest / step) * step;
    auto y_of = [&](double value) { return top + plot_height * (1 - value / axis_top); };
    const double slot = plot_width / double(std::max<size_t>(summaries.size(), 1));

    std::string svg = format("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" "
                             "height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" "
                             "font-family=\"sans-serif\" font-size=\"13\">\n",
                             width,
                             height,
                             width,
                             height);
    svg += format("<rect width=\"%.0f\" height=\"%.0f\" fill=\"white\"/>\n", width, height);
    svg += format("<text x=\"%.0f\" y=\"24\" text-anchor=\"middle\" font-size=\"16\" "
                  "font-weight=\"bold\">%s</text>\n",
                  width / 2,
                  escape_xml(title).c_str());

    // Grid, ticks and axes.
    for (double value = 0; value <= axis_top + step / 2; value += step) {
        double y = y_of(value);
        svg += format("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n",
                      left,
                      y,
                      width - right,
                      y);
        svg += format(
          "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n", left - 6, y + 4, value);
    }
    svg += format("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"black\"/>\n",
                  left,
                  top,
                  left,
                  top + plot_height);
    svg += format("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"black\"/>\n",
                  left,
                  top + plot_height,
                  width - right,
                  top + plot_height);
    svg += format("<text transform=\"translate(22 %.1f) rotate(-90)\" text-anchor=\"middle\">"
                  "seconds on the dangerous colour per robot (runs of %g s)</text>\n",
                  top + plot_height / 2,
                  seconds);

    for (size_t c = 0; c < summaries.size(); c++) {
        const ConditionSummary &summary = summaries[c];
        const double centre = left + slot * (double(c) + 0.5);
        const double bar_width = slot * bar_share;
        svg += format("<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"%s\" "
                      "fill-opacity=\"0.55\" stroke=\"%s\"/>\n",
                      centre - bar_width / 2,
                      y_of(summary.mean),
                      bar_width,
                      top + plot_height - y_of(summary.mean),
                      bar_colors[c % 4],
                      bar_colors[c % 4]);
        // Standard-deviation whisker.
        const double low = std::max(0.0, summary.mean - summary.standard_deviation);
        const double high = summary.mean + summary.standard_deviation;
        svg += format("<path d=\"M%.1f %.1fV%.1fM%.1f %.1fH%.1fM%.1f %.1fH%.1f\" "
                      "stroke=\"black\" fill=\"none\"/>\n",
                      centre,
                      y_of(low),
                      y_of(high),
                      centre - 8,
                      y_of(low),
                      centre + 8,
                      centre - 8,
                      y_of(high),
                      centre + 8);
        // Each run in its own column across the bar: its robots, then its mean.
        const size_t runs = summary.run_means.size();
        for (size_t r = 0; r < runs; r++) {
            const double x = centre + bar_width * ((double(r) + 0.5) / double(runs) - 0.5);
            for (double value : summary.robot_seconds[r])
                svg += format("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"2.5\" fill=\"#666\" "
                              "fill-opacity=\"0.6\"/>\n",
                              x,
                              y_of(value));
            svg += format("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4.5\" fill=\"black\"/>\n",
                          x,
                          y_of(summary.run_means[r]));
        }
        const Condition &condition = summary.condition;
        svg += format("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">communication %s"
                      "</text>\n",
                      centre,
                      top + plot_height + 20,
                      condition.communication ? "on" : "off");
        svg += format("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">shocks %s</text>\n",
                      centre,
                      top + plot_height + 38,
                      condition.shocks ? "on" : "off");
    }

    // Legend, above the plot.
    const double legend_y = 44;
    svg += format("<rect x=\"%.1f\" y=\"%.1f\" width=\"14\" height=\"10\" fill=\"#999\" "
                  "fill-opacity=\"0.55\" stroke=\"#666\"/>\n"
                  "<text x=\"%.1f\" y=\"%.1f\">mean ± s.d. of the run means</text>\n",
                  left,
                  legend_y - 9,
                  left + 20,
                  legend_y);
    svg += format("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4.5\" fill=\"black\"/>\n"
                  "<text x=\"%.1f\" y=\"%.1f\">one run (mean of its robots)</text>\n",
                  left + 255,
                  legend_y - 4,
                  left + 265,
                  legend_y);
    svg += format("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"2.5\" fill=\"#666\"/>\n"
                  "<text x=\"%.1f\" y=\"%.1f\">one robot</text>\n",
                  left + 475,
                  legend_y - 4,
                  left + 485,
                  legend_y);
    svg += "</svg>\n";
    return svg;
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
