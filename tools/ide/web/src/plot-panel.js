// The Plot panel: event arguments and variables of any robot over time
// (uPlot), each series labelled with its robot; a time window of 10 s,
// 30 s, 60 s or everything; clear; export as CSV.

import uPlot from "uplot";
import "uplot/dist/uPlot.min.css";
import { h, button, setChildren, download } from "./dom.js";
import { icons } from "./icons.js";
import { csv, stampedFileName } from "./format.js";
import { Emitter } from "./emitter.js";

const COLORS = ["#2f81f7", "#e5534b", "#2fbf71", "#d29922", "#a371f7", "#1fb6c1", "#f778ba", "#8b949e"];
const WINDOWS = [
    { seconds: 10, text: "10 s" },
    { seconds: 30, text: "30 s" },
    { seconds: 60, text: "60 s" },
    { seconds: 0, text: "All" },
];
// Samples kept per series (at 10 Hz: almost 3 hours).
const MAX_SAMPLES = 100000;
const REDRAW_MS = 250;

export class PlotPanel extends Emitter {
    constructor(container, { model, messages }) {
        super();
        this.model = model;
        this.messages = messages;
        this.series = []; // {key, robot, kind: "variable" | "event", name, index, color, times, values}
        this.window = 30;
        this.plot = null;
        this.redrawTimer = null;
        // The user zoomed in: the time window stops following until a
        // double-click zooms out.
        this.zoomed = false;

        this.robotSelect = h("select", {
            class: "select",
            label: "Robot of the new series",
            onChange: () => this.renderSources(),
        });
        this.sourceSelect = h("select", { class: "select", label: "Variable or event of the new series" });
        this.indexInput = h("input", {
            class: "text-input number",
            type: "number",
            min: "0",
            value: "0",
            label: "Index in the variable or argument of the event",
        });
        this.seriesList = h("div", { class: "series-list", attrs: { role: "list", "aria-label": "Plotted series" } });
        this.windowButtons = WINDOWS.map((entry) =>
            h("button", {
                type: "button",
                class: "segment",
                text: entry.text,
                label: `Show ${entry.seconds ? `the last ${entry.text}` : "everything"}`,
                dataset: { seconds: String(entry.seconds) },
                onClick: () => this.setWindow(entry.seconds),
            }),
        );
        this.chart = h("div", { class: "plot-chart" });
        this.empty = h("div", {
            class: "plot-empty",
            text: "Choose a robot and a variable or an event argument, then Add.",
        });

        const form = h(
            "form",
            {
                class: "plot-form",
                onSubmit: (event) => {
                    event.preventDefault();
                    this.addFromForm();
                },
            },
            this.robotSelect,
            this.sourceSelect,
            h("label", { class: "inline-label" }, "index ", this.indexInput),
            h(
                "button",
                { type: "submit", class: "button", label: "Add the series to the plot" },
                h("span", { class: "button-text", text: "Add" }),
            ),
        );
        this.element = h(
            "div",
            { class: "plot-panel" },
            h(
                "div",
                { class: "panel-toolbar" },
                h("span", { class: "panel-title", text: "Plot" }),
                form,
                h(
                    "div",
                    { class: "segmented", attrs: { role: "group", "aria-label": "Time window" } },
                    this.windowButtons,
                ),
                button({
                    icon: icons.clear,
                    text: "Clear",
                    label: "Clear the plot's data",
                    onClick: () => this.clear(),
                }),
                button({
                    icon: icons.download,
                    text: "CSV",
                    label: "Export the plot's data as CSV",
                    onClick: () => this.exportCsv(),
                }),
            ),
            this.seriesList,
            h("div", { class: "plot-area" }, this.chart, this.empty),
        );
        container.append(this.element);
        new ResizeObserver(() => this.resize()).observe(this.chart);
        this.chart.addEventListener("dblclick", () => {
            this.zoomed = false;
            this.redraw();
        });
        model.on("robots", () => this.renderRobots());
        model.on("robot", (robot) => {
            if (robot.robot === this.robotSelect.value) this.renderSources();
        });
        model.on("definitions", () => this.renderSources());
        this.setWindow(this.window);
        this.renderRobots();
        this.renderSeries();
    }

    // Robots whose variables a series needs (the page watches them).
    watchedRobots() {
        return [...new Set(this.series.filter((series) => series.kind === "variable").map((series) => series.robot))];
    }

    renderRobots() {
        const selected = this.robotSelect.value;
        setChildren(
            this.robotSelect,
            this.model
                .sortedRobots()
                .map((robot) => h("option", { value: robot.robot, text: this.model.label(robot) })),
        );
        if (this.model.robots.has(selected)) this.robotSelect.value = selected;
        this.renderSources();
    }

