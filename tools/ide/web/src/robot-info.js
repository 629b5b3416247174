// What a robot offers a program, from its description: its local events and
// its native functions with their documentation.

import { h, setChildren } from "./dom.js";

// "math.fill(dest[<1>], value)", as the console writes it: a parameter's
// size > 0 is fixed, < 0 a template shared by the parameters with the same
// number, 0 any.
export function nativeSignature(native) {
    const parameters = native.parameters.map((parameter) => {
        if (parameter.size === 1) return parameter.name;
        if (parameter.size > 1) return `${parameter.name}[${parameter.size}]`;
        if (parameter.size < 0) return `${parameter.name}[<${-parameter.size}>]`;
        return `${parameter.name}[]`;
    });
    return `${native.name}(${parameters.join(", ")})`;
}

export class RobotInfoPanel {
    constructor(container, kind) {
        this.kind = kind; // "events" or "natives"
        this.key = "";
        this.filter = h("input", {
            type: "search",
            class: "panel-filter",
            placeholder: kind === "natives" ? "Filter native functions" : "Filter local events",
            label: kind === "natives" ? "Filter native functions" : "Filter local events",
            onInput: () => this.render(),
        });
        this.list = h("dl", { class: "info-list" });
        this.element = h("div", { class: `info-panel info-${kind}` }, this.filter, this.list);
        container.append(this.element);
        this.description = null;
    }

    setRobot(robot) {
        const description = robot?.description ?? null;
        const key = description
            ? `${robot.robot}|${description.name}|${description.natives.length}|${description.localEvents.length}`
            : "";
        if (key === this.key) return;
        this.key = key;
        this.description = description;
        this.render();
    }

    render() {
        if (!this.description) {
            setChildren(
                this.list,
                h("div", { class: "panel-note", text: "Known once the robot has described itself." }),
            );
            return;
        }
        const filter = this.filter.value.trim().toLowerCase();
        const entries =
            this.kind === "natives"
                ? this.description.natives.map((native) => ({
                      name: native.name,
                      title: nativeSignature(native),
                      text: native.description,
                  }))
                : this.description.localEvents.map((event) => ({
                      name: event.name,
                      title: event.name,
                      text: event.description,
                  }));
        const shown = entries.filter(
            (entry) =>
                !filter || entry.name.toLowerCase().includes(filter) || entry.text.toLowerCase().includes(filter),
        );
        setChildren(
            this.list,
            shown.length === 0
                ? h("div", {
                      class: "panel-note",
                      text: entries.length
                          ? "Nothing matches."
                          : this.kind === "natives"
                            ? "No native functions."
                            : "No local events.",
                  })
                : null,
            shown.map((entry) => [
                h("dt", { class: "info-name", text: entry.title }),
                h("dd", { class: "info-text", text: entry.text || "(no description)" }),
            ]),
        );
    }
}
