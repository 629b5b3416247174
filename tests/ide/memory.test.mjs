// A robot's memory exported to a file and imported back: the values in the
// file are those the robot holds (read by the console, `aseba vars`), and
// importing the file writes them back to the robot.

import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { startSession, stopSession, openIde, setEditorText, waitFor, aseba, temporaryFolder } from "./harness.mjs";

const TIMEOUT = { timeout: 40000 };
const PROGRAM = "var gains[3]\nvar offset = 0\n";

let emulator;
let ide;
let browser;
let folder;
let programFile;

before(async () => {
    folder = temporaryFolder();
    programFile = join(folder.path, "program.aesl");
    writeFileSync(programFile, `<!DOCTYPE aesl-source>\n<network>\n<node nodeId="1" name="e-puck">${PROGRAM}</node>\n</network>\n`);
    ({ emulator, ide, browser } = await startSession({ robots: 1 }));
});

after(async () => {
    await stopSession({ emulator, ide, browser });
    folder?.remove();
});

async function consoleValues(...names) {
    const output = await aseba(emulator.port, "-p", programFile, "vars", ...names);
    return Object.fromEntries(names.map((name) => [name, new RegExp(`^${name} = (.*)$`, "m").exec(output)?.[1]]));
}

test("a robot's memory goes to a file and back", TIMEOUT, async () => {
    const page = await openIde(browser, ide.url, { robots: 1 });
    await setEditorText(page, PROGRAM);
    await waitFor(async () => (await page.locator('[data-testid="compile-status"]').getAttribute("data-kind")) === "ok", "the program to compile");
    await page.locator(".robot-toolbar button.robot-load").click();
    await page.locator('.variable-value[data-variable="offset"]').waitFor();
    await aseba(emulator.port, "-p", programFile, "vars", "gains=10,-20,30000", "offset=-5");
    await waitFor(async () => (await page.locator('.variable-value[data-variable="offset"]').innerText()) === "-5", "the page to read offset = -5");

    const [download] = await Promise.all([page.waitForEvent("download"), page.locator("button.memory-export").click()]);
    const saved = join(folder.path, download.suggestedFilename());
    await download.saveAs(saved);
    assert.equal(download.suggestedFilename(), "e-puck-1-memory.json");
    const file = JSON.parse(readFileSync(saved, "utf8"));
    const valuesOf = Object.fromEntries(file.variables.map((variable) => [variable.name, variable.values]));
    assert.deepEqual(valuesOf.gains, [10, -20, 30000]);
    assert.deepEqual(valuesOf.offset, [-5]);
    // The robot's own variables too, as it describes them.
    assert.equal(valuesOf.prox.length, 8);
    assert.equal(valuesOf.camR.length, 60);

    await aseba(emulator.port, "-p", programFile, "vars", "gains=0,0,0", "offset=0");
    assert.deepEqual(await consoleValues("gains", "offset"), { gains: "0 0 0", offset: "0" });
    const [chooser] = await Promise.all([page.waitForEvent("filechooser"), page.locator("button.memory-import").click()]);
    await chooser.setFiles(saved);
    await page.locator(".message-success", { hasText: /\d+ variables of e-puck-1-memory\.json written to e-puck 1\./ }).waitFor();
    await waitFor(async () => JSON.stringify(await consoleValues("gains", "offset")) === JSON.stringify({ gains: "10 -20 30000", offset: "-5" }), "the console to read the imported values");

    // A file that is not one: said, nothing written.
    const other = join(folder.path, "other.json");
    writeFileSync(other, '{"hello": 1}');
    const [again] = await Promise.all([page.waitForEvent("filechooser"), page.locator("button.memory-import").click()]);
    await again.setFiles(other);
    await page.locator(".message-error", { hasText: "other.json not imported: it is not a robot's memory saved by this IDE." }).waitFor();
    assert.deepEqual(page.errors, []);
    await page.context().close();
});
