// The strip of robot tabs: one per robot the page has seen, in network and
// id order; robots that left stay, greyed, with their text.

import { h } from "./dom.js";
import { robotState, STATE_TEXT } from "./model.js";

export class RobotTabs {
    // `onSelect(name)` when the user picks a tab.
    constructor(container, { model, sessions, onSelect }) {
        this.model = model;
        this.sessions = sessions;
        this.onSelect = onSelect;
        this.active = null;
        this.tabs = new Map(); // name -> element
        this.element = h("nav", { class: "robot-tabs", attrs: { role: "tablist", "aria-label": "Robots" } });
        this.element.addEventListener("keydown", (event) => this.keydown(event));
        container.append(this.element);
        model.on("robots", () => this.render());
        model.on("links", () => this.render());
        model.on("robot", (robot) => this.update(robot.robot));
        sessions.on("status", (session) => this.update(session.name));
        sessions.on("added", () => this.render());
    }

    names() {
        return this.model.sortedRobots().map((robot) => robot.robot);
    }

    render() {
        const names = this.names();
        for (const [name, tab] of this.tabs)
            if (!names.includes(name)) {
                tab.remove();
                this.tabs.delete(name);
            }
        for (const name of names) {
            let tab = this.tabs.get(name);
            if (!tab) {
                tab = h(
                    "button",
                    {
                        type: "button",
                        class: "robot-tab",
                        attrs: { role: "tab" },
                        dataset: { robot: name },
                        onClick: () => this.onSelect(name),
                    },
                    h("span", { class: "dot" }),
                    h("span", { class: "tab-label" }),
                    h("span", { class: "tab-error", text: "!", title: "The script does not compile" }),
                );
                this.tabs.set(name, tab);
            }
            this.element.append(tab); // keeps the order
            this.update(name);
        }
    }

    update(name) {
        const tab = this.tabs.get(name);
        const robot = this.model.robots.get(name);
        if (!tab || !robot) return;
        const state = robotState(robot);
        tab.dataset.state = state;
        tab.classList.toggle("offline", !robot.present);
        tab.querySelector(".tab-label").textContent = this.model.label(robot);
        const session = this.sessions.get(name);
        const failing = session?.status.kind === "error";
        tab.querySelector(".tab-error").hidden = !failing;
        tab.title = `${this.model.label(robot)}: ${STATE_TEXT[state] ?? state}${failing ? "; the script does not compile" : ""}`;
        tab.setAttribute("aria-selected", String(name === this.active));
        tab.tabIndex = name === this.active ? 0 : -1;
    }

    setActive(name) {
        const previous = this.active;
        this.active = name;
        if (previous) this.update(previous);
        if (name) {
            this.update(name);
            this.tabs.get(name)?.scrollIntoView({ block: "nearest", inline: "nearest" });
        }
    }

    // Arrow keys move between tabs, as in any tab list.
    keydown(event) {
        const names = this.names();
        const index = names.indexOf(this.active);
        let next = null;
        if (event.key === "ArrowRight") next = names[(index + 1) % names.length];
        else if (event.key === "ArrowLeft") next = names[(index - 1 + names.length) % names.length];
        else if (event.key === "Home") next = names[0];
        else if (event.key === "End") next = names[names.length - 1];
        if (!next) return;
        event.preventDefault();
        this.onSelect(next);
        this.tabs.get(next)?.focus();
    }
}
