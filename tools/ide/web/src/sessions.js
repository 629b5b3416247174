// Each robot's script as the page edits it: its EditorState, what the server
// has of it, and its compile result. The rules that keep the user's work:
// every change goes to localStorage at once and to the server as soon as
// the previous request is answered (`compile` when the robot can compile
// it, else `script`); after a reconnection the page's text wins where it
// differs from the server's; another tab's text replaces ours only when we
// have nothing unsent.

import { Emitter } from "./emitter.js";
import {
    createState,
    compileDiagnostics,
    breakpointLines,
    breakpointsAt,
    breakpointStatus,
    executionLine,
    runtimeError,
    fromServer,
} from "./editor.js";
import { loadScript, saveScript } from "./storage.js";

// The server refuses longer scripts (docs/ide-protocol.md); the page does
// not even send them, so that a huge paste never reaches the socket.
export const MAX_SCRIPT_BYTES = 256 * 1024;
// How long typing may go on before the text is written to localStorage.
const PERSIST_DELAY_MS = 200;

function utf8Length(text) {
    // Cheap for the usual script; exact when it could matter.
    if (text.length * 3 <= MAX_SCRIPT_BYTES) return text.length;
    return new TextEncoder().encode(text).length;
}

function percent(used, total) {
    return total > 0 ? Math.round((100 * used) / total) : 0;
}

// "bytecode 120/1024 words (12 %), variables 300/509 (59 %)"
export function memoryText(bytecodeUsed, bytecodeTotal, variablesUsed, variablesTotal) {
    return (
        `bytecode ${bytecodeUsed}/${bytecodeTotal} words (${percent(bytecodeUsed, bytecodeTotal)} %), ` +
        `variables ${variablesUsed}/${variablesTotal} (${percent(variablesUsed, variablesTotal)} %)`
    );
}

// "line 3, column 5: message"
export function compileErrorText(error) {
    return error.line > 0 ? `line ${error.line}, column ${error.column}: ${error.message}` : error.message;
}

export class RobotSession {
    constructor(sessions, name, text) {
        this.sessions = sessions;
        this.name = name;
        this.ownState = createState(text, sessions.extensions);
        this.view = null;
        this.syncedText = ""; // what the server is known to hold
        this.compiledText = null; // the text of the compile shown (or asked for)
        this.flight = null; // the request on its way, as a promise
        this.persistTimer = null;
        // {kind: "ok" | "error" | "refused" | "idle", text, memory}
        this.status = { kind: "idle", text: "" };
        this.runtimeError = null;
        this.executionLine = 0; // where the robot stands, 0: not shown
    }

    get state() {
        return this.view ? this.view.state : this.ownState;
    }

    text() {
        return this.state.doc.toString();
    }

    // Applies a transaction to the robot's text, shown or not.
    dispatch(spec) {
        if (this.view) this.view.dispatch(spec);
        else this.ownState = this.ownState.update(spec).state;
    }

    attach(view) {
        this.view = view;
        view.setState(this.ownState);
    }

    detach() {
        this.ownState = this.view.state;
        this.view = null;
    }

    hasUnsentChange() {
        return this.text() !== this.syncedText;
    }

    // The user typed.
    changed() {
        this.schedulePersist();
        this.pump();
    }

    // Replaces the text as the user would (undoable), and sends it.
    setText(text) {
        if (text === this.text()) return;
        this.dispatch({ changes: { from: 0, to: this.state.doc.length, insert: text }, userEvent: "input.paste" });
        // The view's listener saw the change; a robot not shown is told here.
        if (!this.view) this.changed();
    }

    // Replaces the text by the server's (another tab, a project).
    replaceFromServer(source) {
        this.syncedText = source;
        this.compiledText = null;
        if (source !== this.text())
            this.dispatch({
                changes: { from: 0, to: this.state.doc.length, insert: source },
                annotations: fromServer.of(true),
            });
        this.persist();
        this.pump();
    }

    // Compiles again (definitions changed, the robot came back).
    recompile() {
        this.compiledText = null;
        this.pump();
    }

    // Sends the text if the server lacks it or its compile result is not
    // shown; one request at a time, the latest text wins.
    pump() {
        if (this.flight || !this.sessions.connection.open) return;
        const text = this.text();
        const compile = this.sessions.canCompile(this.name) && text !== this.compiledText;
        if (!compile && text === this.syncedText) return;
        const bytes = utf8Length(text);
        if (bytes > MAX_SCRIPT_BYTES) {
            this.compiledText = null; // no compile result is shown now
            this.setStatus({
                kind: "error",
                text: `this script is ${Math.ceil(bytes / 1024)} KB: the IDE takes scripts up to ${MAX_SCRIPT_BYTES / 1024} KB; it is kept in this browser only`,
            });
            return;
        }
        const request = { type: compile ? "compile" : "script", robot: this.name, source: text };
        // The server's own text is compiled for its result only: sending it
        // back as ours could undo a newer text of another tab.
        if (compile && text === this.syncedText) request.remember = false;
        this.flight = this.sessions.connection
            .request(request)
            .then(
                (reply) => {
                    this.acknowledged(text, compile);
                    if (compile) this.showCompile(reply.compile, text);
                },
                (error) => {
                    // Refused, but the server has the text (it remembers a
                    // script before it compiles it).
                    if (error.unsent) return;
                    this.acknowledged(text, compile);
                    if (compile) this.setStatus({ kind: "refused", text: error.message });
                },
            )
            .finally(() => {
                this.flight = null;
                this.pump();
            });
    }