    renderSources() {
        const selected = this.sourceSelect.value;
        const robot = this.model.robots.get(this.robotSelect.value);
        const variables = robot?.variables ?? [];
        setChildren(
            this.sourceSelect,
            h(
                "optgroup",
                { label: "Variables" },
                variables.map((variable) =>
                    h("option", {
                        value: `variable:${variable.name}`,
                        text: variable.size > 1 ? `${variable.name}[${variable.size}]` : variable.name,
                    }),
                ),
            ),
            h(
                "optgroup",
                { label: "Events" },
                this.model.definitions.events.map((event) =>
                    h("option", { value: `event:${event.name}`, text: `event ${event.name}` }),
                ),
            ),
        );
        if ([...this.sourceSelect.options].some((option) => option.value === selected))
            this.sourceSelect.value = selected;
    }

    addFromForm() {
        const robot = this.robotSelect.value;
        const [kind, name] = this.sourceSelect.value.split(/:(.*)/s);
        const index = Number(this.indexInput.value);
        if (!robot || !name) {
            this.messages.error("Choose a robot and a variable or an event to plot.");
            return;
        }
        const size =
            kind === "variable"
                ? this.model.robots.get(robot)?.variables?.find((variable) => variable.name === name)?.size
                : this.model.definitions.events.find((event) => event.name === name)?.size;
        if (!Number.isInteger(index) || index < 0 || (size !== undefined && index >= size)) {
            this.messages.error(
                `${name} has ${size} ${kind === "variable" ? "word" : "argument"}${size === 1 ? "" : "s"}: index ${index} is out of it.`,
            );
            return;
        }
        this.add({ robot, kind, name, index });
    }

    // Adds a series: {robot, kind: "variable" | "event", name, index}.
    add({ robot, kind, name, index = 0 }) {
        const key = `${robot}|${kind}|${name}|${index}`;
        if (this.series.some((series) => series.key === key)) return;
        const used = new Set(this.series.map((series) => series.color));
        const color = COLORS.find((candidate) => !used.has(candidate)) ?? COLORS[this.series.length % COLORS.length];
        this.series.push({ key, robot, kind, name, index, color, times: [], values: [] });
        this.rebuild();
        this.emit("watch");
    }

    remove(key) {
        this.series = this.series.filter((series) => series.key !== key);
        this.rebuild();
        this.emit("watch");
    }

    label(series) {
        const what =
            series.kind === "variable"
                ? `${series.name}${this.isArray(series) ? `[${series.index}]` : ""}`
                : `${series.name}[${series.index}]`;
        return `${this.model.label(series.robot)} · ${series.kind === "event" ? "event " : ""}${what}`;
    }

    isArray(series) {
        const size = this.model.robots
            .get(series.robot)
            ?.variables?.find((variable) => variable.name === series.name)?.size;
        return size === undefined || size > 1;
    }

    push(series, time, value) {
        series.times.push(time / 1000);
        series.values.push(value);
        if (series.times.length > MAX_SAMPLES) {
            series.times.splice(0, series.times.length - MAX_SAMPLES);
            series.values.splice(0, series.values.length - MAX_SAMPLES);
        }
        this.scheduleRedraw();
    }

    // A `variables` message.
    addVariables(message) {
        const robot = this.model.robots.get(message.robot);
        for (const series of this.series) {
            if (series.kind !== "variable" || series.robot !== message.robot) continue;
            const location = robot?.variables?.find((variable) => variable.name === series.name);
            const address = location ? location.address + series.index : -1;
            if (address >= 0 && address < message.values.length)
                this.push(series, message.time, message.values[address]);
        }
    }

    // Log entries.
    addEvents(entries) {
        for (const entry of entries) {
            if (entry.kind !== "event") continue;
            const name = this.model.eventName(entry);
            for (const series of this.series)
                if (
                    series.kind === "event" &&
                    series.robot === entry.source &&
                    series.name === name &&
                    series.index < (entry.args?.length ?? 0)
                )
                    this.push(series, entry.time, entry.args[series.index]);
        }
    }

    setWindow(seconds) {
        this.window = seconds;
        this.zoomed = false;
        for (const element of this.windowButtons)
            element.setAttribute("aria-pressed", String(Number(element.dataset.seconds) === seconds));
        this.redraw();
    }

    clear() {
        for (const series of this.series) {
            series.times = [];
            series.values = [];
        }
        this.redraw();
    }

