// The bottom panel: Events (global events, sending one, the monitor), Plot
// and Constants, as tabs.

import { h, button, setChildren, iconElement } from "./dom.js";
import { icons } from "./icons.js";
import { EventMonitor } from "./event-monitor.js";
import { DefinitionList, EventSender } from "./definitions.js";
import { PlotPanel } from "./plot-panel.js";
import { loadSetting, saveSetting } from "./storage.js";

export class BottomPanel {
    constructor(container, { model, commands, messages }) {
        const panes = {
            events: h("div", { class: "bottom-pane events-pane" }),
            plot: h("div", { class: "bottom-pane plot-pane" }),
            constants: h("div", { class: "bottom-pane constants-pane" }),
        };
        const titles = { events: "Events", plot: "Plot", constants: "Constants" };
        this.panes = panes;
        this.tabs = Object.keys(panes).map((key) =>
            h("button", {
                type: "button",
                class: "bottom-tab",
                text: titles[key],
                attrs: { role: "tab", "aria-controls": `pane-${key}` },
                dataset: { pane: key },
                onClick: () => this.show(key),
            }),
        );
        for (const [key, pane] of Object.entries(panes)) {
            pane.id = `pane-${key}`;
            pane.setAttribute("role", "tabpanel");
            pane.setAttribute("aria-label", titles[key]);
        }
        this.container = container;
        this.sizeButton = button({
            icon: icons.enlarge,
            text: "Enlarge",
            label: "Enlarge the bottom panel (the plot, the monitor) over the editor",
            className: "small bottom-size",
            onClick: () => this.setEnlarged(!this.enlarged),
        });
        this.element = h(
            "section",
            { class: "bottom-panel" },
            h(
                "div",
                { class: "bottom-tabs" },
                h(
                    "div",
                    { class: "bottom-tab-list", attrs: { role: "tablist", "aria-label": "Bottom panel" } },
                    this.tabs,
                ),
                this.sizeButton,
            ),
            h("div", { class: "bottom-body" }, Object.values(panes)),
        );
        container.append(this.element);
        this.enlarged = false;

        const eventSide = h("div", { class: "events-side" });
        panes.events.append(eventSide);
        this.eventDefinitions = new DefinitionList(eventSide, { kind: "events", model, commands, messages });
        this.sender = new EventSender(eventSide, { model, commands, messages });
        this.monitor = new EventMonitor(panes.events, { model });
        this.plot = new PlotPanel(panes.plot, { model, messages });
        const constantsBox = h(
            "div",
            { class: "constants-box" },
            h("p", {
                class: "panel-note",
                text: "Constants are shared by every robot's script: defined here once, used by name (for loops, array sizes, thresholds).",
            }),
        );
        panes.constants.append(constantsBox);
        this.constants = new DefinitionList(constantsBox, { kind: "constants", model, commands, messages });
        this.show(loadSetting("bottom-tab", "events"));
    }

    // Enlarged, the panel takes the height of the editor but for the robot
    // tabs and toolbar; the page remembers neither: the editor comes back
    // at the next visit.
    setEnlarged(enlarged) {
        this.enlarged = enlarged;
        this.container.parentElement.classList.toggle("bottom-enlarged", enlarged);
        const label = enlarged
            ? "Shrink the bottom panel back under the editor"
            : "Enlarge the bottom panel (the plot, the monitor) over the editor";
        this.sizeButton.setAttribute("aria-label", label);
        this.sizeButton.title = label;
        setChildren(
            this.sizeButton,
            iconElement(enlarged ? icons.shrink : icons.enlarge),
            h("span", { class: "button-text", text: enlarged ? "Shrink" : "Enlarge" }),
        );
        this.plot.resize();
    }

    show(key) {
        if (!this.panes[key]) key = "events";
        for (const [name, pane] of Object.entries(this.panes)) pane.hidden = name !== key;
        for (const tab of this.tabs) tab.setAttribute("aria-selected", String(tab.dataset.pane === key));
        saveSetting("bottom-tab", key);
        if (key === "plot") this.plot.resize();
    }
}
