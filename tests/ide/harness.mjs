// What the browser tests, the screenshots and the benchmark share: free
// ports, the simulated robots (epuck-emu) and the IDE server started as
// child processes and stopped by their PIDs, the console for checks, and
// headless Chromium driven by playwright-core.

import { spawn, execFile } from "node:child_process";
import { createServer, connect } from "node:net";
import { mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve, dirname } from "node:path";
import { fileURLToPath } from "node:url";
import { createRequire } from "node:module";

export const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), "../..");
// The programs under test: BIN (default build/host/bin).
export const BIN = resolve(ROOT, process.env.BIN ?? "build/host/bin");
export const CHROMIUM = process.env.CHROMIUM ?? "/usr/bin/chromium";

// playwright-core is a development dependency of the page.
const require = createRequire(join(ROOT, "tools/ide/web/package.json"));
const { chromium } = require("playwright-core");

// Children still running; stopped on exit whatever happens.
const children = new Set();
process.on("exit", () => {
    for (const child of children) {
        try {
            process.kill(child.pid, "SIGKILL");
        } catch {
            // already gone
        }
    }
});

// A TCP port free on loopback now.
export function freePort() {
    return new Promise((resolvePort, reject) => {
        const server = createServer();
        server.unref();
        server.on("error", reject);
        server.listen(0, "127.0.0.1", () => {
            const { port } = server.address();
            server.close(() => resolvePort(port));
        });
    });
}

export const sleep = (milliseconds) => new Promise((done) => setTimeout(done, milliseconds));

// Polls `check` (sync or async) until it returns a truthy value; throws
// `what` after `timeout` ms.
export async function waitFor(check, what, timeout = 10000, interval = 50) {
    const deadline = Date.now() + timeout;
    let last;
    for (;;) {
        try {
            last = await check();
            if (last) return last;
        } catch (error) {
            last = error;
        }
        if (Date.now() > deadline) throw new Error(`timed out waiting for ${what} (last: ${last instanceof Error ? last.message : JSON.stringify(last)})`);
        await sleep(interval);
    }
}

// A program of BIN running in the background, with its output collected.
export class Child {
    constructor(name, args) {
        this.name = name;
        this.args = args;
        this.output = "";
        this.process = spawn(join(BIN, name), args, { stdio: ["ignore", "pipe", "pipe"] });
        children.add(this.process);
        this.exited = new Promise((done) =>
            this.process.on("exit", (code, signal) => {
                children.delete(this.process);
                this.exitCode = code ?? signal;
                done(this.exitCode);
            }),
        );
        this.process.on("error", (error) => {
            this.output += `cannot start ${name}: ${error.message}\n`;
        });
        for (const stream of [this.process.stdout, this.process.stderr])
            stream.on("data", (data) => {
                this.output += data.toString();
                if (this.output.length > 200000) this.output = this.output.slice(-100000);
            });
    }

    get pid() {
        return this.process.pid;
    }

    // Waits until the output matches `pattern`.
    async ready(pattern, timeout = 15000) {
        await waitFor(() => {
            if (this.exitCode !== undefined) throw new Error(`${this.name} exited (${this.exitCode}): ${this.output.slice(-2000)}`);
            return pattern.test(this.output);
        }, `${this.name} to start (${pattern})`, timeout);
    }

    // SIGTERM, then SIGKILL after `grace` ms.
    async stop(grace = 3000) {
        if (this.exitCode !== undefined) return this.exitCode;
        try {
            process.kill(this.pid, "SIGTERM");
        } catch {
            return this.exitCode;
        }
        const timer = setTimeout(() => {
            try {
                process.kill(this.pid, "SIGKILL");
            } catch {
                // gone meanwhile
            }
        }, grace);
        const code = await this.exited;
        clearTimeout(timer);
        return code;
    }
}

// The console's answer to `aseba -t TARGET ARGS...`.
export function aseba(port, ...args) {
    return run(join(BIN, "aseba"), ["-t", `tcp:localhost;${port}`, ...args]);
}

export function run(program, args, timeout = 20000) {
    return new Promise((done, reject) => {
        execFile(program, args, { timeout, env: { ...process.env, LC_ALL: "en_US.UTF-8" } }, (error, stdout, stderr) => {
            if (error) reject(new Error(`${program} ${args.join(" ")}: ${error.message}\n${stdout}${stderr}`));
            else done(stdout + stderr);
        });
    });
}

