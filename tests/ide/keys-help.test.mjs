// Aseba Studio's keys (its Debug and Edit menus, 1.6: F7 Load all, F8 Reset
// all, F9 Run all, F10 Pause all, Ctrl+B a breakpoint, Ctrl+D and
// Ctrl+Shift+D comments), clearing the breakpoints, the help (F1) with the
// keys, the language and the robot's own description, and the e-puck's
// camera line. The robots' answers come from the console (`aseba`).

import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { writeFileSync } from "node:fs";
import { join } from "node:path";
import { startSession, stopSession, openIde, setEditorText, editorText, selectRobot, waitFor, sleep, aseba, temporaryFolder } from "./harness.mjs";

const TIMEOUT = { timeout: 30000 };

const PROGRAM = `var counter = 0

onevent ir_sensors
    counter = counter + 1
    leds[0] = counter % 2
`;
const COUNT_LINE = 4;

let emulator;
let ide;
let browser;
let page;
let folder;
let programFile;

before(async () => {
    folder = temporaryFolder();
    programFile = join(folder.path, "program.aesl");
    const xml = PROGRAM.replaceAll("<", "&lt;");
    writeFileSync(programFile, `<!DOCTYPE aesl-source>\n<network>\n<node nodeId="1" name="e-puck">${xml}</node>\n</network>\n`);
    ({ emulator, ide, browser } = await startSession({ robots: 2 }));
});

after(async () => {
    await stopSession({ emulator, ide, browser });
    folder?.remove();
});

async function counters() {
    const output = await aseba(emulator.port, "-p", programFile, "vars", "counter");
    return [...output.matchAll(/counter = (-?\d+)/g)].map((match) => Number(match[1]));
}

// The robots' own states, as `aseba nodes` asks them.
async function ownStates() {
    const output = await aseba(emulator.port, "nodes");
    return [...output.matchAll(/; (running|stepping|stopped)$/gm)].map((match) => match[1]);
}

async function counting() {
    const first = await counters();
    await sleep(250);
    const second = await counters();
    return first.length === 2 && first.every((value, i) => second[i] > value);
}

// The lines of the script shown that carry a breakpoint.
function breakpointLines() {
    return page.evaluate(() => window.asebaIde.robotPanel.session.breakpointLines());
}

function lineOf(selector) {
    return page.evaluate((css) => {
        const element = document.querySelector(css);
        if (!element) return 0;
        const view = window.asebaIde.robotPanel.view;
        return view.state.doc.lineAt(view.posAtDOM(element)).number;
    }, selector);
}

test("F7 loads all, F10 pauses all, F9 runs all, F8 resets all, as in Aseba Studio", TIMEOUT, async () => {
    page = await openIde(browser, ide.url, { robots: 2 });
    for (const name of ["0:2", "0:1"]) {
        await selectRobot(page, name);
        await setEditorText(page, PROGRAM);
    }
    await waitFor(async () => (await page.locator('[data-testid="compile-status"]').getAttribute("data-kind")) === "ok", "the program to compile");
    // The keys work with the focus in the editor.
    await page.locator(".cm-content").click();
    await page.keyboard.press("F7");
    await waitFor(async () => (await ownStates()).join() === "running,running" && (await counting()), "both robots to count after F7");

    await page.keyboard.press("F10");
    await waitFor(async () => (await ownStates()).every((state) => state !== "running"), "both robots paused after F10");
    assert.equal(await counting(), false);

    await page.keyboard.press("F9");
    await waitFor(async () => (await ownStates()).join() === "running,running", "both robots running after F9");
    assert.equal(await counting(), true);

    // Reset: each program starts again, stopped at its start until run.
    const before = await counters();
    await page.keyboard.press("F8");
    await waitFor(async () => (await ownStates()).every((state) => state !== "running"), "both robots reset after F8");
    await page.keyboard.press("F9");
    await waitFor(async () => {
        const after = await counters();
        return after.length === 2 && after.every((value, i) => value < before[i]);
    }, "both counters to start again from 0");
    await waitFor(() => counting(), "both robots to count again");
    assert.deepEqual(page.errors, []);
});

