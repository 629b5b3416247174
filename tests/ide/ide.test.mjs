// End-to-end tests of the group IDE in a real browser: headless Chromium
// on the page that aseba-ide serves, against three simulated e-pucks
// (epuck-emu). Each check reads what the user sees on the page and, where
// the robots are concerned, asks them independently with the console
// (`aseba vars`) or the reference tools (asebamassloader).

import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { writeFileSync, readFileSync } from "node:fs";
import { join } from "node:path";
import {
    startEmulator,
    startIde,
    launchBrowser,
    openIde,
    setEditorText,
    editorText,
    selectRobot,
    waitFor,
    sleep,
    aseba,
    run,
    temporaryFolder,
} from "./harness.mjs";

const TIMEOUT = { timeout: 30000 };

// The program of the tests; STEP is a constant of the project, ping and
// pong its global events.
const PROGRAM = `# counts the IR updates; the tests write target
var counter = 0
var target = 0
var pings = 0

onevent ir_sensors
    counter = counter + STEP
    leds[0] = counter % 2

onevent ping
    pings = pings + 1
    emit pong args[0] + args[1]
`;
const COUNT_LINE = 7; // counter = counter + STEP
const LED_LINE = 8;

let emulator;
let ide;
let browser;
let page;
let folder;
let programFile;
// Every emulator and server started, for their reports at the end.
const started = [];

before(async () => {
    folder = temporaryFolder();
    programFile = join(folder.path, "program.aesl");
    emulator = await startEmulator({ robots: 3 });
    ide = await startIde({ targets: [`tcp:localhost;${emulator.port}`] });
    started.push(emulator, ide);
    browser = await launchBrowser();
});

after(async () => {
    await browser?.close();
    await ide?.stop();
    await emulator?.stop();
    folder?.remove();
});

// A project the console can read the program's variables from.
function writeProgramFile(source) {
    const xml = source.replaceAll("&", "&amp;").replaceAll("<", "&lt;").replaceAll(">", "&gt;");
    writeFileSync(
        programFile,
        `<!DOCTYPE aesl-source>\n<network>\n<event size="2" name="ping"/>\n<event size="1" name="pong"/>\n<constant value="1" name="STEP"/>\n<node nodeId="1" name="e-puck">${xml}</node>\n</network>\n`,
    );
}

// `name` of every robot (or of node `node`), as the console reads it.
async function consoleValues(name, node = null) {
    const args = ["-p", programFile, ...(node ? ["-n", String(node)] : []), "vars", name];
    const output = await aseba(emulator.port, ...args);
    return [...output.matchAll(new RegExp(`${name.replace(".", "\\.")} = (-?\\d+)`, "g"))].map((match) => Number(match[1]));
}

async function robotStates(target) {
    return page.$$eval(".robot-tab", (tabs) => tabs.map((tab) => tab.dataset.state));
}

async function compileStatus(target = page) {
    const status = target.locator('[data-testid="compile-status"]');
    return { kind: await status.getAttribute("data-kind"), text: await status.innerText() };
}

// The line (1-based) of the first element matching `selector` in the editor.
function lineOf(selector, target = page) {
    return target.evaluate((css) => {
        const element = document.querySelector(css);
        if (!element) return 0;
        const view = window.asebaIde.robotPanel.view;
        return view.state.doc.lineAt(view.posAtDOM(element)).number;
    }, selector);
}

async function clickBreakpointGutter(line) {
    const point = await page.evaluate((number) => {
        const view = window.asebaIde.robotPanel.view;
        const block = view.lineBlockAt(view.state.doc.line(number).from);
        const gutter = document.querySelector(".cm-breakpoint-gutter").getBoundingClientRect();
        const top = view.documentTop + block.top + block.height / 2;
        return { x: gutter.left + gutter.width / 2, y: top };
    }, line);
    await page.mouse.click(point.x, point.y);
}

// The button whose accessible name starts with `label`.
async function clickButton(label, target = page) {
    await target.locator(`button[aria-label^="${label}"]`).first().click();
}

// A button of the robot's own toolbar: load, run, step, store...
async function clickRobotButton(action) {
    await page.locator(`.robot-toolbar button.robot-${action}`).click();
}

