// The state the page shows for a robot is the robot's own, whatever stopped
// it: a run-time error, a breakpoint, the end of an event stepped through,
// Stop, a reboot. Each is read where the user sees it (the robot's tab, the
// header of its panel, the network view, and again after a reload) and
// checked against the robot itself, asked by the console (`aseba nodes`).

import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { startSession, stopSession, openIde, setEditorText, selectRobot, waitFor, aseba } from "./harness.mjs";

const TIMEOUT = { timeout: 30000 };

// A ping divides by its argument: `ping 0` is a division by zero.
const PROGRAM = `var pings = 0
var quotient = 0

onevent ping
    pings = pings + 1
    quotient = 100 / args[0]
`;
const COUNT_LINE = 5;
const DIVISION_LINE = 6;

let emulator;
let ide;
let browser;
let page;

before(async () => {
    ({ emulator, ide, browser } = await startSession({ robots: 2 }));
});

after(async () => {
    await stopSession({ emulator, ide, browser });
});

// What the robot says of itself: "running", "stepping" or "stopped"
// (`aseba nodes` asks it).
async function robotsOwnState(node) {
    const output = await aseba(emulator.port, "-n", String(node), "nodes");
    const match = /; (running|stepping|stopped)$/m.exec(output);
    assert.ok(match, `a state in: ${output}`);
    return match[1];
}

// The state shown for `name` in its tab, its panel's header and its row of
// the network view (the panel shows the robot selected).
function shownStates(target, name) {
    return target.evaluate((robot) => {
        const tab = document.querySelector(`.robot-tab[data-robot="${robot}"]`);
        const header = document.querySelector('[data-testid="robot-state"]');
        const row = document.querySelector(`.network-row[data-robot="${robot}"]`);
        return {
            tab: tab?.dataset.state,
            header: header?.dataset.state,
            headerText: header?.textContent,
            network: row?.dataset.state,
            networkText: row?.querySelector(".network-state")?.textContent,
        };
    }, name);
}

const TEXT = { running: "running", stopped: "stopped", stepping: "stopped in an event" };

// Waits until every view shows `state` for robot `name`; the header only
// when it is the robot shown.
async function waitForShown(target, name, state, why, { shownInPanel = true } = {}) {
    const expected = { tab: state, network: state, networkText: TEXT[state] };
    if (shownInPanel) Object.assign(expected, { header: state, headerText: TEXT[state] });
    await waitFor(async () => {
        const shown = await shownStates(target, name);
        return Object.entries(expected).every(([view, value]) => shown[view] === value) && shown;
    }, `${name} shown ${state} everywhere (${why})`, 10000);
}

async function sendPing(argument) {
    await page.selectOption('select[aria-label="Event to send"]', "ping");
    await page.fill('input[aria-label="Arguments of the event"]', String(argument));
    await page.locator('button[aria-label="Send the event"]').click();
}

async function clickRobotButton(action) {
    await page.locator(`.robot-toolbar button.robot-${action}`).click();
}

function executionLine() {
    return page.evaluate(() => {
        const element = document.querySelector(".cm-execution-line");
        if (!element) return 0;
        const view = window.asebaIde.robotPanel.view;
        return view.state.doc.lineAt(view.posAtDOM(element)).number;
    });
}

async function loadProgram() {
    await setEditorText(page, PROGRAM);
    await waitFor(async () => (await page.locator('[data-testid="compile-status"]').getAttribute("data-kind")) === "ok", "the program to compile");
    await clickRobotButton("load");
    await waitForShown(page, "0:1", "running", "after the load");
    assert.equal(await robotsOwnState(1), "running");
}

test("a robot that runs its program is shown running", TIMEOUT, async () => {
    page = await openIde(browser, ide.url, { robots: 2 });
    await page.locator('.bottom-tab[data-pane="events"]').click();
    await page.fill('input[aria-label="Name of the new event"]', "ping");
    await page.fill('input[aria-label="Size of the new event"]', "1");
    await page.locator('button[aria-label^="Add the event"]').click();
    await page.locator('.definitions-events .definition-row[data-name="ping"]').waitFor();
    await selectRobot(page, "0:1");
    await loadProgram();
});