test("Ctrl+B sets the breakpoint of the cursor's line and clears it; Clear all breakpoints removes them", TIMEOUT, async () => {
    await selectRobot(page, "0:1");
    await page.evaluate((line) => {
        const view = window.asebaIde.robotPanel.view;
        view.dispatch({ selection: { anchor: view.state.doc.line(line).from + 4 } });
        view.focus();
    }, COUNT_LINE);
    await page.keyboard.press("Control+b");
    await page.locator(".cm-breakpoint-set").waitFor();
    assert.deepEqual(await breakpointLines(), [COUNT_LINE]);
    await waitFor(async () => (await ownStates())[0] === "stepping", "robot 1 to stop at the breakpoint");
    await waitFor(async () => (await lineOf(".cm-execution-line")) === COUNT_LINE, "the execution line");
    // Ctrl+B again takes it away; robot 2 was never stopped.
    await page.keyboard.press("Control+b");
    await waitFor(async () => (await page.locator(".cm-breakpoint").count()) === 0, "the breakpoint to go");
    assert.equal((await ownStates())[1], "running");

    // Two breakpoints, then Clear all breakpoints: the robot runs through.
    await page.keyboard.press("Control+b");
    await page.evaluate(() => {
        const view = window.asebaIde.robotPanel.view;
        view.dispatch({ selection: { anchor: view.state.doc.line(5).from } });
    });
    await page.keyboard.press("Control+b");
    await waitFor(async () => (await page.locator(".cm-breakpoint-set").count()) === 2, "two breakpoints set");
    assert.deepEqual(await breakpointLines(), [COUNT_LINE, 5]);
    await page.locator('button[aria-label="Clear all breakpoints of this script"]').click();
    await waitFor(async () => (await page.locator(".cm-breakpoint").count()) === 0, "no breakpoint left");
    await page.locator(".robot-toolbar button.robot-run").click();
    await waitFor(async () => (await ownStates()).join() === "running,running" && (await counting()), "both robots to count again");
});

test("Ctrl+D comments the selected lines and Ctrl+Shift+D uncomments them", TIMEOUT, async () => {
    const lines = PROGRAM.split("\n");
    // Lines 3 to 5 selected, from the middle of 3 to the middle of 5.
    await page.evaluate(() => {
        const view = window.asebaIde.robotPanel.view;
        const doc = view.state.doc;
        view.dispatch({ selection: { anchor: doc.line(3).from + 3, head: doc.line(5).from + 6 } });
        view.focus();
    });
    await page.keyboard.press("Control+d");
    const commented = lines.map((line, i) => (i >= 2 && i <= 4 ? `#${line}` : line)).join("\n");
    assert.equal(await editorText(page), commented);
    await page.keyboard.press("Control+Shift+D");
    assert.equal(await editorText(page), PROGRAM);
    // The selection still covers the lines: a second Ctrl+Shift+D finds no # and changes nothing.
    await page.keyboard.press("Control+Shift+D");
    assert.equal(await editorText(page), PROGRAM);
});

test("F1 opens the help on the keys; the top bar's Help too; Escape closes it", TIMEOUT, async () => {
    const help = page.locator('aside[aria-label="Help"]');
    assert.equal(await help.isVisible(), false);
    await page.keyboard.press("F1");
    await help.waitFor();
    const keys = await help.locator(".help-keys tr").evaluateAll((rows) => rows.map((row) => [row.querySelector("kbd").textContent, row.querySelector("td").textContent]));
    const keyOf = Object.fromEntries(keys);
    for (const [key, what] of [
        ["F7", /^Load all/],
        ["F8", /^Reset all/],
        ["F9", /^Run all/],
        ["F10", /^Pause all/],
        ["Ctrl+B", /breakpoint/],
        ["Ctrl+D", /^Comment/],
        ["Ctrl+Shift+D", /^Uncomment/],
        ["F1", /help/],
    ])
        assert.match(keyOf[key] ?? "", what, `${key} in the list of keys`);
    await page.keyboard.press("Escape");
    await help.waitFor({ state: "hidden" });
    await page.locator(".topbar button.help-button").click();
    await help.waitFor();
    await page.keyboard.press("F1");
    await help.waitFor({ state: "hidden" });
});

