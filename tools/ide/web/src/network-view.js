// The network view: every robot at a glance (name, id, state, last error,
// events per second), filterable, and cheap to keep live with 100 robots:
// rows are made once and only their changed cells are touched.

import { h, setChildren } from "./dom.js";
import { robotState, STATE_TEXT } from "./model.js";

function rateText(rate) {
    if (!rate) return "–";
    return rate >= 10 ? `${Math.round(rate)}/s` : `${rate.toFixed(1)}/s`;
}

export class NetworkView {
    constructor(container, { model, onSelect }) {
        this.model = model;
        this.onSelect = onSelect;
        this.active = null;
        this.rows = new Map(); // name -> {row, cells}
        this.summary = h("span", { class: "section-summary" });
        this.filter = h("input", {
            type: "search",
            class: "panel-filter",
            placeholder: "Filter robots",
            label: "Filter robots by name, id or state",
            onInput: () => this.applyFilter(),
        });
        this.list = h("div", {
            class: "network-list",
            attrs: { role: "listbox", "aria-label": "Robots on the network" },
        });
        this.waiting = h("div", { class: "waiting-programs" });
        this.empty = h("div", { class: "panel-note", text: "No robot on the network yet." });
        this.linkProblems = h("div", { class: "link-problems", attrs: { role: "status" } });
        this.element = h(
            "section",
            { class: "sidebar-section network-view", attrs: { "aria-label": "Network" } },
            h("h2", { class: "section-title" }, h("span", { text: "Network" }), this.summary),
            this.filter,
            this.linkProblems,
            this.empty,
            this.list,
            this.waiting,
        );
        container.append(this.element);
        model.on("robots", () => this.render());
        model.on("links", () => {
            this.render();
            this.renderLinkProblems();
        });
        model.on("robot", (robot) => {
            this.updateRow(robot.robot);
            this.renderSummary();
        });
        model.on("status", () => {
            for (const name of this.rows.keys()) this.updateRate(name);
        });
        model.on("project", () => this.renderWaiting());
    }

    render() {
        const robots = this.model.sortedRobots();
        const names = new Set(robots.map((robot) => robot.robot));
        for (const [name, entry] of this.rows)
            if (!names.has(name)) {
                entry.row.remove();
                this.rows.delete(name);
            }
        for (const robot of robots) {
            if (!this.rows.has(robot.robot)) this.rows.set(robot.robot, this.makeRow(robot.robot));
            this.list.append(this.rows.get(robot.robot).row);
            this.updateRow(robot.robot);
        }
        this.empty.hidden = robots.length > 0;
        this.renderSummary();
        this.renderWaiting();
        this.applyFilter();
    }

    makeRow(name) {
        const cells = {
            dot: h("span", { class: "dot" }),
            label: h("span", { class: "network-label" }),
            state: h("span", { class: "network-state" }),
            rate: h("span", { class: "network-rate", title: "user events per second, over the last 5 s" }),
            error: h("div", { class: "network-error" }),
        };
        const row = h(
            "div",
            {
                class: "network-row",
                tabIndex: 0,
                attrs: { role: "option" },
                dataset: { robot: name },
                onClick: () => this.onSelect(name),
                onKeydown: (event) => {
                    if (event.key === "Enter" || event.key === " ") {
                        event.preventDefault();
                        this.onSelect(name);
                    }
                },
            },
            h("div", { class: "network-main" }, cells.dot, cells.label, cells.state, cells.rate),
            cells.error,
        );
        return { row, cells };
    }

    updateRow(name) {
        const entry = this.rows.get(name);
        const robot = this.model.robots.get(name);
        if (!entry || !robot) return;
        const state = robotState(robot);
        const { row, cells } = entry;
        row.dataset.state = state;
        row.classList.toggle("offline", !robot.present);
        row.setAttribute("aria-selected", String(name === this.active));
        cells.label.textContent = this.model.label(robot);
        cells.label.title = `node ${robot.id} on network ${robot.target}${robot.protocol ? `, protocol ${robot.protocol}` : ""}`;
        cells.state.textContent = STATE_TEXT[state] ?? state;
        const error = robot.lastError;
        cells.error.hidden = !error;
        cells.error.textContent = error ? `${error.message}${error.line ? ` (line ${error.line})` : ""}` : "";
        row.dataset.search = `${cells.label.textContent} ${robot.id} ${state}`.toLowerCase();
        this.updateRate(name);
    }

    updateRate(name) {
        const entry = this.rows.get(name);
        if (entry) entry.cells.rate.textContent = rateText(this.model.eventRates[name]);
    }

    renderSummary() {
        const robots = [...this.model.robots.values()];
        const present = robots.filter((robot) => robot.present).length;
        const running = robots.filter((robot) => robot.present && robot.state === "running").length;
        this.summary.textContent = robots.length ? `${present} online · ${running} running` : "";
    }

    // Each network the server cannot reach, with the reason in full.
    renderLinkProblems() {
        const down = this.model.links.filter((link) => !link.up && link.error && link.error !== "connecting");
        setChildren(
            this.linkProblems,
            down.map((link) =>
                h(
                    "div",
                    { class: "link-problem", dataset: { target: link.target } },
                    h("strong", { text: link.target }),
                    h("span", { text: ` cannot be reached: ${link.error}. The IDE tries again by itself.` }),
                ),
            ),
        );
        this.linkProblems.hidden = down.length === 0;
    }

    renderWaiting() {
        const waiting = this.model.waitingPrograms;
        setChildren(
            this.waiting,
            waiting.length ? h("div", { class: "waiting-title", text: "Programs waiting for their robot" }) : null,
            waiting.map((program) => h("div", { class: "waiting-row", text: `${program.name} (node ${program.id})` })),
        );
    }

    applyFilter() {
        const filter = this.filter.value.trim().toLowerCase();
        for (const { row } of this.rows.values()) row.hidden = filter !== "" && !row.dataset.search.includes(filter);
    }

    setActive(name) {
        const previous = this.active;
        this.active = name;
        if (previous) this.updateRow(previous);
        if (name) this.updateRow(name);
    }
}