test("the page opens with one tab per robot", TIMEOUT, async () => {
    page = await openIde(browser, ide.url, { robots: 3 });
    const labels = await page.$$eval(".robot-tab .tab-label", (tabs) => tabs.map((tab) => tab.textContent));
    assert.deepEqual(labels, ["e-puck 1", "e-puck 2", "e-puck 3"]);
    await waitFor(async () => (await page.locator(".network-row").count()) === 3, "three robots in the network view");
    assert.equal(await page.locator('.link-state[data-up="true"]').count(), 1);
});

test("global events and constants are defined once for all robots", TIMEOUT, async () => {
    await page.locator('.bottom-tab[data-pane="events"]').click();
    for (const [name, size] of [
        ["ping", 2],
        ["pong", 1],
    ]) {
        await page.fill('input[aria-label="Name of the new event"]', name);
        await page.fill('input[aria-label="Size of the new event"]', String(size));
        await clickButton("Add the event");
        await page.locator(`.definitions-events .definition-row[data-name="${name}"]`).waitFor();
    }
    await page.locator('.bottom-tab[data-pane="constants"]').click();
    await page.fill('input[aria-label="Name of the new constant"]', "STEP");
    await page.fill('input[aria-label="Value of the new constant"]', "1");
    await clickButton("Add the constant");
    await page.locator('.definitions-constants .definition-row[data-name="STEP"]').waitFor();
    await page.locator('.bottom-tab[data-pane="events"]').click();
});

test("a compile error is marked in red at its line, and goes when fixed", TIMEOUT, async () => {
    const broken = PROGRAM.replace("counter + STEP", "counter + undefinedThing");
    const column = broken.split("\n")[COUNT_LINE - 1].indexOf("undefinedThing") + 1;
    await setEditorText(page, broken);
    await waitFor(async () => (await compileStatus()).kind === "error", "a compile error");
    const { text } = await compileStatus();
    assert.match(text, new RegExp(`line ${COUNT_LINE}, column ${column}: .*undefinedThing`));
    assert.equal(await lineOf(".cm-lintRange-error"), COUNT_LINE);
    assert.equal(await page.locator(".cm-lintRange-error").first().innerText(), "undefinedThing");
    assert.equal(await page.locator('.robot-tab[data-robot="0:1"] .tab-error').isVisible(), true);
    // Loading it is refused, with the reason in the message bar.
    await clickButton("Load: compile this script");
    const refusal = page.locator(".message-error", { hasText: "Nothing was loaded: a program does not compile." });
    await refusal.waitFor();
    assert.match(await refusal.innerText(), new RegExp(`e-puck 1: line ${COUNT_LINE}, column ${column}: .*undefinedThing`));
    await refusal.locator(".message-close").click();

    await setEditorText(page, PROGRAM);
    await waitFor(async () => (await compileStatus()).kind === "ok", "the fixed script to compile");
    assert.match((await compileStatus()).text, /bytecode \d+\/1024 words \(\d+ %\), variables \d+\/605 \(\d+ %\)/);
    assert.equal(await page.locator(".cm-lintRange-error").count(), 0);
});

test("Load all loads every robot's script and runs them", TIMEOUT, async () => {
    for (const name of ["0:2", "0:3"]) {
        await selectRobot(page, name);
        await setEditorText(page, PROGRAM);
    }
    await selectRobot(page, "0:1");
    writeProgramFile(PROGRAM);
    await clickButton("Load all");
    await waitFor(async () => (await robotStates()).every((state) => state === "running"), "three running robots");
    // The robots count: the console sees counter grow on each.
    const first = await consoleValues("counter");
    assert.equal(first.length, 3);
    await sleep(300);
    const second = await consoleValues("counter");
    for (let i = 0; i < 3; i++) assert.ok(second[i] > first[i], `counter of robot ${i + 1} grows: ${first[i]} then ${second[i]}`);
});

