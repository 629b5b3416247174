// The Variables panel of a robot: every variable with its live value (from
// `variables` messages), the robot's own (sensors, actuators) apart from the
// program's, arrays folded or open, and each value editable in place:
// Enter writes it to the robot (`set-variable`), Escape gives up.

import { h, button, setChildren, iconElement, download, pickTextFile } from "./dom.js";
import { icons } from "./icons.js";
import { parseIntegers } from "./format.js";
import { memoryFile, memoryWrites } from "./memory-file.js";

// Elements of an open array shown at most (the rest: "…").
const MAX_ARRAY_ROWS = 256;
// Values in a folded array's summary.
const SUMMARY_VALUES = 8;

function parseValues(text) {
    const values = parseIntegers(text);
    if (values.length === 0) throw new Error("type a number");
    return values;
}

export class VariablesPanel {
    // `onSet(robot, name, index, values)` writes to the robot; `label(robot)`
    // names it; `messages` (messages.js) tells how an import went.
    constructor(container, { onSet, label, messages }) {
        this.onSet = onSet;
        this.label = label;
        this.messages = messages;
        this.robot = null;
        this.layoutKey = "";
        this.values = null;
        this.open = new Set(); // "robot/name" of open arrays
        this.cells = []; // {element, address, count} updated live
        this.filter = h("input", {
            type: "search",
            class: "panel-filter",
            placeholder: "Filter variables",
            label: "Filter variables by name",
            onInput: () => this.render(),
        });
        this.list = h("div", { class: "variables-list", attrs: { role: "tree", "aria-label": "Variables" } });
        this.note = h("div", { class: "panel-note" });
        const memoryButtons = [
            button({
                icon: icons.download,
                label: "Export the robot's memory: every variable's value, as a file",
                className: "icon-only memory-export",
                onClick: () => this.exportMemory(),
            }),
            button({
                icon: icons.open,
                label: "Import a memory file: write its variables to the robot",
                className: "icon-only memory-import",
                onClick: () => this.importMemory(),
            }),
        ];
        this.element = h(
            "div",
            { class: "variables-panel" },
            h("div", { class: "variables-tools" }, this.filter, memoryButtons),
            this.note,
            this.list,
        );
        container.append(this.element);
    }

    // Shows `robot` (the server's robot object); redraws only when its
    // variables changed.
    setRobot(robot) {
        const key = robot ? `${robot.robot}|${JSON.stringify(robot.variables ?? [])}` : "";
        const changedRobot = robot?.robot !== this.robot?.robot;
        this.robot = robot;
        if (changedRobot) this.values = null;
        this.note.textContent = !robot
            ? ""
            : !robot.present
              ? "The robot is offline: the values are the last read."
              : !robot.described
                ? "Waiting for the robot's description…"
                : this.values
                  ? ""
                  : "Reading the values…";
        if (key === this.layoutKey && !changedRobot) return;
        this.layoutKey = key;
        this.render();
    }

    exportMemory() {
        const robot = this.robot;
        if (!robot || !this.values) {
            this.messages.warning("No values to export yet: the robot's variables have not been read.");
            return;
        }
        const label = this.label(robot);
        download(
            `${label.replace(/[^\w.-]+/g, "-")}-memory.json`,
            memoryFile(robot, label, this.values),
            "application/json",
        );
    }

    async importMemory() {
        const robot = this.robot;
        if (!robot?.present) {
            this.messages.warning("The robot is not on the network: nothing to write to.");
            return;
        }
        const file = await pickTextFile(".json,application/json");
        if (!file) return;
        let plan;
        try {
            plan = memoryWrites(robot, file.text);
        } catch (error) {
            this.messages.error(`${file.name} not imported: ${error.message}.`);
            return;
        }
        let written = 0;
        for (const { name, values } of plan.writes) if (await this.onSet(robot.robot, name, 0, values)) written++;
        const left = plan.left.length
            ? [`not written (unknown here, or of another size): ${plan.left.join(", ")}`]
            : [];
        this.messages.success(`${written} variables of ${file.name} written to ${this.label(robot)}.`, left);
    }

    // A `variables` message for the robot shown.
    setValues(values) {
        const first = this.values === null;
        this.values = values;
        if (first && this.robot?.present) this.note.textContent = "";
        for (const cell of this.cells) this.updateCell(cell);
    }

    render() {
        this.cells = [];
        const variables = this.robot?.variables ?? [];
        const filter = this.filter.value.trim().toLowerCase();
        const shown = variables.filter((variable) => !filter || variable.name.toLowerCase().includes(filter));
        const groups = [
            {
                title: "Program",
                hint: "the variables the program declares",
                entries: shown.filter((variable) => variable.user),
            },
            {
                title: "Robot",
                hint: "sensors, actuators and settings of the robot",
                entries: shown.filter((variable) => !variable.user),
            },
        ];
        setChildren(
            this.list,
            groups
                .filter((group) => group.entries.length)
                .map((group) =>
                    h(
                        "section",
                        {
                            class: "variables-group",
                            attrs: { role: "group", "aria-label": `${group.title} variables` },
                        },
                        h("h3", { class: "group-title", title: group.hint, text: `${group.title} variables` }),
                        group.entries.map((variable) => this.variableRows(variable)),
                    ),
                ),
        );
        if (this.robot?.described && variables.length === 0) this.note.textContent = "This robot has no variables.";
    }

