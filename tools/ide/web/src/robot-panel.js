// The robot tab's content: its debug toolbar and execution state, the
// script editor, the compile result and memory use under it, and beside it
// the Variables, Local events and Native functions panels. One panel serves
// every robot: switching tabs swaps the robot it shows.

import { EditorView } from "@codemirror/view";
import { openSearchPanel, gotoLine } from "@codemirror/search";
import { h, button, setChildren } from "./dom.js";
import { icons } from "./icons.js";
import { robotState, STATE_TEXT } from "./model.js";
import { tokenRange, clearBreakpoints } from "./editor.js";
import { VariablesPanel } from "./variables-panel.js";
import { RobotInfoPanel } from "./robot-info.js";
import { CameraStrip } from "./camera-strip.js";

const ROBOT_ACTIONS = [
    {
        action: "load",
        icon: icons.load,
        text: "Load",
        label: "Load: compile this script and load it into the robot, then run",
    },
    { action: "run", icon: icons.run, text: "Run", label: "Run" },
    { action: "pause", icon: icons.pause, text: "Pause", label: "Pause" },
    { action: "step", icon: icons.step, text: "Step", label: "Step: run to the next line" },
    { action: "stop", icon: icons.stop, text: "Stop", label: "Stop" },
    { action: "reset", icon: icons.reset, text: "Reset", label: "Reset: restart the program from its start" },
    { separator: true },
    {
        action: "store",
        icon: icons.store,
        text: "Store",
        label: "Store in flash: the robot keeps this program after a reboot",
    },
    { action: "reboot", icon: icons.reboot, text: "Reboot", label: "Reboot the robot" },
    { separator: true },
    { action: "binary", icon: icons.binary, text: ".abo", label: "Save the binary code (.abo file)" },
    { action: "copy", icon: icons.copy, text: "To all", label: "Copy this script to every robot's editor" },
];

function meter(label, used, total) {
    const ratio = total > 0 ? Math.min(1, used / total) : 0;
    const level = ratio > 0.9 ? "high" : ratio > 0.7 ? "medium" : "low";
    return h(
        "span",
        { class: `meter meter-${level}`, title: `${label}: ${used} of ${total} words used` },
        h(
            "span",
            { class: "meter-bar" },
            h("span", { class: "meter-fill", style: { width: `${(ratio * 100).toFixed(1)}%` } }),
        ),
    );
}