// epuck-emu on a free port: `robots` robots, or the arena (with its feed).
export async function startEmulator({ robots = 3, arena = null, port = null } = {}) {
    port = port ?? (await freePort());
    const args = ["--port", String(port), "--robots", String(robots), "--quiet"];
    let feedPort = null;
    if (arena) {
        feedPort = await freePort();
        args.push("--arena", arena, "--speed", "realtime", "--arena-feed", String(feedPort));
    }
    const child = new Child("epuck-emu", args);
    // Listening once a client can connect.
    await waitFor(() => canConnect(port), `epuck-emu on port ${port}`, 15000, 100);
    child.port = port;
    child.feedPort = feedPort;
    return child;
}

function canConnect(port) {
    return new Promise((done) => {
        const socket = connect(port, "127.0.0.1");
        socket.on("connect", () => {
            socket.destroy();
            done(true);
        });
        socket.on("error", () => done(false));
    });
}

// aseba-ide on a free port, joined to `targets`.
export async function startIde({ targets, port = null, arenaFeed = null } = {}) {
    port = port ?? (await freePort());
    const args = ["--port", String(port), ...targets];
    if (arenaFeed) args.push("--arena", `tcp:localhost;${arenaFeed}`);
    const child = new Child("aseba-ide", args);
    await child.ready(/open http:\/\//);
    child.port = port;
    // ?test: the page shows its parts as window.asebaIde (src/main.js).
    child.url = `http://127.0.0.1:${port}/?test`;
    return child;
}

// Headless Chromium from Debian, with a profile of its own.
export async function launchBrowser() {
    return chromium.launch({
        executablePath: CHROMIUM,
        headless: true,
        args: ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking", "--disable-component-update", "--disable-sync"],
    });
}

// What most test files start before their tests: `robots` simulated
// e-pucks (in the default arena with `arena`, its feed given to the IDE), an
// IDE on them and a browser.
// What did start is stopped when a part fails.
export async function startSession({ robots = 3, arena = false } = {}) {
    const session = {};
    try {
        session.emulator = await startEmulator({ robots, arena: arena ? "default" : null });
        const feed = arena ? session.emulator.feedPort : null;
        session.ide = await startIde({ targets: [`tcp:localhost;${session.emulator.port}`], arenaFeed: feed });
        session.browser = await launchBrowser();
        return session;
    } catch (error) {
        await stopSession(session);
        throw error;
    }
}

// Stops what startSession started, whichever parts of it did start.
export async function stopSession({ emulator, ide, browser } = {}) {
    await browser?.close();
    await ide?.stop();
    await emulator?.stop();
}

export function temporaryFolder(prefix = "aseba-ide-test-") {
    const path = mkdtempSync(join(tmpdir(), prefix));
    return { path, remove: () => rmSync(path, { recursive: true, force: true }) };
}

// Page helpers ------------------------------------------------------------------

// Opens the IDE in a new page and waits for its robots' tabs; `settings`
// are the page's remembered settings (storage.js) to start with.
export async function openIde(browser, url, { robots = 0, viewport = { width: 1366, height: 768 }, settings = {} } = {}) {
    const context = await browser.newContext({ viewport, acceptDownloads: true });
    await context.addInitScript((values) => {
        for (const [name, value] of Object.entries(values)) localStorage.setItem(`aseba-ide/setting/${name}`, JSON.stringify(value));
    }, settings);
    const page = await context.newPage();
    page.errors = [];
    page.on("pageerror", (error) => page.errors.push(error.message));
    await page.goto(url);
    await page.locator('[data-testid="page-connection"][data-state="open"]').waitFor();
    if (robots > 0) await waitFor(async () => (await page.locator(".robot-tab").count()) >= robots, `${robots} robot tabs`);
    return page;
}

// Replaces the text of the editor shown with `text`, as typing would.
export async function setEditorText(page, text) {
    await page.evaluate((source) => {
        const view = window.asebaIde.robotPanel.view;
        view.dispatch({ changes: { from: 0, to: view.state.doc.length, insert: source }, userEvent: "input.paste" });
    }, text);
}

export function editorText(page) {
    return page.evaluate(() => window.asebaIde.robotPanel.view.state.doc.toString());
}

export async function selectRobot(page, name) {
    await page.locator(`.robot-tab[data-robot="${name}"]`).click();
    await page.locator(`.robot-tab[data-robot="${name}"][aria-selected="true"]`).waitFor();
}
