// What the buttons do: load, execution control, flash, projects and binary
// files, for one robot or the whole group. Each command tells the user its
// outcome in the message bar, robot by robot when some failed.

import { download, pickTextFile } from "./dom.js";
import { compileErrorText, MAX_SCRIPT_BYTES } from "./sessions.js";
import { rememberProject } from "./storage.js";

// What New project opens: no events, no constants, no programs.
const EMPTY_PROJECT = "<!DOCTYPE aesl-source>\n<network>\n</network>\n";
// New project empties every script: a second click within this time does it.
const NEW_PROJECT_CONFIRM_MS = 6000;

// The server refuses larger projects (docs/ide-protocol.md).
const MAX_PROJECT_BYTES = 2 * 1024 * 1024;

export const ACTION_TEXT = {
    run: "Run",
    pause: "Pause",
    step: "Step",
    stop: "Stop",
    reset: "Reset",
    store: "Store in flash",
    reboot: "Reboot",
};

// Actions whose success is worth a message (the others show in the states).
const REPORTED_ACTIONS = new Set(["store", "reboot"]);

function plural(count, word) {
    return `${count} ${word}${count === 1 ? "" : "s"}`;
}

export class Commands {
    constructor({ connection, model, sessions, messages }) {
        this.connection = connection;
        this.model = model;
        this.sessions = sessions;
        this.messages = messages;
        // When New project was first clicked (0: not lately).
        this.newProjectAsked = 0;
    }

    readyNames() {
        return this.model.readyRobots().map((robot) => robot.robot);
    }

    // Compiles and loads each robot's script; runs them unless run is false.
    async load(names, { run = true } = {}) {
        if (names.length === 0) {
            this.messages.warning("No robot can take a program now: none is on the network and described.");
            return false;
        }
        const programs = names.map((name) => {
            const session = this.sessions.ensure(name);
            return { robot: name, source: session.text(), breakpoints: session.breakpointLines() };
        });
        const tooLong = programs.filter(
            (program) => new TextEncoder().encode(program.source).length > MAX_SCRIPT_BYTES,
        );
        if (tooLong.length) {
            this.messages.error(
                "Nothing was loaded: a script is too long.",
                tooLong.map((program) => `${this.model.label(program.robot)}: over ${MAX_SCRIPT_BYTES / 1024} KB`),
            );
            return false;
        }
        try {
            const reply = await this.connection.request({ type: "load", programs, run });
            this.loaded(programs, reply.results);
            const what = names.length === 1 ? this.model.label(names[0]) : plural(names.length, "robot");
            this.messages.success(`Loaded on ${what}${run ? ", running" : ""}.`);
            return true;
        } catch (error) {
            const reply = error.reply ?? {};
            if (reply.failures) {
                for (const failure of reply.failures) this.sessions.get(failure.robot)?.showLoadFailure(failure);
                this.messages.error(
                    "Nothing was loaded: a program does not compile.",
                    reply.failures.map(
                        (failure) => `${this.model.label(failure.robot)}: ${compileErrorText(failure.error)}`,
                    ),
                );
            } else if (reply.results) {
                this.loaded(programs, reply.results);
                this.reportFailures("Load", reply.results);
            } else {
                this.messages.error(`Load failed: ${error.message}`);
            }
            return false;
        }
    }

    loaded(programs, results) {
        for (const result of results ?? []) {
            if (!result.ok) continue;
            const session = this.sessions.get(result.robot);
            if (!session) continue;
            session.setRuntimeError(null);
            if (result.breakpoints) session.showBreakpointResults(result.breakpoints);
            const program = programs.find((entry) => entry.robot === result.robot);
            if (program) session.acknowledged(program.source, false);
        }
    }

    // Puts robot `name`'s script in every other robot's editor: a swarm
    // usually runs one program.
    copyToAll(name) {
        const text = this.sessions.ensure(name).text();
        const others = this.model.sortedRobots().filter((robot) => robot.robot !== name);
        for (const robot of others) this.sessions.ensure(robot.robot).setText(text);
        this.messages.success(
            `The script of ${this.model.label(name)} is now in the editors of ${plural(others.length, "robot")} (Ctrl+Z in an editor takes it back).`,
        );
    }

    // `action` on each robot of `names`: run, pause, step, stop, reset,
    // store or reboot.
    async control(names, action) {
        if (names.length === 0) {
            this.messages.warning(`${ACTION_TEXT[action]}: no robot is on the network.`);
            return false;
        }
        if (action === "reset" || action === "reboot")
            for (const name of names) this.sessions.get(name)?.setRuntimeError(null);
        try {
            await this.connection.request({ type: "control", robots: names, action });
            if (REPORTED_ACTIONS.has(action)) {
                const what = names.length === 1 ? this.model.label(names[0]) : plural(names.length, "robot");
                this.messages.success(
                    action === "store" ? `Program written to the flash of ${what}.` : `Rebooting ${what}.`,
                );
            }
            return true;
        } catch (error) {
            if (error.reply?.results) this.reportFailures(ACTION_TEXT[action], error.reply.results);
            else this.messages.error(`${ACTION_TEXT[action]} failed: ${error.message}`);
            return false;
        }
    }

