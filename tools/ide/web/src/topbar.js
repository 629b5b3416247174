// The top bar: the project's buttons, the toolbar of the whole group, and
// the state of the page's connection and of each Aseba network.

import { h, button, setChildren } from "./dom.js";
import { icons } from "./icons.js";
import { loadRecentProjects } from "./storage.js";

const GROUP_ACTIONS = [
    {
        action: "load",
        icon: icons.load,
        text: "Load all",
        label: "Load all (F7): compile every robot's script and load it, then run",
    },
    { action: "run", icon: icons.run, text: "Run all", label: "Run all robots (F9)" },
    { action: "pause", icon: icons.pause, text: "Pause all", label: "Pause all robots (F10)" },
    { action: "stop", icon: icons.stop, text: "Stop all", label: "Stop all robots" },
    {
        action: "reset",
        icon: icons.reset,
        text: "Reset all",
        label: "Reset all robots (F8): restart their programs from the start",
    },
    {
        action: "store",
        icon: icons.store,
        text: "Store all",
        label: "Store all in flash: each robot keeps its program after a reboot",
    },
    { action: "reboot", icon: icons.reboot, text: "Reboot all", label: "Reboot all robots" },
];

export class TopBar {
    constructor(container, { connection, model, commands, help }) {
        this.connection = connection;
        this.model = model;
        this.commands = commands;
        this.pageState = h("div", {
            class: "connection-state",
            attrs: { role: "status" },
            dataset: { testid: "page-connection" },
        });
        this.linkStates = h("div", { class: "link-states" });
        this.projectName = h("span", { class: "project-name" });

        this.groupButtons = GROUP_ACTIONS.map((entry) =>
            button({
                icon: entry.icon,
                text: entry.text,
                label: entry.label,
                className: `group-${entry.action}`,
                onClick: () =>
                    entry.action === "load"
                        ? commands.load(commands.readyNames())
                        : commands.control(commands.readyNames(), entry.action),
            }),
        );
        const element = h(
            "header",
            { class: "topbar" },
            h(
                "div",
                { class: "brand" },
                h("span", { class: "brand-mark", text: "A" }),
                h("span", { class: "brand-name", text: "Aseba IDE" }),
                this.projectName,
            ),
            h(
                "div",
                { class: "toolbar project-toolbar", attrs: { role: "toolbar", "aria-label": "Project" } },
                button({
                    icon: icons.add,
                    text: "New",
                    label: "New project: empty scripts, no events, no constants (click twice)",
                    onClick: () => commands.newProject(),
                }),
                button({
                    icon: icons.open,
                    text: "Open",
                    label: "Open project: an .aesl file from this computer",
                    onClick: () => commands.openProject(),
                }),
                h(
                    "div",
                    { class: "recent-projects" },
                    (this.recentButton = button({
                        icon: icons.collapse,
                        label: "Open a recent project: one opened before from this browser",
                        className: "icon-only recent-button",
                        onClick: () => this.toggleRecent(),
                    })),
                    (this.recentMenu = h("div", {
                        class: "recent-menu",
                        attrs: { role: "menu", "aria-label": "Recent projects" },
                        hidden: true,
                    })),
                ),
                button({
                    icon: icons.save,
                    text: "Save",
                    label: "Save the project",
                    onClick: () => commands.saveProject(),
                }),
                button({
                    icon: icons.download,
                    text: ".aesl",
                    label: "Download the project as an .aesl file",
                    onClick: () => commands.downloadProject(),
                }),
            ),
            h(
                "div",
                { class: "toolbar group-toolbar", attrs: { role: "toolbar", "aria-label": "Whole group" } },
                this.groupButtons,
            ),
            h(
                "div",
                { class: "topbar-status" },
                this.linkStates,
                this.pageState,
                button({
                    icon: icons.help,
                    text: "Help",
                    label: "Help (F1): the keys, the language, this robot's variables, events and functions",
                    className: "help-button",
                    onClick: () => help.toggle(),
                }),
            ),
        );
        container.append(element);
        this.saveButton = element.querySelector('[aria-label="Save the project"]');

        connection.on("state", () => this.renderPage());
        model.on("links", () => this.renderLinks());
        model.on("project", () => this.renderProject());
        model.on("robots", () => this.renderGroup());
        model.on("robot", () => this.renderGroup());
        this.renderPage();
        this.renderProject();
        this.renderGroup();
        // The countdown to the next attempt.
        setInterval(() => {
            if (connection.state === "waiting") this.renderPage();
        }, 500);
    }