test("a run-time error stops the robot: stopped in its tab, its header, the network view, and after a reload", TIMEOUT, async () => {
    await sendPing(0);
    await page.locator(".runtime-status", { hasText: `line ${DIVISION_LINE}: division by zero` }).waitFor();
    await waitForShown(page, "0:1", "stopped", "after the division by zero");
    assert.equal(await robotsOwnState(1), "stopped");
    assert.equal(await page.locator(".network-view .section-summary").innerText(), "2 online · 1 running");
    // Not at a line: no event is under way.
    assert.equal(await executionLine(), 0);

    await page.reload();
    await page.locator('[data-testid="page-connection"][data-state="open"]').waitFor();
    await waitFor(async () => (await page.locator(".robot-tab").count()) === 2, "two tabs after the reload");
    await selectRobot(page, "0:1");
    await waitForShown(page, "0:1", "stopped", "after a reload");
    assert.equal(await robotsOwnState(1), "stopped");
});

test("a reboot: the robot runs again, and the page says so", TIMEOUT, async () => {
    await clickRobotButton("reboot");
    await page.locator(".message-success", { hasText: "Rebooting e-puck 1." }).waitFor();
    await waitForShown(page, "0:1", "running", "after the reboot");
    assert.equal(await robotsOwnState(1), "running");
    // It runs what its flash holds (nothing): the page no longer says loaded.
    assert.equal(await page.locator(".program-status").innerText(), "");
});

test("a breakpoint stops the robot in its event; stepping past the event's end leaves it stopped", TIMEOUT, async () => {
    await page.locator('.bottom-tab[data-pane="events"]').click();
    await loadProgram();
    await clickGutter(COUNT_LINE);
    await page.locator(".cm-breakpoint-set").waitFor();
    await sendPing(1);
    await waitForShown(page, "0:1", "stepping", "at the breakpoint");
    assert.equal(await robotsOwnState(1), "stepping");
    assert.equal(await executionLine(), COUNT_LINE);

    await clickRobotButton("step");
    await waitFor(async () => (await executionLine()) === DIVISION_LINE, `the execution line ${DIVISION_LINE}`);
    await waitForShown(page, "0:1", "stepping", "after a step");
    // The last line stepped: the event is over, the robot waits stopped.
    await clickRobotButton("step");
    await waitForShown(page, "0:1", "stopped", "after the event's end");
    assert.equal(await robotsOwnState(1), "stopped");
    assert.equal(await executionLine(), 0);

    await clickGutter(COUNT_LINE);
    await waitFor(async () => (await page.locator(".cm-breakpoint").count()) === 0, "the breakpoint to go");
    await clickRobotButton("run");
    await waitForShown(page, "0:1", "running", "after Run");
    assert.equal(await robotsOwnState(1), "running");
});

test("Stop stops the robot, Run runs it again", TIMEOUT, async () => {
    await clickRobotButton("stop");
    await waitForShown(page, "0:1", "stopped", "after Stop");
    assert.equal(await robotsOwnState(1), "stopped");
    // The other robot was not touched.
    await waitForShown(page, "0:2", "running", "robot 2 after robot 1's Stop", { shownInPanel: false });
    await clickRobotButton("run");
    await waitForShown(page, "0:1", "running", "after Run");
    assert.equal(await robotsOwnState(1), "running");
    assert.deepEqual(page.errors, []);
});

async function clickGutter(line) {
    const point = await page.evaluate((number) => {
        const view = window.asebaIde.robotPanel.view;
        const block = view.lineBlockAt(view.state.doc.line(number).from);
        const gutter = document.querySelector(".cm-breakpoint-gutter").getBoundingClientRect();
        return { x: gutter.left + gutter.width / 2, y: view.documentTop + block.top + block.height / 2 };
    }, line);
    await page.mouse.click(point.x, point.y);
}