    acknowledged(text, compiled) {
        this.syncedText = text;
        if (compiled) this.compiledText = text;
        this.persist();
    }

    // Resolves once the server holds the current text.
    async flush() {
        while (this.flight) await this.flight;
        const text = this.text();
        if (text === this.syncedText || utf8Length(text) > MAX_SCRIPT_BYTES) return;
        await this.sessions.connection.request({ type: "script", robot: this.name, source: text });
        this.acknowledged(text, false);
    }

    showCompile(result, text) {
        // A result for an older text would point at the wrong places; the
        // newer text's compile is already on its way.
        if (text !== this.text()) return;
        this.dispatch(compileDiagnostics(this.state, result.ok ? null : result.error));
        this.setStatus(this.statusOf(result));
    }

    statusOf(result) {
        if (!result.ok) return { kind: "error", text: compileErrorText(result.error), error: result.error };
        return {
            kind: "ok",
            text: memoryText(result.bytecodeWords, result.bytecodeSize, result.variableWords, result.variablesSize),
            memory: {
                bytecode: [result.bytecodeWords, result.bytecodeSize],
                variables: [result.variableWords, result.variablesSize],
            },
        };
    }

    setStatus(status) {
        this.status = status;
        this.sessions.emit("status", this);
    }

    // A load that did not compile: the error at its place.
    showLoadFailure(failure) {
        this.dispatch(compileDiagnostics(this.state, failure.error));
        this.setStatus(this.statusOf(failure));
    }

    breakpointLines() {
        return breakpointLines(this.state);
    }

    setBreakpointLines(lines) {
        this.dispatch(breakpointsAt(this.state, lines));
    }

    // The robot's answer about the breakpoints: [{line, set}].
    showBreakpointResults(results) {
        this.dispatch(breakpointStatus(results));
    }

    async sendBreakpoints() {
        try {
            const reply = await this.sessions.connection.request({
                type: "breakpoints",
                robot: this.name,
                lines: this.breakpointLines(),
            });
            if (!reply.pending) this.showBreakpointResults(reply.breakpoints);
        } catch (error) {
            this.sessions.emit("error", `Breakpoints of ${this.sessions.model.label(this.name)}: ${error.message}`);
        }
    }

    setExecutionLine(line) {
        this.dispatch(executionLine(line));
    }

    setRuntimeError(error) {
        this.runtimeError = error;
        this.dispatch(runtimeError(error));
        this.sessions.emit("status", this);
    }

    schedulePersist() {
        clearTimeout(this.persistTimer);
        this.persistTimer = setTimeout(() => this.persist(), PERSIST_DELAY_MS);
    }

    persist() {
        clearTimeout(this.persistTimer);
        this.persistTimer = null;
        const text = this.text();
        if (!saveScript(this.name, text, text === this.syncedText)) this.sessions.emit("storage-full", this);
    }
}

export class Sessions extends Emitter {
    // `extensions`: the editor extensions of every robot's state.
    constructor({ connection, model, extensions }) {
        super();
        this.connection = connection;
        this.model = model;
        this.extensions = extensions;
        this.sessions = new Map();
        this.serverScripts = {}; // from the last hello
    }

    get(name) {
        return this.sessions.get(name);
    }

    all() {
        return [...this.sessions.values()];
    }

    canCompile(name) {
        const robot = this.model.robots.get(name);
        return Boolean(robot && robot.present && robot.described && robot.compatible);
    }

    // The robot's session, made from localStorage and the server's script
    // the first time: the stored text wins when the server never got it or
    // has none, the server's when both had it.
    ensure(name) {
        let session = this.sessions.get(name);
        if (session) return session;
        const server = this.serverScripts[name];
        const stored = loadScript(name);
        const keepStored = stored && (!stored.synced || server === undefined);
        session = new RobotSession(this, name, keepStored ? stored.text : (server ?? stored?.text ?? ""));
        session.syncedText = server ?? "";
        const robot = this.model.robots.get(name);
        if (robot?.breakpoints?.length) session.setBreakpointLines(robot.breakpoints);
        if (robot?.lastError) session.setRuntimeError(robot.lastError);
        this.sessions.set(name, session);
        this.emit("added", session);
        return session;
    }

    // After every (re)connection: the page's texts win where they differ,
    // and are sent back.
    applyHello(hello) {
        this.serverScripts = hello.scripts ?? {};
        for (const session of this.sessions.values()) {
            session.syncedText = this.serverScripts[session.name] ?? "";
            session.compiledText = null;
        }
        for (const robot of hello.robots ?? []) this.ensure(robot.robot);
        for (const session of this.sessions.values()) session.pump();
    }

    // Another tab changed a robot's script.
    applyScript(name, source) {
        this.serverScripts[name] = source;
        const session = this.sessions.get(name);
        if (!session) return;
        if (session.hasUnsentChange()) return;
        session.replaceFromServer(source);
    }

    // A project was opened: its scripts replace the editors' texts.
    applyProject(project) {
        this.serverScripts = project.scripts ?? {};
        for (const [name, source] of Object.entries(this.serverScripts)) this.ensure(name).replaceFromServer(source);
        this.recompileAll();
    }

    recompileAll() {
        for (const session of this.sessions.values()) session.recompile();
    }

    // Resolves once the server holds every text (before a save).
    async flushAll() {
        await Promise.all(this.all().map((session) => session.flush()));
    }

    persistAll() {
        for (const session of this.sessions.values()) if (session.persistTimer) session.persist();
    }
}