    renderPage() {
        const { state } = this.connection;
        let text;
        if (state === "open") text = "Connected";
        else if (state === "connecting") text = "Connecting…";
        else {
            const seconds = Math.max(0, Math.ceil((this.connection.retryAt - Date.now()) / 1000));
            text = `Disconnected, retrying${seconds > 0 ? ` in ${seconds} s` : "…"}`;
        }
        this.pageState.className = `connection-state state-${state}`;
        this.pageState.dataset.state = state;
        this.pageState.title =
            state === "open"
                ? "The page is connected to the IDE server"
                : `The page lost the IDE server (${this.connection.lastClose || "no answer"}); your texts are kept`;
        setChildren(
            this.pageState,
            h("span", { class: "dot" }),
            h("span", {}, h("span", { class: "connection-prefix", text: "Server: " }), text),
            state === "waiting"
                ? h("button", {
                      type: "button",
                      class: "link-button",
                      text: "Retry now",
                      onClick: () => this.connection.retryNow(),
                  })
                : null,
        );
        // Links are the server's to tell: unknown while it is away.
        if (state !== "open") this.renderLinks();
    }

    // The projects opened before from this browser, newest first.
    toggleRecent() {
        if (!this.recentMenu.hidden) {
            this.recentMenu.hidden = true;
            return;
        }
        const entries = loadRecentProjects();
        setChildren(
            this.recentMenu,
            entries.length === 0
                ? h("div", { class: "recent-empty", text: "No project opened from this browser yet." })
                : null,
            entries.map((entry) =>
                h("button", {
                    type: "button",
                    class: "recent-entry",
                    attrs: { role: "menuitem" },
                    text: entry.name,
                    title: `Opened ${new Date(entry.time).toLocaleString()}`,
                    onClick: () => {
                        this.recentMenu.hidden = true;
                        this.commands.openRecentProject(entry);
                    },
                }),
            ),
        );
        this.recentMenu.hidden = false;
        const close = (event) => {
            if (this.recentMenu.parentElement.contains(event.target)) return;
            this.recentMenu.hidden = true;
            document.removeEventListener("pointerdown", close, true);
        };
        document.addEventListener("pointerdown", close, true);
    }

    // The group's buttons act on the robots there: none, nothing to do.
    renderGroup() {
        const none = this.model.readyRobots().length === 0;
        for (const element of this.groupButtons) {
            element.disabled = none;
            element.title = none
                ? `${element.getAttribute("aria-label")} (no robot on the network)`
                : element.getAttribute("aria-label");
        }
    }

    // Each network's state in a few words; why one is down is said in full
    // in the network view (network-view.js), where it has room.
    renderLinks() {
        const open = this.connection.open;
        setChildren(
            this.linkStates,
            this.model.links.map((link) =>
                h(
                    "span",
                    {
                        class: `link-state ${!open ? "link-unknown" : link.up ? "link-up" : "link-down"}`,
                        title: !open
                            ? `${link.target}: unknown while the server is away`
                            : link.up
                              ? `${link.target}: connected`
                              : `${link.target}: ${link.error || "down"}`,
                        dataset: { target: link.target, up: String(open && link.up) },
                    },
                    h("span", { class: "dot" }),
                    h("span", { class: "link-target", text: link.target }),
                    open && !link.up ? h("span", { class: "link-error", text: "unreachable" }) : null,
                ),
            ),
        );
    }

    renderProject() {
        const file = this.model.projectFile;
        this.projectName.textContent = file ? file.split(/[\\/]/).pop() : "";
        this.projectName.title = file ? `Project file on the server: ${file}` : "";
        this.saveButton.title = file
            ? `Save the project to ${file} on the server`
            : "Save the project (downloads an .aesl file: the server has no project file)";
    }
}