export class RobotPanel {
    constructor(container, { model, sessions, commands }) {
        this.model = model;
        this.sessions = sessions;
        this.commands = commands;
        this.session = null;
        this.robotName = null;

        this.stateBadge = h("span", {
            class: "state-badge",
            attrs: { role: "status" },
            dataset: { testid: "robot-state" },
        });
        this.title = h("span", { class: "robot-title" });
        this.actionButtons = {};
        const toolbarItems = ROBOT_ACTIONS.map((entry) => {
            if (entry.separator) return h("span", { class: "toolbar-separator" });
            const element = button({
                icon: entry.icon,
                text: entry.text,
                label: entry.label,
                className: `robot-${entry.action}`,
                onClick: () => this.act(entry.action),
            });
            this.actionButtons[entry.action] = element;
            return element;
        });
        const editorTools = [
            button({
                icon: icons.find,
                label: "Find and replace (Ctrl+F)",
                className: "icon-only",
                onClick: () => this.withView(openSearchPanel),
            }),
            button({
                icon: icons.gotoLine,
                label: "Go to line (Ctrl+Alt+G)",
                className: "icon-only",
                onClick: () => this.withView(gotoLine),
            }),
            button({
                icon: icons.breakpointsOff,
                label: "Clear all breakpoints of this script",
                className: "icon-only clear-breakpoints",
                onClick: () =>
                    this.withView((view) => {
                        if (clearBreakpoints(view)) this.session?.sendBreakpoints();
                    }),
            }),
        ];
        this.toolbar = h(
            "div",
            { class: "robot-toolbar", attrs: { role: "toolbar", "aria-label": "This robot" } },
            this.title,
            this.stateBadge,
            h("div", { class: "toolbar" }, toolbarItems),
            h("div", { class: "toolbar editor-tools" }, editorTools),
        );

        this.editorHost = h("div", { class: "editor-host" });
        this.compileStatus = h("div", {
            class: "compile-status",
            attrs: { role: "status", "aria-live": "polite" },
            dataset: { testid: "compile-status" },
        });
        this.programStatus = h("div", { class: "program-status" });
        this.runtimeStatus = h("div", { class: "runtime-status", attrs: { role: "alert" } });
        const statusBar = h(
            "div",
            { class: "editor-status" },
            this.compileStatus,
            this.runtimeStatus,
            this.programStatus,
        );

        const cameraHost = h("div", { class: "camera-host" });
        this.camera = new CameraStrip(cameraHost);
        const sideTabs = h("div", { class: "side-tabs", attrs: { role: "tablist", "aria-label": "Robot details" } });
        const sideBody = h("div", { class: "side-body" });
        this.variables = new VariablesPanel(sideBody, {
            onSet: (robot, name, index, values) => commands.setVariable(robot, name, index, values),
            label: (robot) => model.label(robot),
            messages: commands.messages,
        });
        this.events = new RobotInfoPanel(sideBody, "events");
        this.natives = new RobotInfoPanel(sideBody, "natives");
        this.sidePanes = {
            variables: this.variables.element,
            events: this.events.element,
            natives: this.natives.element,
        };
        this.sideTabButtons = Object.entries({
            variables: ["Variables", "Variables"],
            events: ["Events", "Local events"],
            natives: ["Functions", "Native functions"],
        }).map(([key, [text, label]]) =>
            h("button", {
                type: "button",
                class: "side-tab",
                text,
                label,
                attrs: { role: "tab" },
                dataset: { pane: key },
                onClick: () => this.showSide(key),
            }),
        );
        sideTabs.append(...this.sideTabButtons);
        this.showSide("variables");

        this.placeholder = h(
            "div",
            { class: "robot-placeholder" },
            h("h2", { text: "No robot yet" }),
            h("p", {
                text: "Robots appear here as they join the Aseba network; each gets a tab with its script, its variables and its debugger.",
            }),
        );
        this.content = h(
            "div",
            { class: "robot-content" },
            this.toolbar,
            h(
                "div",
                { class: "robot-body" },
                h("div", { class: "editor-column" }, this.editorHost, statusBar),
                h("aside", { class: "side-panel" }, cameraHost, sideTabs, sideBody),
            ),
        );
        this.element = h(
            "section",
            { class: "robot-panel", attrs: { role: "tabpanel" } },
            this.placeholder,
            this.content,
        );
        container.append(this.element);

        this.view = new EditorView({ parent: this.editorHost });

        model.on("robot", (robot) => {
            if (robot.robot === this.robotName) this.renderRobot();
        });
        model.on("definitions", () => this.renderStatus());
        sessions.on("status", (session) => {
            if (session === this.session) this.renderStatus();
        });
        this.show(null);
    }

    withView(command) {
        if (!this.session) return;
        command(this.view);
        this.view.focus();
    }

    showSide(key) {
        for (const [name, pane] of Object.entries(this.sidePanes)) pane.hidden = name !== key;
        for (const tab of this.sideTabButtons) tab.setAttribute("aria-selected", String(tab.dataset.pane === key));
    }

    // Shows robot `name` (or nothing).
    show(name) {
        if (this.session && this.session.name === name) return;
        if (this.session) this.session.detach();
        this.robotName = name;
        this.session = name ? this.sessions.ensure(name) : null;
        this.placeholder.hidden = Boolean(this.session);
        this.content.hidden = !this.session;
        if (this.session) {
            this.session.attach(this.view);
            this.element.setAttribute("aria-label", `Robot ${this.model.label(name)}`);
        }
        this.renderRobot();
        this.renderStatus();
    }

    act(action) {
        const name = this.robotName;
        if (!name) return;
        if (action === "load") this.commands.load([name]);
        else if (action === "binary") this.commands.saveBinary(name);
        else if (action === "copy") this.commands.copyToAll(name);
        else this.commands.control([name], action);
    }

    // A `variables` message.
    showValues(message) {
        if (message.robot !== this.robotName) return;
        this.variables.setValues(message.values);
        this.camera.setValues(message.values);
    }