    reportFailures(what, results) {
        const failed = results.filter((result) => !result.ok);
        this.messages.error(
            `${what} failed on ${plural(failed.length, "robot")} of ${results.length}.`,
            failed.map((result) => `${this.model.label(result.robot)}: ${result.error}`),
        );
    }

    // Opens an .aesl file from this computer as the project of every tab.
    async openProject() {
        const file = await pickTextFile(".aesl,.xml,application/xml,text/xml");
        if (!file) return;
        if (await this.openProjectText(file.name, file.text)) rememberProject(file.name, file.text);
    }

    // A project opened before from this browser (storage.js), as it was then.
    async openRecentProject(entry) {
        if (await this.openProjectText(entry.name, entry.content)) rememberProject(entry.name, entry.content);
    }

    // Empties the project of every tab, at the second call within a few
    // seconds: the first says what it will do (no dialog).
    async newProject() {
        if (!this.newProjectAsked || Date.now() - this.newProjectAsked > NEW_PROJECT_CONFIRM_MS) {
            this.newProjectAsked = Date.now();
            this.messages.warning(
                "New project: every robot's script, the global events and the constants will be emptied, for every tab. Click New again to go on (.aesl downloads the current project first).",
            );
            return false;
        }
        this.newProjectAsked = 0;
        try {
            await this.connection.request({ type: "open-project", name: "new.aesl", content: EMPTY_PROJECT });
            // The server keeps a robot's script that no program replaced: the
            // editors are emptied here, as an edit (Ctrl+Z takes it back),
            // and the other tabs follow.
            for (const session of this.sessions.all()) session.setText("");
            this.messages.success("New project: every script is empty (Ctrl+Z in an editor takes its text back).");
            return true;
        } catch (error) {
            this.messages.error(`No new project: ${error.message}`);
            return false;
        }
    }

    /** @param {string} name @param {string} text */
    async openProjectText(name, text) {
        const file = { name, text };
        if (new TextEncoder().encode(file.text).length > MAX_PROJECT_BYTES) {
            this.messages.error(
                `${file.name} is larger than ${MAX_PROJECT_BYTES / 1024 / 1024} MB: it is not an Aseba project.`,
            );
            return false;
        }
        try {
            const reply = await this.connection.request({ type: "open-project", name: file.name, content: file.text });
            const details = (reply.waitingPrograms ?? []).map(
                (program) => `waiting for "${program.name}" (node ${program.id}) to join the network`,
            );
            this.messages.success(
                `Opened ${file.name}: ${plural(reply.matched.length, "robot")} got ${reply.matched.length === 1 ? "its" : "their"} program.`,
                details,
            );
            return true;
        } catch (error) {
            this.messages.error(`Cannot open ${file.name}: ${error.message}`);
            return false;
        }
    }

    // Saves to the server's project file when it has one, else downloads.
    async saveProject() {
        if (!this.model.projectFile) return this.downloadProject();
        try {
            await this.sessions.flushAll();
            const reply = await this.connection.request({ type: "save-project", toServerFile: true });
            this.messages.success(`Project saved to ${reply.savedTo}.`);
        } catch (error) {
            this.messages.error(`The project was not saved: ${error.message}`);
        }
    }

    async downloadProject() {
        try {
            await this.sessions.flushAll();
            const reply = await this.connection.request({ type: "save-project", toServerFile: false });
            const name = this.model.projectFile.split(/[\\/]/).pop() || "aseba-project.aesl";
            download(name, reply.content, "application/xml");
        } catch (error) {
            this.messages.error(`The project cannot be downloaded: ${error.message}`);
        }
    }

    // Studio's "save the binary code": the robot's program as an .abo file.
    async saveBinary(name) {
        const session = this.sessions.get(name);
        if (!session) return;
        try {
            const reply = await this.connection.request({ type: "bytecode", robot: name, source: session.text() });
            const bytes = Uint8Array.from(atob(reply.base64), (character) => character.charCodeAt(0));
            download(reply.fileName, new Blob([bytes], { type: "application/octet-stream" }));
        } catch (error) {
            this.messages.error(`No binary file for ${this.model.label(name)}: ${error.message}`);
        }
    }

    async emit(event, args) {
        try {
            await this.connection.request({ type: "emit", event, args });
            return true;
        } catch (error) {
            this.messages.error(`Event ${event} not sent: ${error.message}`);
            return false;
        }
    }

    async setVariable(robot, name, index, values) {
        try {
            await this.connection.request({ type: "set-variable", robot, name, index, values });
            return true;
        } catch (error) {
            this.messages.error(`${name} of ${this.model.label(robot)} not changed: ${error.message}`);
            return false;
        }
    }

    async setDefinitions(definitions) {
        try {
            await this.connection.request({ type: "definitions", ...definitions });
            return true;
        } catch (error) {
            this.messages.error(`Definitions not changed: ${error.message}`);
            return false;
        }
    }
}