test("a breakpoint stops the robot at its line; step goes to the next line", TIMEOUT, async () => {
    await clickBreakpointGutter(COUNT_LINE);
    await page.locator(".cm-breakpoint-set").waitFor();
    await waitFor(async () => (await page.locator('[data-testid="robot-state"]').getAttribute("data-state")) === "stepping", "robot 1 to stop");
    await waitFor(async () => (await lineOf(".cm-execution-line")) === COUNT_LINE, `the execution line ${COUNT_LINE}`);
    // Robot 1 stands still, the others go on.
    const stopped = (await consoleValues("counter", 1))[0];
    await sleep(200);
    assert.equal((await consoleValues("counter", 1))[0], stopped);

    await clickRobotButton("step");
    await waitFor(async () => (await lineOf(".cm-execution-line")) === LED_LINE, `the execution line ${LED_LINE} after a step`);
    assert.equal((await consoleValues("counter", 1))[0], stopped + 1);

    await clickBreakpointGutter(COUNT_LINE);
    await waitFor(async () => (await page.locator(".cm-breakpoint").count()) === 0, "the breakpoint to go");
    await clickRobotButton("run");
    await waitFor(async () => (await page.locator('[data-testid="robot-state"]').getAttribute("data-state")) === "running", "robot 1 to run again");
    assert.equal(await page.locator(".cm-execution-line").count(), 0);
});

test("Stop all, Run all and Pause all act on every robot", TIMEOUT, async () => {
    const frozen = async () => {
        const first = await consoleValues("counter");
        await sleep(200);
        const second = await consoleValues("counter");
        return first.length === 3 && first.every((value, i) => value === second[i]);
    };
    for (const [action, stopped] of [
        ["Stop all", true],
        ["Run all", false],
        ["Pause all", true],
        ["Run all", false],
    ]) {
        await clickButton(action);
        await waitFor(async () => (await robotStates()).every((state) => (state === "running") === !stopped), `the robots' states after ${action}`);
        assert.equal(await frozen(), stopped, `${action}: the counters ${stopped ? "stand still" : "grow"}`);
    }
});

test("a program stored in flash runs after a reboot", TIMEOUT, async () => {
    await selectRobot(page, "0:1");
    await clickRobotButton("store");
    await page.locator(".message-success", { hasText: "Program written to the flash of e-puck 1" }).waitFor();
    await waitFor(async () => (await page.locator(".program-status").innerText()).includes("stored in flash"), "the program shown as stored");
    const before = (await consoleValues("counter", 1))[0];
    await clickRobotButton("reboot");
    // Rebooted, it runs the stored program from its start: the count starts again.
    await waitFor(async () => {
        const [value] = await consoleValues("counter", 1).catch(() => [undefined]);
        return value !== undefined && value < before;
    }, "robot 1 to count again from 0 after its reboot", 15000, 200);
    const [first] = await consoleValues("counter", 1);
    await sleep(200);
    assert.ok((await consoleValues("counter", 1))[0] > first);
    await waitFor(async () => (await page.locator('[data-testid="robot-state"]').getAttribute("data-state")) === "running", "the page to show robot 1 running");
});

