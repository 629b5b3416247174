// The event monitor: the events and errors that cross the network, decoded
// (time, source robot, event name, arguments), filterable by robot, event
// and text; pause, clear, export as CSV. Only the latest matching rows are
// in the page, so that a busy network does not slow it down.

import { h, button, setChildren, download } from "./dom.js";
import { icons } from "./icons.js";
import { clockTime, csv, stampedFileName } from "./format.js";

// Entries kept in the page (the export has them all).
const MAX_ENTRIES = 50000;
// Rows in the table.
const MAX_ROWS = 400;

export class EventMonitor {
    constructor(container, { model }) {
        this.model = model;
        this.entries = [];
        this.clearedAt = 0;
        this.paused = false;
        this.unseen = 0;

        this.sourceFilter = h("select", {
            class: "select",
            label: "Show the entries of",
            onChange: () => this.render(),
        });
        this.eventFilter = h("select", { class: "select", label: "Show the event", onChange: () => this.render() });
        this.textFilter = h("input", {
            type: "search",
            class: "panel-filter inline",
            placeholder: "Filter text",
            label: "Filter the log by text",
            onInput: () => this.render(),
        });
        this.pauseButton = button({
            icon: icons.pause,
            text: "Pause",
            label: "Pause the monitor",
            onClick: () => this.setPaused(!this.paused),
        });
        this.count = h("span", { class: "monitor-count", attrs: { "aria-live": "off" } });
        this.body = h("tbody");
        this.scroller = h(
            "div",
            { class: "monitor-scroller" },
            h(
                "table",
                { class: "monitor-table", attrs: { "aria-label": "Event log" } },
                h(
                    "thead",
                    {},
                    h(
                        "tr",
                        {},
                        ["Time", "Source", "Event", "Arguments"].map((title) =>
                            h("th", { text: title, attrs: { scope: "col" } }),
                        ),
                    ),
                ),
                this.body,
            ),
        );
        this.element = h(
            "div",
            { class: "monitor" },
            h(
                "div",
                { class: "panel-toolbar" },
                h("span", { class: "panel-title", text: "Monitor" }),
                this.sourceFilter,
                this.eventFilter,
                this.textFilter,
                this.pauseButton,
                button({ icon: icons.clear, text: "Clear", label: "Clear the log", onClick: () => this.clear() }),
                button({
                    icon: icons.download,
                    text: "CSV",
                    label: "Export the log as CSV",
                    onClick: () => this.exportCsv(),
                }),
                this.count,
            ),
            this.scroller,
        );
        container.append(this.element);
        model.on("robots", () => this.renderFilters());
        model.on("definitions", () => {
            this.renderFilters();
            this.render();
        });
        this.renderFilters();
    }

    // The history a hello brings replaces ours (minus what the user cleared).
    reset(entries) {
        this.entries = entries.filter((entry) => entry.time > this.clearedAt);
        this.unseen = 0;
        this.render();
    }

    add(entries) {
        for (const entry of entries) if (entry.time > this.clearedAt) this.entries.push(entry);
        if (this.entries.length > MAX_ENTRIES) this.entries.splice(0, this.entries.length - MAX_ENTRIES);
        if (this.paused) {
            this.unseen += entries.length;
            this.renderCount();
            return;
        }
        const atBottom = this.scroller.scrollTop + this.scroller.clientHeight >= this.scroller.scrollHeight - 4;
        const matches = this.matcher();
        for (const entry of entries) if (matches(entry)) this.body.append(this.row(entry));
        while (this.body.children.length > MAX_ROWS) this.body.firstElementChild.remove();
        if (atBottom) this.scroller.scrollTop = this.scroller.scrollHeight;
        this.renderCount();
    }

    setPaused(paused) {
        this.paused = paused;
        this.unseen = 0;
        this.pauseButton.querySelector(".button-text").textContent = paused ? "Resume" : "Pause";
        this.pauseButton.setAttribute("aria-label", paused ? "Resume the monitor" : "Pause the monitor");
        this.pauseButton.title = this.pauseButton.getAttribute("aria-label");
        this.pauseButton.classList.toggle("active", paused);
        if (!paused) this.render();
        else this.renderCount();
    }