    renderRobot() {
        const robot = this.robotName ? this.model.robots.get(this.robotName) : null;
        if (!robot) {
            this.variables.setRobot(null);
            this.camera.setRobot(null);
            this.events.setRobot(null);
            this.natives.setRobot(null);
            return;
        }
        const state = robotState(robot);
        this.title.textContent = this.model.label(robot);
        this.stateBadge.className = `state-badge state-${state}`;
        this.stateBadge.dataset.state = state;
        this.stateBadge.textContent = STATE_TEXT[state] ?? state;
        this.stateBadge.title = robot.line > 0 && state !== "running" ? `at line ${robot.line}` : "";
        const ready = robot.present && robot.described && robot.compatible;
        for (const [action, element] of Object.entries(this.actionButtons))
            element.disabled = !ready && action !== "copy";
        this.element.classList.toggle("offline", !robot.present);
        this.variables.setRobot(robot);
        this.camera.setRobot(robot);
        this.events.setRobot(robot);
        this.natives.setRobot(robot);
        this.renderStatus();
    }

    renderStatus() {
        const session = this.session;
        if (!session) return;
        const robot = this.model.robots.get(session.name);
        const status = session.status;
        const children = [];
        if (status.kind === "ok") {
            const [bytecodeUsed, bytecodeTotal] = status.memory.bytecode;
            const [variablesUsed, variablesTotal] = status.memory.variables;
            children.push(h("span", { class: "status-icon ok", text: "✓", attrs: { "aria-hidden": "true" } }));
            children.push(h("span", { class: "status-text", text: "Compiles" }));
            children.push(h("span", { class: "memory-text", text: status.text }));
            children.push(meter("bytecode", bytecodeUsed, bytecodeTotal));
            children.push(meter("variables", variablesUsed, variablesTotal));
        } else if (status.kind === "error" || status.kind === "refused") {
            children.push(h("span", { class: "status-icon error", text: "✗", attrs: { "aria-hidden": "true" } }));
            const place = status.error?.line > 0 ? status.error : null;
            children.push(
                place
                    ? h("button", {
                          type: "button",
                          class: "status-text error-text go-to-error",
                          text: status.text,
                          title: "Go to the error",
                          onClick: () => this.goTo(place),
                      })
                    : h("span", { class: "status-text error-text", text: status.text }),
            );
        } else if (robot && !robot.present) {
            children.push(
                h("span", {
                    class: "status-text muted",
                    text: "The robot is offline: your text is kept, and compiled when it comes back.",
                }),
            );
        } else {
            children.push(h("span", { class: "status-text muted", text: "Compiling…" }));
        }
        this.compileStatus.dataset.kind = status.kind;
        setChildren(this.compileStatus, children);

        const error = session.runtimeError;
        this.runtimeStatus.hidden = !error;
        if (error) {
            setChildren(
                this.runtimeStatus,
                h("span", { class: "status-icon error", text: "!", attrs: { "aria-hidden": "true" } }),
                h("span", {
                    text: `Run-time error${error.line > 0 ? ` at line ${error.line}` : ""}: ${error.message}`,
                }),
                h("button", {
                    type: "button",
                    class: "link-button",
                    text: "Dismiss",
                    onClick: () => session.setRuntimeError(null),
                }),
            );
        }

        let program = "";
        if (robot?.program) {
            program = robot.program.source === session.text() ? "loaded" : "edited since loaded";
            if (robot.program.stored) program += ", stored in flash";
        }
        this.programStatus.textContent = program;
    }

    // Puts the cursor on the token at {line, column} and shows it.
    goTo({ line, column }) {
        const { from, to } = tokenRange(this.view.state.doc, line, column);
        this.view.dispatch({
            selection: { anchor: from, head: to },
            effects: EditorView.scrollIntoView(from, { y: "center" }),
        });
        this.view.focus();
    }

    completionNames() {
        const robot = this.robotName ? this.model.robots.get(this.robotName) : null;
        const description = robot?.description;
        const definitions = this.model.definitions;
        return {
            variables: (robot?.variables ?? []).map((variable) => variable.name),
            natives: (description?.natives ?? []).map((native) => ({ name: native.name, info: native.description })),
            events: [
                ...(description?.localEvents ?? []).map((event) => event.name),
                ...definitions.events.map((event) => event.name),
            ],
            constants: definitions.constants.map((constant) => constant.name),
        };
    }
}