test("the help's language samples compile on the robot", TIMEOUT, async () => {
    // The global events the samples use.
    await page.locator('.bottom-tab[data-pane="events"]').click();
    for (const name of ["ping", "pong"]) {
        await page.fill('input[aria-label="Name of the new event"]', name);
        await page.fill('input[aria-label="Size of the new event"]', "1");
        await page.locator('button[aria-label^="Add the event"]').click();
        await page.locator(`.definitions-events .definition-row[data-name="${name}"]`).waitFor();
    }
    await page.keyboard.press("F1");
    await page.locator('.help-section-tab[data-section="language"]').click();
    const samples = await page.locator(".help-code").allInnerTexts();
    assert.ok(samples.length >= 6, `${samples.length} samples`);
    // Each sample as a robot's script, after the globals it uses unless it declares its own.
    const globals = "var x\nvar y\nvar a\nvar b\nvar c\nvar i\nvar sum\nvar mask\nvar readings[8]\n";
    const status = page.locator('[data-testid="compile-status"]');
    for (const sample of samples) {
        const source = `${sample.startsWith("var ") ? "" : globals}${sample}\n`;
        await setEditorText(page, source);
        // The result shown is this text's once the server compiled it.
        await waitFor(() => page.evaluate(() => {
            const session = window.asebaIde.robotPanel.session;
            return session.compiledText === session.text();
        }), "the sample's compile result");
        assert.equal(await status.getAttribute("data-kind"), "ok", `${source}→ ${await status.innerText()}`);
    }
    await setEditorText(page, PROGRAM);
    await page.keyboard.press("Escape");
});

test("the help lists the robot's variables, local events and native functions as it describes them", TIMEOUT, async () => {
    await page.keyboard.press("F1");
    await page.locator('.help-section-tab[data-section="robot"]').click();
    const help = page.locator('aside[aria-label="Help"]');
    await help.locator(".help-variables").waitFor();
    const described = await aseba(emulator.port, "-n", "1", "nodes", "--describe");
    const expectedVariables = /variables: (.*)$/m.exec(described)[1].trim().split(" ");
    const expectedEvents = /local events: (.*)$/m.exec(described)[1].trim().split(" ");
    const expectedNatives = described
        .split("native functions:\n")[1]
        .split("\n")
        .map((line) => line.trim())
        .filter(Boolean);
    assert.deepEqual(await help.locator(".help-variables th").allInnerTexts(), expectedVariables);
    assert.deepEqual(
        (await help.locator(".help-events dt").allInnerTexts()).map((text) => text.replace(/^onevent /, "")),
        expectedEvents,
    );
    assert.deepEqual(
        (await help.locator(".help-natives dt").allInnerTexts()).map((text) => text.replace(/^call /, "")),
        expectedNatives,
    );
    await page.keyboard.press("Escape");
});

test("the camera line is drawn live from camR, camG and camB", TIMEOUT, async () => {
    await selectRobot(page, "0:1");
    const strip = page.locator(".camera-strip canvas");
    await strip.waitFor();
    // Left half red, right half green, the last pixel also blue; full scale
    // is 93 for red and blue, 94 for green (the e-puck's camera driver).
    const red = Array.from({ length: 60 }, (_, i) => (i < 30 ? 93 : 0));
    const green = Array.from({ length: 60 }, (_, i) => (i < 30 ? 0 : 94));
    const blue = Array.from({ length: 60 }, (_, i) => (i === 59 ? 93 : 0));
    await aseba(emulator.port, "-n", "1", "vars", `camR=${red}`, `camG=${green}`, `camB=${blue}`);
    const pixel = (x) => strip.evaluate((canvas, at) => [...canvas.getContext("2d").getImageData(at, 0, 1, 1).data], x);
    await waitFor(async () => JSON.stringify(await pixel(0)) === "[255,0,0,255]", "the first pixel red");
    assert.deepEqual(await pixel(29), [255, 0, 0, 255]);
    assert.deepEqual(await pixel(30), [0, 255, 0, 255]);
    assert.deepEqual(await pixel(59), [0, 255, 255, 255]);
    // Half of the scale is half of the intensity.
    await aseba(emulator.port, "-n", "1", "vars", "camR=46");
    await waitFor(async () => (await pixel(0))[0] === Math.round((46 * 255) / 93), "the first pixel half red");
    assert.deepEqual(page.errors, []);
});