    clear() {
        this.clearedAt = this.entries.reduce((latest, entry) => Math.max(latest, entry.time), Date.now());
        this.entries = [];
        this.unseen = 0;
        this.render();
    }

    sourceText(source) {
        if (source === "ide") return "this IDE";
        if (source === "host") return "another tool";
        return this.model.label(source);
    }

    // What an entry says, cell by cell: [source, event, arguments, kind].
    cells(entry) {
        const source = this.sourceText(entry.source);
        if (entry.kind === "event")
            return [source, this.model.eventName(entry), (entry.args ?? []).join(", "), "event"];
        if (entry.kind === "error") {
            const error = entry.error ?? {};
            return [
                source,
                "run-time error",
                `${error.message ?? ""}${error.line ? ` (line ${error.line})` : ""}`,
                "error",
            ];
        }
        return [source, "malformed message", entry.message ?? "", "malformed"];
    }

    row(entry) {
        const [source, event, args, kind] = this.cells(entry);
        return h(
            "tr",
            { class: `monitor-row kind-${kind}` },
            h("td", { class: "monitor-time", text: clockTime(entry.time) }),
            h("td", { class: "monitor-source", text: source }),
            h("td", { class: "monitor-event", text: event }),
            h("td", { class: "monitor-args", text: args }),
        );
    }

    matcher() {
        const source = this.sourceFilter.value;
        const event = this.eventFilter.value;
        const text = this.textFilter.value.trim().toLowerCase();
        return (entry) => {
            if (source && entry.source !== source) return false;
            if (event === "@errors" && entry.kind === "event") return false;
            if (event && event !== "@errors" && (entry.kind !== "event" || this.model.eventName(entry) !== event))
                return false;
            if (text && !this.cells(entry).slice(0, 3).join(" ").toLowerCase().includes(text)) return false;
            return true;
        };
    }

    render() {
        const matches = this.matcher();
        const rows = [];
        for (let index = this.entries.length - 1; index >= 0 && rows.length < MAX_ROWS; index--)
            if (matches(this.entries[index])) rows.push(this.row(this.entries[index]));
        rows.reverse();
        this.body.replaceChildren(...rows);
        this.scroller.scrollTop = this.scroller.scrollHeight;
        this.renderCount();
    }

    renderCount() {
        const total = this.entries.length;
        this.count.textContent = this.paused
            ? `paused, ${this.unseen} new`
            : `${total} entr${total === 1 ? "y" : "ies"}`;
    }

    renderFilters() {
        const keep = (select) => select.value;
        const source = keep(this.sourceFilter);
        const event = keep(this.eventFilter);
        setChildren(
            this.sourceFilter,
            h("option", { value: "", text: "All sources" }),
            this.model
                .sortedRobots()
                .map((robot) => h("option", { value: robot.robot, text: this.model.label(robot) })),
            h("option", { value: "ide", text: "This IDE" }),
            h("option", { value: "host", text: "Other tools" }),
        );
        setChildren(
            this.eventFilter,
            h("option", { value: "", text: "All events" }),
            this.model.definitions.events.map((definition) =>
                h("option", { value: definition.name, text: definition.name }),
            ),
            h("option", { value: "@errors", text: "Errors only" }),
        );
        this.sourceFilter.value = [...this.sourceFilter.options].some((option) => option.value === source)
            ? source
            : "";
        this.eventFilter.value = [...this.eventFilter.options].some((option) => option.value === event) ? event : "";
    }

    exportCsv() {
        const matches = this.matcher();
        const rows = [["time", "source", "kind", "event", "arguments"]];
        for (const entry of this.entries) {
            if (!matches(entry)) continue;
            const [source, event, args, kind] = this.cells(entry);
            rows.push([new Date(entry.time).toISOString(), source, kind, event, args]);
        }
        download(stampedFileName("aseba-events", "csv"), csv(rows), "text/csv");
    }
}
