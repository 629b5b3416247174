// The page's entry point: builds the layout, connects to the IDE server and
// routes its messages (docs/ide-protocol.md) to the model and the views.

import "./style.css";
import "./panels.css";
import { h } from "./dom.js";
import { Connection } from "./connection.js";
import { Model } from "./model.js";
import { Sessions } from "./sessions.js";
import { Commands } from "./commands.js";
import { editorExtensions } from "./editor.js";
import { MessageBar } from "./messages.js";
import { TopBar } from "./topbar.js";
import { NetworkView } from "./network-view.js";
import { ArenaView } from "./arena-view.js";
import { RobotTabs } from "./robot-tabs.js";
import { RobotPanel } from "./robot-panel.js";
import { BottomPanel } from "./bottom-panel.js";
import { splitter } from "./layout.js";
import { loadSetting, saveSetting } from "./storage.js";

const root = document.getElementById("app");
const scheme = location.protocol === "https:" ? "wss" : "ws";
const connection = new Connection(`${scheme}://${location.host}/ws`);
const model = new Model();

let robotPanel = null;
const extensions = editorExtensions({
    onChange: () => robotPanel?.session?.changed(),
    onBreakpointsChanged: () => robotPanel?.session?.sendBreakpoints(),
    namesOf: () => robotPanel.completionNames(),
});
const sessions = new Sessions({ connection, model, extensions });

// --- layout --------------------------------------------------------------------

const topArea = h("div", { class: "top-area" });
root.append(topArea);
const messages = new MessageBar(root);
const commands = new Commands({ connection, model, sessions, messages });
new TopBar(topArea, { connection, model, commands });

const sidebar = h("aside", { class: "sidebar", attrs: { "aria-label": "Network and arena" } });
const main = h("main", { class: "main-area" });
const editorArea = h("div", { class: "editor-area" });
const bottomArea = h("div", { class: "bottom-area" });
main.append(editorArea);
root.append(
    h(
        "div",
        { class: "workbench" },
        sidebar,
        splitter({
            target: sidebar,
            axis: "x",
            min: 200,
            max: () => window.innerWidth * 0.45,
            setting: "sidebar-width",
            initial: 300,
            label: "Resize the side panel",
        }),
        main,
    ),
);

const select = (name) => {
    robotPanel.show(name);
    tabs.setActive(name);
    network.setActive(name);
    arena.setActive(name);
    saveSetting("active-robot", name);
    updateWatch();
};

const network = new NetworkView(sidebar, { model, onSelect: select });
const arena = new ArenaView(sidebar, { model, onSelect: select });
const tabs = new RobotTabs(editorArea, { model, sessions, onSelect: select });
robotPanel = new RobotPanel(editorArea, { model, sessions, commands });
main.append(
    splitter({
        target: bottomArea,
        axis: "y",
        direction: -1,
        min: 120,
        max: () => window.innerHeight * 0.7,
        setting: "bottom-height",
        initial: Math.round(Math.min(300, Math.max(180, window.innerHeight * 0.3))),
        label: "Resize the bottom panel",
    }),
    bottomArea,
);
const bottom = new BottomPanel(bottomArea, { model, commands, messages });

// --- what the page watches --------------------------------------------------------

let watched = "";
// The robot shown and the robots plotted get `variables` messages.
function updateWatch(force = false) {
    const robots = new Set(bottom.plot.watchedRobots());
    if (robotPanel.robotName && model.robots.get(robotPanel.robotName)?.present) robots.add(robotPanel.robotName);
    const list = [...robots].sort();
    const key = list.join(",");
    if ((key === watched && !force) || !connection.open) return;
    watched = key;
    connection.request({ type: "watch", robots: list }).catch(() => {
        watched = "";
    });
}
bottom.plot.on("watch", () => updateWatch());

// The line where a robot stands, in its editor.
function showExecution(robot) {
    const session = sessions.get(robot.robot);
    if (!session) return;
    const stopped = robot.present && (robot.state === "stepping" || robot.state === "stopped");
    const line = stopped ? (robot.line ?? 0) : 0;
    if (session.executionLine === line) return;
    session.executionLine = line;
    session.setExecutionLine(line);
}

function ensureSelection() {
    if (robotPanel.robotName && model.robots.has(robotPanel.robotName)) return;
    const remembered = loadSetting("active-robot", null);
    const first = model.robots.has(remembered) ? remembered : model.sortedRobots()[0]?.robot;
    if (first) select(first);
}

// --- the server's messages ---------------------------------------------------------

let hellos = 0;
connection.on("hello", (hello) => {
    hellos++;
    // A server that restarted lost the definitions: this page gives them back.
    const ours = model.definitions;
    const theirs = hello.definitions ?? { events: [], constants: [] };
    const restarted =
        hellos > 1 &&
        theirs.events.length + theirs.constants.length === 0 &&
        ours.events.length + ours.constants.length > 0;
    if (restarted) hello = { ...hello, definitions: ours };
    model.applyHello(hello);
    if (restarted) commands.setDefinitions(ours);
    sessions.applyHello(hello);
    bottom.monitor.reset(hello.log ?? []);
    for (const robot of model.robots.values()) showExecution(robot);
    ensureSelection();
    robotPanel.renderRobot();
    updateWatch(true);
});
connection.on("links", (message) => model.applyLinks(message.links));
connection.on("robot", ({ robot }) => {
    const previous = model.robots.get(robot.robot);
    model.applyRobot(robot);
    const session = sessions.ensure(robot.robot);
    const ready = sessions.canCompile(robot.robot);
    const wasReady = Boolean(previous && previous.present && previous.described && previous.compatible);
    if (ready && !wasReady) session.recompile();
    showExecution(robot);
    ensureSelection();
    updateWatch();
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
    if (state !== "open") watched = "";
});

sessions.on("error", (text) => messages.error(text));
let storageWarned = false;
sessions.on("storage-full", () => {
    if (storageWarned) return;
    storageWarned = true;
    messages.warning("This browser's storage is full: scripts are no longer kept in the browser, only on the server.");
});

window.addEventListener("pagehide", () => sessions.persistAll());
window.addEventListener("beforeunload", () => sessions.persistAll());

// For tests and the curious: the page's state, read-only by convention.
window.asebaIde = { connection, model, sessions, commands, robotPanel, bottom };

connection.start();
