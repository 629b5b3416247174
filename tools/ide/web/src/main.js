// The page's entry point: builds the layout and its parts, and hands them to
// the controller (controller.js), which routes the IDE server's messages
// (docs/ide-protocol.md) to them.

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
import { Controller } from "./controller.js";
import { HelpPanel } from "./help-panel.js";
import { installKeys } from "./keys.js";

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
const controller = new Controller({ connection, model, sessions, commands, messages });
const help = new HelpPanel(root, { model, robotShown: () => robotPanel?.robotName ?? null });
new TopBar(topArea, { connection, model, commands, help });
installKeys({ commands, help });

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

const select = (name) => controller.select(name);

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
        // Room for the plot (or the monitor) and the editor both.
        initial: Math.round(Math.min(420, Math.max(260, window.innerHeight * 0.38))),
        label: "Resize the bottom panel",
    }),
    bottomArea,
);
const bottom = new BottomPanel(bottomArea, { model, commands, messages });
// The message bar stays above the bottom panel, whatever its height.
new ResizeObserver(() =>
    document.documentElement.style.setProperty("--bottom-area-height", `${bottomArea.offsetHeight}px`),
).observe(bottomArea);

// For the browser tests, which open the page as /?test
// (tests/ide/harness.mjs): the page's parts, read-only by convention.
if (new URLSearchParams(location.search).has("test"))
    window.asebaIde = { connection, model, sessions, commands, robotPanel, bottom, controller, help };

// The server's messages, to the parts of the page.
controller.start({ robotPanel, tabs, network, arena, bottom, help });