test("the binary code is saved as an .abo file", TIMEOUT, async () => {
    const words = Number(/bytecode (\d+)\//.exec((await compileStatus()).text)[1]);
    const [download] = await Promise.all([page.waitForEvent("download"), clickRobotButton("binary")]);
    const path = join(folder.path, download.suggestedFilename());
    await download.saveAs(path);
    assert.equal(download.suggestedFilename(), "e-puck-1.abo");
    // The layout of aesl.md §6: magic, ..., node id at 12, length at 18.
    const bytes = readFileSync(path);
    assert.deepEqual([...bytes.subarray(0, 4)], [0x41, 0x42, 0x4f, 0x00]);
    assert.equal(bytes.readUInt16LE(12), 1);
    assert.equal(bytes.readUInt16LE(18), words);
    assert.equal(bytes.length, 22 + 2 * words);
});

test("a variable changed in the page is the robot's", TIMEOUT, async () => {
    await selectRobot(page, "0:2");
    const value = page.locator('.variable-value[data-variable="target"]');
    await waitFor(async () => (await value.innerText()) === "0", "target to show 0");
    await value.click();
    await page.locator(".variable-input").fill("1234");
    await page.locator(".variable-input").press("Enter");
    await waitFor(async () => (await consoleValues("target", 2))[0] === 1234, "the console to read target = 1234");
    assert.deepEqual(await consoleValues("target", 1), [0]);
    // The live value is the robot's.
    await sleep(300);
    assert.equal(await value.innerText(), "1234");
});

test("an event sent from the page reaches the robots and shows in the monitor", TIMEOUT, async () => {
    await page.selectOption('select[aria-label="Event to send"]', "ping");
    await page.fill('input[aria-label="Arguments of the event"]', "3, 4");
    await clickButton("Send the event");
    const rows = page.locator(".monitor-row");
    await waitFor(async () => {
        const texts = await rows.allInnerTexts();
        return texts.some((text) => /this IDE\s+ping\s+3, 4/.test(text)) && texts.filter((text) => /e-puck \d\s+pong\s+7$/.test(text.trim())).length === 3;
    }, "ping from the IDE and three pongs in the monitor");
    assert.deepEqual(await consoleValues("pings"), [1, 1, 1]);
    // Each robot sent one event: the network view counts it.
    await waitFor(async () => (await page.locator('.network-row[data-robot="0:2"] .network-rate').innerText()) !== "–", "robot 2's event rate");

    // Filters: one robot's entries only.
    await page.selectOption('select[aria-label="Show the entries of"]', "0:3");
    const filtered = await rows.allInnerTexts();
    assert.ok(filtered.length >= 1 && filtered.every((text) => text.includes("e-puck 3")), `only robot 3: ${filtered}`);
    await page.selectOption('select[aria-label="Show the entries of"]', "");
});

test("the plot follows a robot's variable and an event's argument", TIMEOUT, async () => {
    await page.locator('.bottom-tab[data-pane="plot"]').click();
    for (const [robot, source] of [
        ["0:1", "variable:counter"],
        ["0:2", "event:pong"],
    ]) {
        await page.selectOption('select[aria-label="Robot of the new series"]', robot);
        await page.selectOption('select[aria-label="Variable or event of the new series"]', source);
        await page.fill('input[aria-label="Index in the variable or argument of the event"]', "0");
        await clickButton("Add the series");
    }
    const chips = page.locator(".series-chip");
    assert.deepEqual(await chips.locator("span:nth-child(2)").allInnerTexts(), ["e-puck 1 · counter", "e-puck 2 · event pong[0]"]);
    // counter grows on the plot (read while robot 1's tab is not shown).
    await selectRobot(page, "0:3");
    const counterSamples = () => page.evaluate(() => window.asebaIde.bottom.plot.series[0].values.slice());
    await waitFor(async () => (await counterSamples()).length >= 5, "samples of counter");
    const samples = await counterSamples();
    assert.ok(samples[samples.length - 1] > samples[0], `counter grows on the plot: ${samples}`);
    // An event's argument: ping 2, 5 makes robot 2 answer pong 7.
    await page.locator('.bottom-tab[data-pane="events"]').click();
    await page.fill('input[aria-label="Arguments of the event"]', "2, 5");
    await clickButton("Send the event");
    await page.locator('.bottom-tab[data-pane="plot"]').click();
    await waitFor(() => page.evaluate(() => window.asebaIde.bottom.plot.series[1].values.includes(7)), "pong 7 on the plot");
    await waitFor(() => page.evaluate(() => window.asebaIde.bottom.plot.plot.data[0].length > 5), "the chart to hold the samples");
    for (let i = 0; i < 2; i++) await page.locator('.series-chip button[aria-label^="Remove"]').first().click();
    assert.equal(await chips.count(), 0);
    await page.locator('.bottom-tab[data-pane="events"]').click();
});

test("a run-time error shows at its line", TIMEOUT, async () => {
    await selectRobot(page, "0:3");
    const faulty = "var zero = 0\nvar x = 0\n\nonevent ir_sensors\n    x = 10 / zero\n";
    await setEditorText(page, faulty);
    await waitFor(async () => (await compileStatus()).kind === "ok", "the faulty script to compile");
    await clickRobotButton("load");
    await page.locator(".cm-runtime-error-line").waitFor();
    assert.equal(await lineOf(".cm-runtime-error-line"), 5);
    assert.match(await page.locator(".runtime-status").innerText(), /line 5: division by zero/);
    assert.match(await page.locator('.network-row[data-robot="0:3"] .network-error').innerText(), /division by zero/);

    await setEditorText(page, PROGRAM);
    await clickRobotButton("load");
    await waitFor(async () => (await page.locator(".cm-runtime-error-line").count()) === 0, "the error mark to go after a new load");
});

test("another tab's edit replaces the text of a tab with nothing unsent", TIMEOUT, async () => {
    const other = await openIde(browser, ide.url, { robots: 3 });
    await selectRobot(other, "0:3");
    await selectRobot(page, "0:3");
    const edited = PROGRAM.replace("# counts", "# edited in another tab; counts");
    await setEditorText(other, edited);
    await waitFor(async () => (await editorText(page)) === edited, "the first tab to show the other tab's text");
    await other.context().close();
});

test("another tab's text does not replace unsent changes; the last sent wins", TIMEOUT, async () => {
    const other = await openIde(browser, ide.url, { robots: 3 });
    await selectRobot(other, "0:3");
    await selectRobot(page, "0:3");
    // This page's requests wait, as on a slow network: its change is unsent.
    await page.evaluate(() => {
        const connection = window.asebaIde.connection;
        const send = connection.request.bind(connection);
        let release;
        const released = new Promise((resolve) => (release = resolve));
        window.releaseRequests = () => {
            connection.request = send;
            release();
        };
        connection.request = (message) => released.then(() => send(message));
    });
    const ours = PROGRAM.replace("# counts", "# ours; counts");
    const theirs = PROGRAM.replace("# counts", "# theirs; counts");
    await setEditorText(page, ours);
    await setEditorText(other, theirs);
    await sleep(600);
    assert.equal(await editorText(page), ours, "the unsent text stays");
    await page.evaluate(() => window.releaseRequests());
    // Ours reaches the server after theirs: the other tab follows.
    await waitFor(async () => (await editorText(other)) === ours, "the other tab to show the text sent last");
    assert.equal(await editorText(page), ours);
    await other.context().close();
    await setEditorText(page, PROGRAM);
});

test("a huge paste gets a clear error and the connection stays", TIMEOUT, async () => {
    await selectRobot(page, "0:1");
    const huge = PROGRAM + `# ${"x".repeat(300 * 1024)}\n`;
    await setEditorText(page, huge);
    await waitFor(async () => (await compileStatus()).kind === "error", "an error about the size");
    assert.match((await compileStatus()).text, /this script is 30\d KB: the IDE takes scripts up to 256 KB/);
    await sleep(500);
    assert.equal(await page.locator('[data-testid="page-connection"]').getAttribute("data-state"), "open");
    await setEditorText(page, PROGRAM);
    await waitFor(async () => (await compileStatus()).kind === "ok", "the script to compile again");
});

// A stress test: 21 pages on a machine that CI shares with two other test
// programs. Its waits are long, and its tabs close whatever happens, so
// that a failure here is reported here and not again by the tests after it
// (the tabs would otherwise stay connected and answer the server too).
test("20 tabs at once are all served", { timeout: 150000 }, async () => {
    const context = await browser.newContext({ viewport: { width: 1024, height: 700 } });
    const errorsBefore = page.errors.length;
    try {
        const pages = await Promise.all(Array.from({ length: 20 }, () => context.newPage()));
        for (const tab of pages) {
            tab.errors = [];
            tab.on("pageerror", (error) => tab.errors.push(error.message));
        }
        await Promise.all(pages.map((tab) => tab.goto(ide.url)));
        await Promise.all(
            pages.map((tab) => waitFor(async () => (await tab.locator(".robot-tab").count()) === 3 && (await tab.locator('[data-testid="page-connection"]').getAttribute("data-state")) === "open", "a tab to connect", 40000)),
        );
        // Each still compiles.
        const last = pages[pages.length - 1];
        await setEditorText(last, PROGRAM.replace("STEP", "undefinedThing"));
        await waitFor(async () => (await compileStatus(last)).kind === "error", "the 20th tab to compile", 30000);
        await setEditorText(last, PROGRAM);
        await waitFor(async () => (await compileStatus(last)).kind === "ok", "the 20th tab to compile again", 30000);
        // The first tab follows: the last text wins everywhere.
        await waitFor(async () => (await editorText(page)) === PROGRAM, "the first tab to show the 20th tab's last text", 30000);
        assert.deepEqual([...page.errors.slice(errorsBefore), ...pages.flatMap((tab) => tab.errors)], []);
    } finally {
        await context.close();
    }
});

test("the saved project is what asebamassloader loads", TIMEOUT, async () => {
    const [download] = await Promise.all([page.waitForEvent("download"), clickButton("Download the project")]);
    const saved = join(folder.path, "saved.aesl");
    await download.saveAs(saved);
    const text = readFileSync(saved, "utf8");
    assert.match(text, /<event size="2" name="ping"\s*\/>/);
    assert.match(text, /<constant value="1" name="STEP"\s*\/>/);
    assert.equal((text.match(/<node /g) ?? []).length, 3);

    // Another program stops the counting (no ir_sensors handler)...
    const idle = join(folder.path, "idle.aseba");
    writeFileSync(idle, "var counter = 0\n");
    await aseba(emulator.port, "load", idle);
    const before = await consoleValues("counter");
    await sleep(300);
    assert.deepEqual(await consoleValues("counter"), before);
    // ... and the reference loader puts the saved project back. As a user
    // deploying a project, the IDE is closed first: `asebamassloader --once`
    // loads again whenever a node announces itself, which any IDE's
    // discovery (LIST_NODES every second, Studio's too) makes them do.
    // It matches nodes by name only: each of the three programs goes to the
    // three robots named e-puck, and the last one stays (all count).
    const idePort = ide.port;
    await ide.stop();
    try {
        const output = await run("asebamassloader", ["--once", saved, `tcp:localhost;${emulator.port}`]);
        assert.equal((output.match(/bytecodes loaded to target e-puck/g) ?? []).length, 9, output);
        await waitFor(async () => {
            const first = await consoleValues("counter");
            await sleep(200);
            const second = await consoleValues("counter");
            return second.length === 3 && second.every((value, i) => value > first[i]);
        }, "the three robots to count again");
    } finally {
        ide = await startIde({ targets: [`tcp:localhost;${emulator.port}`], port: idePort });
        started.push(ide);
    }
    await page.locator('[data-testid="page-connection"][data-state="open"]').waitFor({ timeout: 20000 });
});

test("the page reconnects to a restarted emulator with its text intact", { timeout: 45000 }, async () => {
    const errorsBefore = page.errors.length;
    await selectRobot(page, "0:1");
    const port = emulator.port;
    await emulator.stop();
    await page.locator('.link-state[data-up="false"]').waitFor();
    await waitFor(async () => (await page.locator(".robot-tab.offline").count()) === 3, "three offline tabs");
    // Typing goes on while the robots are away.
    const offlineText = PROGRAM + "# typed while the robots were away\n";
    await setEditorText(page, offlineText);
    emulator = await startEmulator({ robots: 3, port });
    started.push(emulator);
    await page.locator('.link-state[data-up="true"]').waitFor({ timeout: 20000 });
    await waitFor(async () => (await page.locator(".robot-tab.offline").count()) === 0, "the robots to come back", 20000);
    assert.equal(await editorText(page), offlineText);
    await waitFor(async () => (await compileStatus()).kind === "ok", "the text to compile on the robot that came back");
    assert.deepEqual(page.errors.slice(errorsBefore), []);
});

test("the page reconnects to a restarted IDE server and gives it back its text", { timeout: 45000 }, async () => {
    const errorsBefore = page.errors.length;
    const port = ide.port;
    await ide.stop();
    await page.locator('[data-testid="page-connection"][data-state="waiting"]').waitFor();
    const keptText = PROGRAM + "# typed while the IDE server was away\n";
    await setEditorText(page, keptText);
    ide = await startIde({ targets: [`tcp:localhost;${emulator.port}`], port });
    started.push(ide);
    await page.locator('[data-testid="page-connection"][data-state="open"]').waitFor({ timeout: 20000 });
    assert.equal(await editorText(page), keptText);
    // The definitions came back with the text: it compiles.
    await waitFor(async () => (await compileStatus()).kind === "ok", "the text to compile on the restarted server");
    // A new browser (no local storage) gets the text from the server.
    const fresh = await openIde(browser, ide.url, { robots: 3 });
    await selectRobot(fresh, "0:1");
    await waitFor(async () => (await editorText(fresh)) === keptText, "the new page to show the text the old one sent back");
    await fresh.locator('.bottom-tab[data-pane="constants"]').click();
    await fresh.locator('.definitions-constants .definition-row[data-name="STEP"]').waitFor();
    await fresh.context().close();
    assert.deepEqual(page.errors.slice(errorsBefore), []);
});

test("a hundred robots: each in the network view and in a tab, found by the filter, stopped and run as a group", { timeout: 120000 }, async () => {
    const many = await startEmulator({ robots: 100 });
    started.push(many);
    const manyIde = await startIde({ targets: [`tcp:localhost;${many.port}`] });
    started.push(manyIde);
    const crowd = await openIde(browser, manyIde.url);
    try {
        await waitFor(async () => (await crowd.locator(".network-row").count()) === 100, "a hundred robots in the network view", 60000);
        await waitFor(async () => (await crowd.locator(".robot-tab").count()) === 100, "a hundred robot tabs", 60000);
        const summary = crowd.locator(".network-view .section-summary");
        await waitFor(async () => (await summary.innerText()) === "100 online · 100 running", "every robot online and running", 60000);
        await crowd.locator(".network-view .panel-filter").fill("57");
        await waitFor(async () => (await crowd.locator(".network-row:visible").count()) === 1, "the filter to keep one robot");
        assert.equal(await crowd.locator(".network-row:visible .network-label").innerText(), "e-puck 57");
        await clickButton("Stop all", crowd);
        await waitFor(async () => (await summary.innerText()) === "100 online · 0 running", "every robot stopped", 30000);
        await clickButton("Run all", crowd);
        await waitFor(async () => (await summary.innerText()) === "100 online · 100 running", "every robot running again", 30000);
        assert.deepEqual(crowd.errors, []);
    } finally {
        await crowd.context().close();
        await manyIde.stop();
        await many.stop();
    }
});

test("the arena view shows the simulated robots live: they move, and a LED set in the page lights there", { timeout: 60000 }, async () => {
    const arena = await startEmulator({ robots: 2, arena: "default" });
    started.push(arena);
    const arenaIde = await startIde({ targets: [`tcp:localhost;${arena.port}`], arenaFeed: arena.feedPort });
    started.push(arenaIde);
    const viewer = await openIde(browser, arenaIde.url, { robots: 2 });
    try {
        await viewer.locator(".arena-view canvas").waitFor();
        const state = () => viewer.evaluate(() => window.asebaIde.model.arenaState);
        await waitFor(async () => (await state())?.robots?.length === 2, "two robots in the arena view", 20000);
        const geometry = await viewer.evaluate(() => window.asebaIde.model.arena);
        assert.deepEqual([geometry.width, geometry.height, geometry.areas.length], [100, 100, 3]); // docs/arena-format.md, the default arena
        // The robots move: a wheel speed set from the page turns into positions.
        const before = (await state()).robots.find((robot) => robot.id === 1);
        await aseba(arena.port, "vars", "leftSpeed=500", "rightSpeed=500", "leds=0,0,1,0,0,0,0,0");
        await waitFor(async () => {
            const now = (await state()).robots.find((robot) => robot.id === 1);
            return Math.hypot(now.x - before.x, now.y - before.y) > 1 && now.leds[2] === 1;
        }, "robot 1 to move and light its LED 2 in the arena view", 20000);
        assert.deepEqual(viewer.errors, []);
    } finally {
        await viewer.context().close();
        await arenaIde.stop();
        await arena.stop();
    }
});

test("the server and the emulators stop cleanly, with no sanitizer report", TIMEOUT, async () => {
    await ide.stop();
    await emulator.stop();
    for (const child of started) {
        assert.doesNotMatch(child.output, /AddressSanitizer|LeakSanitizer|runtime error:/, `${child.name} ${child.args.join(" ")}`);
        assert.ok(child.exitCode === 0 || child.exitCode === "SIGTERM", `${child.name} ended with ${child.exitCode}: ${child.output.slice(-1000)}`);
    }
});
