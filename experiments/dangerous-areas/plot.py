#!/usr/bin/env python3
"""The figure of the dangerous-area experiment (docs/experiment.md) from its CSV.

    plot.py docs/experiment/dangerous-areas.csv docs/experiment/dangerous-areas.svg

Per condition: a bar at the mean of the run means (each run's mean over its
robots) with a standard-deviation whisker, each run's mean as a black dot and
each robot as a small grey dot, in one column per run across the bar. The
output's format follows its extension (.svg, .png, .pdf). Prints the summary
it plots, which is the table's. Restyle freely: everything below is plain
matplotlib.
"""

import argparse
import csv
import statistics
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402

# Text stays text in an SVG, and the file is the same from run to run.
plt.rcParams["svg.fonttype"] = "none"
plt.rcParams["svg.hashsalt"] = "dangerous-areas"

# The conditions in the order of the paper's figure, and their colours.
CONDITIONS = [
    ("on", "on", "shocks+communication", "#4c72b0"),
    ("off", "on", "shocks only", "#dd8452"),
    ("on", "off", "communication only", "#55a868"),
    ("off", "off", "neither", "#c44e52"),
]
BAR_WIDTH = 0.6


def read_runs(path):
    """{condition name: {seed: [seconds on dangerous colour of each robot]}}, and the runs' duration."""
    runs = {}
    durations = set()
    with open(path, newline="") as file:
        for row in csv.DictReader(file):
            by_seed = runs.setdefault(row["condition"], {})
            by_seed.setdefault(int(row["seed"]), []).append(float(row["seconds_on_dangerous"]))
            durations.add(float(row["duration"]))
    return runs, durations


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="the experiment's CSV (dangerous-areas --out DIR)")
    parser.add_argument("figure", help="the figure to write: .svg, .png or .pdf")
    parser.add_argument("--title", help="the figure's title (default: robots, runs and duration)")
    args = parser.parse_args()

    try:
        runs, durations = read_runs(args.csv)
    except (OSError, KeyError, ValueError) as error:
        sys.exit(f"plot.py: cannot read {args.csv}: {error}")
    conditions = [c for c in CONDITIONS if c[2] in runs]
    if not conditions:
        sys.exit(f"plot.py: {args.csv} has no run of a known condition")
    duration = max(durations)

    figure, axes = plt.subplots(figsize=(7.6, 4.7))
    highest = 0.0
    for slot, (communication, shocks, name, colour) in enumerate(conditions):
        seeds = sorted(runs[name])
        robots = [runs[name][seed] for seed in seeds]
        means = [statistics.mean(seconds) for seconds in robots]
        mean = statistics.mean(means)
        spread = statistics.stdev(means) if len(means) > 1 else 0.0
        print(f"{name}: {len(means)} runs, mean {mean:.2f} s, standard deviation {spread:.2f} s")
        slug = name.replace(" ", "-")  # the SVG groups' ids: bar-neither, runs-shocks-only...
        axes.bar(slot, mean, BAR_WIDTH, color=colour, alpha=0.55, edgecolor=colour,
                 gid=f"bar-{slug}")
        axes.errorbar(slot, mean, yerr=[[min(spread, mean)], [spread]], color="black",
                      capsize=8, gid=f"spread-{slug}")
        # One column per run across the bar: its robots, then its mean.
        columns = [slot + BAR_WIDTH * ((r + 0.5) / len(means) - 0.5) for r in range(len(means))]
        axes.scatter([x for x, seconds in zip(columns, robots) for _ in seconds],
                     [value for seconds in robots for value in seconds],
                     s=7, color="#666666", alpha=0.6, zorder=3, gid=f"robots-{slug}")
        axes.scatter(columns, means, s=30, color="black", zorder=4, gid=f"runs-{slug}")
        highest = max([highest, mean + spread] + [value for seconds in robots for value in seconds])

    axes.set_xticks(range(len(conditions)),
                    [f"communication {c[0]}\nshocks {c[1]}" for c in conditions])
    axes.set_ylabel(f"seconds on the dangerous colour per robot\n(runs of {duration:g} s)")
    axes.set_ylim(0, 1.3 * highest or 1)  # room for the legend above the points
    axes.grid(axis="y", color="#dddddd")
    axes.set_axisbelow(True)
    robots_per_run = len(next(iter(runs[conditions[0][2]].values())))
    runs_per_condition = len(runs[conditions[0][2]])
    axes.set_title(args.title or f"Time on the dangerous colour: {robots_per_run} robots, "
                   f"{runs_per_condition} runs of {duration:g} s per condition")
    legend = [
        plt.Rectangle((0, 0), 1, 1, color="#999999", alpha=0.55),
        plt.Line2D([], [], marker="o", linestyle="", color="black"),
        plt.Line2D([], [], marker="o", linestyle="", color="#666666", markersize=3),
    ]
    axes.legend(legend, ["mean ± s.d. of the run means", "one run (mean of its robots)",
                         "one robot"], loc="upper left", fontsize="small", framealpha=0.9)
    figure.tight_layout()
    figure.savefig(args.figure, metadata={"Date": None} if args.figure.endswith(".svg") else None)
    print(f"wrote {args.figure}")


if __name__ == "__main__":
    main()
