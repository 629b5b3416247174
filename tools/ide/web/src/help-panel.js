// The help: the keys, the language in brief, and what the robot shown
// offers (its variables, local events and native functions, from its own
// description). A panel over the right of the page, opened by F1 or the top
// bar's Help; it follows the robot shown while open.

import { h, button, setChildren } from "./dom.js";
import { icons } from "./icons.js";
import { SHORTCUTS } from "./keys.js";
import { LANGUAGE } from "./help-language.js";
import { nativeSignature } from "./robot-info.js";

const SECTIONS = [
    ["keys", "Keys"],
    ["language", "Language"],
    ["robot", "This robot"],
];

export class HelpPanel {
    /**
     * @param {HTMLElement} container
     * @param {object} parts
     * @param {import("./model.js").Model} parts.model
     * @param {() => string | null} parts.robotShown the name of the robot shown
     */
    constructor(container, { model, robotShown }) {
        this.model = model;
        this.robotShown = robotShown;
        this.isOpen = false;
        this.section = "keys";
        this.sectionButtons = SECTIONS.map(([key, text]) =>
            h("button", {
                type: "button",
                class: "help-section-tab",
                text,
                attrs: { role: "tab" },
                dataset: { section: key },
                onClick: () => this.show(key),
            }),
        );
        this.body = h("div", { class: "help-body", attrs: { role: "tabpanel" }, tabIndex: 0 });
        this.element = h(
            "aside",
            { class: "help-panel", attrs: { "aria-label": "Help" }, hidden: true },
            h(
                "div",
                { class: "help-header" },
                h("h2", { text: "Help" }),
                h("div", { class: "help-sections", attrs: { role: "tablist" } }, this.sectionButtons),
                button({
                    icon: icons.close,
                    label: "Close the help (Escape)",
                    className: "icon-only",
                    onClick: () => this.close(),
                }),
            ),
            this.body,
        );
        container.append(this.element);
        model.on("robot", (robot) => {
            if (this.isOpen && this.section === "robot" && robot.robot === this.robotShown()) this.render();
        });
    }

    toggle() {
        if (this.isOpen) this.close();
        else this.open();
    }

    open(section = this.section) {
        this.isOpen = true;
        this.element.hidden = false;
        this.show(section);
        this.body.focus();
    }

    close() {
        this.isOpen = false;
        this.element.hidden = true;
    }

    // The robot shown changed: its section follows.
    robotChanged() {
        if (this.isOpen && this.section === "robot") this.render();
    }

    /** @param {string} section */
    show(section) {
        this.section = section;
        for (const tab of this.sectionButtons)
            tab.setAttribute("aria-selected", String(tab.dataset.section === section));
        this.render();
        this.body.scrollTop = 0;
    }

    render() {
        if (this.section === "keys") setChildren(this.body, this.keys());
        else if (this.section === "language") setChildren(this.body, this.language());
        else setChildren(this.body, this.robot());
        this.body.dataset.section = this.section;
    }

    keys() {
        return SHORTCUTS.map(({ section, keys }) => [
            h("h3", { text: section }),
            h(
                "table",
                { class: "help-keys" },
                h(
                    "tbody",
                    {},
                    keys.map(([key, what]) =>
                        h("tr", {}, h("th", {}, h("kbd", { text: key })), h("td", { text: what })),
                    ),
                ),
            ),
        ]);
    }

    language() {
        return LANGUAGE.map(({ title, code, text }) => [
            h("h3", { text: title }),
            h("pre", { class: "help-code" }, h("code", { text: code })),
            h("p", { text }),
        ]);
    }

    robot() {
        const name = this.robotShown();
        const robot = name ? this.model.robots.get(name) : null;
        const description = robot?.description;
        if (!description)
            return h("p", { class: "panel-note", text: "Known once a robot is shown and has described itself." });
        const variables = (robot.variables ?? []).filter((variable) => !variable.user);
        return [
            h("p", {
                class: "help-lead",
                text: `${this.model.label(robot)}, as it describes itself: ${variables.length} variables, ${description.localEvents.length} local events, ${description.natives.length} native functions. Memory: ${description.bytecodeSize} words of bytecode, ${description.variablesSize} of variables, a stack of ${description.stackSize}.`,
            }),
            h("h3", { text: "Variables" }),
            h(
                "table",
                { class: "help-table help-variables" },
                h(
                    "tbody",
                    {},
                    variables.map((variable) =>
                        h(
                            "tr",
                            { dataset: { name: variable.name } },
                            h(
                                "th",
                                {},
                                h("code", {
                                    text: variable.size > 1 ? `${variable.name}[${variable.size}]` : variable.name,
                                }),
                            ),
                            h("td", { text: variable.size > 1 ? `${variable.size} words` : "1 word" }),
                        ),
                    ),
                ),
            ),
            h("h3", { text: "Local events" }),
            h(
                "dl",
                { class: "help-list help-events" },
                description.localEvents.map((event) => [
                    h("dt", {}, h("code", { text: `onevent ${event.name}` })),
                    h("dd", { text: event.description || "(no description)" }),
                ]),
            ),
            h("h3", { text: "Native functions" }),
            h(
                "dl",
                { class: "help-list help-natives" },
                description.natives.map((native) => [
                    h("dt", {}, h("code", { text: `call ${nativeSignature(native)}` })),
                    h("dd", { text: native.description || "(no description)" }),
                ]),
            ),
        ];
    }
}