    renderSeries() {
        setChildren(
            this.seriesList,
            this.series.map((series) =>
                h(
                    "span",
                    { class: "series-chip", attrs: { role: "listitem" }, dataset: { key: series.key } },
                    h("span", { class: "series-swatch", style: { background: series.color } }),
                    h("span", { text: this.label(series) }),
                    (series.valueElement = h("span", {
                        class: "series-value",
                        title: "the value under the cursor, else the latest",
                    })),
                    button({
                        icon: icons.close,
                        label: `Remove ${this.label(series)} from the plot`,
                        className: "icon-only small",
                        onClick: () => this.remove(series.key),
                    }),
                ),
            ),
        );
        this.empty.hidden = this.series.length > 0;
    }

    // A new uPlot when the series change; setData for new samples.
    rebuild() {
        this.renderSeries();
        this.plot?.destroy();
        this.plot = null;
        if (this.series.length === 0) return;
        const { width, height } = this.chartSize();
        // Canvas strokes take colours, not CSS variables.
        const style = getComputedStyle(this.element);
        const axisColor = style.getPropertyValue("--text-muted").trim() || "#6e7781";
        const gridColor = style.getPropertyValue("--grid").trim() || "rgba(128,128,128,0.15)";
        const axis = {
            stroke: axisColor,
            grid: { stroke: gridColor, width: 1 },
            ticks: { stroke: gridColor, width: 1 },
        };
        const options = {
            width,
            height,
            scales: { x: { time: true } },
            series: [
                {},
                ...this.series.map((series) => ({
                    label: this.label(series),
                    stroke: series.color,
                    width: 1.5,
                    spanGaps: true,
                    points: { show: false },
                })),
            ],
            axes: [axis, axis],
            // The chips above are the legend; they show the values.
            legend: { show: false },
            cursor: { drag: { x: true, y: false } },
            hooks: {
                setCursor: [(plot) => this.showValues(plot.cursor.idx)],
                setSelect: [
                    (plot) => {
                        if (plot.select.width > 0) this.zoomed = true;
                    },
                ],
            },
        };
        this.zoomed = false;
        this.plot = new uPlot(options, this.alignedData(), this.chart);
    }

    /** @returns {import("uplot").AlignedData} */
    alignedData() {
        const now = Date.now() / 1000;
        const since = this.window > 0 ? now - this.window : -Infinity;
        const tables = this.series.map((series) => {
            let first = 0;
            while (first < series.times.length && series.times[first] < since) first++;
            return [series.times.slice(first), series.values.slice(first)];
        });
        if (tables.every(([times]) => times.length === 0)) return [[], ...this.series.map(() => [])];
        return /** @type {import("uplot").AlignedData} */ (uPlot.join(tables));
    }

    // The values at data index `index` (under the cursor), or the latest.
    showValues(index) {
        const data = this.plot?.data;
        this.series.forEach((series, column) => {
            let value;
            if (index !== null && index !== undefined && data) value = data[column + 1][index];
            else value = series.values[series.values.length - 1];
            const text = value === null || value === undefined ? "" : `= ${value}`;
            if (series.valueElement && series.valueElement.textContent !== text) series.valueElement.textContent = text;
        });
    }

    scheduleRedraw() {
        if (this.redrawTimer) return;
        this.redrawTimer = setTimeout(() => {
            this.redrawTimer = null;
            this.redraw();
        }, REDRAW_MS);
    }

    redraw() {
        if (!this.plot) return;
        this.plot.setData(this.alignedData(), !this.zoomed);
        if (this.plot.cursor.idx === null || this.plot.cursor.idx === undefined) this.showValues(null);
        if (this.window > 0 && !this.zoomed) {
            const now = Date.now() / 1000;
            this.plot.setScale("x", { min: now - this.window, max: now });
        }
    }

    chartSize() {
        return { width: Math.max(200, this.chart.clientWidth), height: Math.max(80, this.chart.clientHeight) };
    }

    resize() {
        if (this.plot) this.plot.setSize(this.chartSize());
    }

    exportCsv() {
        const tables = this.series.map((series) => [series.times, series.values]);
        if (tables.length === 0) {
            this.messages.info("Nothing to export: the plot has no series.");
            return;
        }
        const data = uPlot.join(tables);
        /** @type {(string | number)[][]} */
        const rows = [["time", ...this.series.map((series) => this.label(series))]];
        for (let i = 0; i < data[0].length; i++)
            rows.push([
                new Date(data[0][i] * 1000).toISOString(),
                ...this.series.map((_, column) => data[column + 1][i] ?? ""),
            ]);
        download(stampedFileName("aseba-plot", "csv"), csv(rows), "text/csv");
    }
}