    variableRows(variable) {
        if (variable.size === 1) return this.row(variable, variable.name, 0, 1, 0);
        const key = `${this.robot.robot}/${variable.name}`;
        const isOpen = this.open.has(key);
        const toggle = h(
            "button",
            {
                type: "button",
                class: "array-toggle",
                label: `${isOpen ? "Fold" : "Open"} the array ${variable.name}`,
                attrs: { "aria-expanded": String(isOpen) },
                onClick: () => {
                    if (isOpen) this.open.delete(key);
                    else this.open.add(key);
                    this.render();
                },
            },
            iconElement(isOpen ? icons.collapse : icons.expand),
        );
        const rows = [this.row(variable, variable.name, 0, variable.size, 0, toggle)];
        if (isOpen) {
            const count = Math.min(variable.size, MAX_ARRAY_ROWS);
            for (let index = 0; index < count; index++) rows.push(this.row(variable, `[${index}]`, index, 1, 1));
            if (count < variable.size)
                rows.push(h("div", { class: "variable-row depth-1 more", text: `… ${variable.size - count} more` }));
        }
        return rows;
    }

    // One row: `count` words of `variable` from `index`.
    row(variable, label, index, count, depth, toggle = null) {
        const value = h("span", {
            class: "variable-value",
            tabIndex: 0,
            title:
                count > 1
                    ? "Click to write values from index 0, separated by commas"
                    : "Click to change; Enter writes it to the robot",
            attrs: {
                role: "textbox",
                "aria-label": `Value of ${variable.name}${count === 1 && variable.size > 1 ? `[${index}]` : ""}`,
            },
            dataset: { variable: variable.name, index: String(index) },
        });
        const cell = { element: value, address: variable.address + index, count, editing: false };
        value.addEventListener("click", () => this.edit(cell, variable, index, count));
        value.addEventListener("keydown", (event) => {
            if (event.key === "Enter" || event.key === "F2") {
                event.preventDefault();
                this.edit(cell, variable, index, count);
            }
        });
        this.cells.push(cell);
        this.updateCell(cell);
        return h(
            "div",
            { class: `variable-row depth-${depth}`, attrs: { role: "treeitem" }, dataset: { name: variable.name } },
            h(
                "span",
                { class: "variable-name" },
                toggle ?? h("span", { class: "array-toggle-space" }),
                h("span", {
                    text: label,
                    title: `${variable.name}: ${variable.size} word${variable.size > 1 ? "s" : ""} at address ${variable.address}`,
                }),
            ),
            h("span", { class: "variable-size", text: count > 1 ? `[${variable.size}]` : "" }),
            value,
        );
    }

    updateCell(cell) {
        if (cell.editing) return;
        const values = this.values;
        let text = "";
        if (values && cell.address + cell.count <= values.length) {
            if (cell.count === 1) text = String(values[cell.address]);
            else {
                const shown = values.slice(cell.address, cell.address + Math.min(cell.count, SUMMARY_VALUES));
                text = shown.join(", ") + (cell.count > SUMMARY_VALUES ? ", …" : "");
            }
        } else if (values) text = "?";
        if (cell.element.textContent !== text) cell.element.textContent = text;
    }

    edit(cell, variable, index, count) {
        if (cell.editing || !this.robot?.present) return;
        cell.editing = true;
        const current = this.values ? this.values.slice(cell.address, cell.address + count).join(", ") : "";
        const input = h("input", { class: "variable-input", value: current, label: `New value of ${variable.name}` });
        const finish = () => {
            cell.editing = false;
            input.replaceWith(cell.element);
            this.updateCell(cell);
        };
        input.addEventListener("keydown", async (event) => {
            if (event.key === "Escape") {
                event.preventDefault();
                finish();
                cell.element.focus();
            } else if (event.key === "Enter") {
                event.preventDefault();
                let values;
                try {
                    values = parseValues(input.value);
                } catch (error) {
                    input.setCustomValidity(error.message);
                    input.reportValidity();
                    return;
                }
                if (index + values.length > variable.size) {
                    input.setCustomValidity(
                        `${variable.name} has ${variable.size} word${variable.size > 1 ? "s" : ""}`,
                    );
                    input.reportValidity();
                    return;
                }
                // Shown at once; the next reading confirms it.
                if (this.values) for (let i = 0; i < values.length; i++) this.values[cell.address + i] = values[i];
                finish();
                cell.element.focus();
                await this.onSet(this.robot.robot, variable.name, index, values);
            }
        });
        input.addEventListener("input", () => input.setCustomValidity(""));
        input.addEventListener("blur", () => {
            if (cell.editing) finish();
        });
        cell.element.replaceWith(input);
        input.focus();
        input.select();
    }
}
