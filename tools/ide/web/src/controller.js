// The page's controller: routes the IDE server's messages
// (docs/ide-protocol.md) to the model, the robots' sessions and the views,
// keeps which robots the page watches, and selects the robot shown. main.js
// builds the page and hands it the parts.

import { loadSetting, saveSetting } from "./storage.js";

/**
 * @typedef {object} Views
 * @property {import("./robot-panel.js").RobotPanel} robotPanel
 * @property {import("./robot-tabs.js").RobotTabs} tabs
 * @property {import("./network-view.js").NetworkView} network
 * @property {import("./arena-view.js").ArenaView} arena
 * @property {import("./bottom-panel.js").BottomPanel} bottom
 * @property {import("./help-panel.js").HelpPanel} help
 */

export class Controller {
    /**
     * @param {object} parts
     * @param {import("./connection.js").Connection} parts.connection
     * @param {import("./model.js").Model} parts.model
     * @param {import("./sessions.js").Sessions} parts.sessions
     * @param {import("./commands.js").Commands} parts.commands
     * @param {import("./messages.js").MessageBar} parts.messages
     */
    constructor({ connection, model, sessions, commands, messages }) {
        this.connection = connection;
        this.model = model;
        this.sessions = sessions;
        this.commands = commands;
        this.messages = messages;
        /** @type {Views | null} */
        this.views = null;
        // The robots the server sends `variables` of, as "a,b,c".
        this.watched = "";
        // `hello` messages so far: a second one comes from a server that
        // restarted.
        this.hellos = 0;
        this.storageWarned = false;
    }

    // Takes the views, once built, and starts listening to the server.
    /** @param {Views} views */
    start(views) {
        this.views = views;
        views.bottom.plot.on("watch", () => this.updateWatch());
        this.route();
        this.sessions.on("error", (text) => this.messages.error(text));
        this.sessions.on("storage-full", () => {
            if (this.storageWarned) return;
            this.storageWarned = true;
            this.messages.warning(
                "This browser's storage is full: scripts are no longer kept in the browser, only on the server.",
            );
        });
        window.addEventListener("pagehide", () => this.sessions.persistAll());
        window.addEventListener("beforeunload", () => this.sessions.persistAll());
        this.connection.start();
    }

    // Shows robot `name` in every view.
    /** @param {string} name */
    select(name) {
        const { robotPanel, tabs, network, arena, help } = this.views;
        robotPanel.show(name);
        tabs.setActive(name);
        network.setActive(name);
        arena.setActive(name);
        help.robotChanged();
        saveSetting("active-robot", name);
        this.updateWatch();
    }

    // The robot shown and the robots plotted get `variables` messages.
    updateWatch(force = false) {
        const { robotPanel, bottom } = this.views;
        const robots = new Set(bottom.plot.watchedRobots());
        if (robotPanel.robotName && this.model.robots.get(robotPanel.robotName)?.present)
            robots.add(robotPanel.robotName);
        const list = [...robots].sort();
        const key = list.join(",");
        if ((key === this.watched && !force) || !this.connection.open) return;
        this.watched = key;
        this.connection.request({ type: "watch", robots: list }).catch(() => {
            this.watched = "";
        });
    }

    // The line where a robot stands in an event, in its editor. A robot
    // stopped outside any event (Stop, a run-time error, an event's end
    // stepped through) stands at no line.
    showExecution(robot) {
        const session = this.sessions.get(robot.robot);
        if (!session) return;
        const inEvent = robot.present && robot.state === "stepping";
        const line = inEvent ? (robot.line ?? 0) : 0;
        if (session.executionLine === line) return;
        session.executionLine = line;
        session.setExecutionLine(line);
    }

    // Some robot is shown: the one shown before, the one remembered, or the first.
    ensureSelection() {
        const { robotPanel } = this.views;
        if (robotPanel.robotName && this.model.robots.has(robotPanel.robotName)) return;
        const remembered = loadSetting("active-robot", null);
        const first = this.model.robots.has(remembered) ? remembered : this.model.sortedRobots()[0]?.robot;
        if (first) this.select(first);
    }

    // Each message of the server, to the parts it concerns.
    route() {
        const { connection, model, sessions, messages } = this;
        const { robotPanel, bottom } = this.views;
        connection.on("hello", (hello) => this.hello(hello));
        connection.on("links", (message) => model.applyLinks(message.links));
        connection.on("robot", ({ robot }) => {
            const previous = model.robots.get(robot.robot);
            model.applyRobot(robot);
            const session = sessions.ensure(robot.robot);
            const ready = sessions.canCompile(robot.robot);
            const wasReady = Boolean(previous && previous.present && previous.described && previous.compatible);
            if (ready && !wasReady) session.recompile();
            this.showExecution(robot);
            this.ensureSelection();
            this.updateWatch();
        });
        connection.on("script", (message) => sessions.applyScript(message.robot, message.source));
        connection.on("definitions", (message) => {
            model.applyDefinitions(message.definitions);
            sessions.recompileAll();
        });
        connection.on("project", (message) => {
            model.applyProject(message);
            sessions.applyProject(message);
        });
        connection.on("variables", (message) => {
            robotPanel.showValues(message);
            bottom.plot.addVariables(message);
        });
        connection.on("log", (message) => {
            bottom.monitor.add(message.entries);
            bottom.plot.addEvents(message.entries);
        });
        connection.on("runtime-error", (message) => {
            sessions.ensure(message.robot).setRuntimeError(message.error);
            const robot = model.robots.get(message.robot);
            if (robot) model.applyRobot({ ...robot, lastError: message.error });
        });
        connection.on("status", (message) => model.applyStatus(message));
        connection.on("arena", (message) => model.applyArena(message.arena));
        connection.on("arena-state", (message) => model.applyArenaState(message));
        connection.on("orphan-error", (error) => messages.error(`The IDE server refused a message: ${error}`));
        connection.on("state", (state) => {
            if (state !== "open") this.watched = "";
        });
    }

    // The server's greeting, at each (re)connection: robots, definitions,
    // project, event log.
    hello(hello) {
        const { model, sessions, commands } = this;
        const { robotPanel, bottom } = this.views;
        this.hellos++;
        // A server that restarted lost the definitions: this page gives them back.
        const ours = model.definitions;
        const theirs = hello.definitions ?? { events: [], constants: [] };
        const restarted =
            this.hellos > 1 &&
            theirs.events.length + theirs.constants.length === 0 &&
            ours.events.length + ours.constants.length > 0;
        if (restarted) hello = { ...hello, definitions: ours };
        model.applyHello(hello);
        if (restarted) commands.setDefinitions(ours);
        sessions.applyHello(hello);
        bottom.monitor.reset(hello.log ?? []);
        for (const robot of model.robots.values()) this.showExecution(robot);
        this.ensureSelection();
        robotPanel.renderRobot();
        this.updateWatch(true);
    }
}
