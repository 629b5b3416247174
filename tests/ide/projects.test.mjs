// New project and Open recent: a project opened from this computer is
// remembered by the browser and opened again from the list; New project
// asks for a second click, then empties the scripts and the definitions of
// every tab. What the server holds is read back as the .aesl it saves.

import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { writeFileSync } from "node:fs";
import { join } from "node:path";
import { startSession, stopSession, openIde, setEditorText, editorText, selectRobot, waitFor, temporaryFolder } from "./harness.mjs";

const TIMEOUT = { timeout: 40000 };
const PROGRAM = "var fromFile = 1\n\nonevent ping\n    fromFile = args[0]\n";

let emulator;
let ide;
let browser;
let folder;
let projectFile;

before(async () => {
    folder = temporaryFolder();
    projectFile = join(folder.path, "small.aesl");
    writeFileSync(projectFile, `<!DOCTYPE aesl-source>\n<network>\n<event size="1" name="ping"/>\n<constant value="3" name="THREE"/>\n<node nodeId="1" name="e-puck">${PROGRAM}</node>\n</network>\n`);
    ({ emulator, ide, browser } = await startSession({ robots: 2 }));
});

after(async () => {
    await stopSession({ emulator, ide, browser });
    folder?.remove();
});

// The project as the server would save it.
function savedProject(page) {
    return page.evaluate(async () => (await window.asebaIde.connection.request({ type: "save-project", toServerFile: false })).content);
}

test("a project opened, emptied by New project (at the second click), opened again from the recent ones", TIMEOUT, async () => {
    const page = await openIde(browser, ide.url, { robots: 2 });
    await selectRobot(page, "0:2");
    await setEditorText(page, "var typedHere = 2\n");
    await selectRobot(page, "0:1");

    const [chooser] = await Promise.all([page.waitForEvent("filechooser"), page.locator('button[aria-label^="Open project"]').click()]);
    await chooser.setFiles(projectFile);
    await waitFor(async () => (await editorText(page)) === PROGRAM, "robot 1 to get the project's program");
    await page.locator('.definitions-events .definition-row[data-name="ping"]').waitFor();

    // New project: the first click only says what the second would do.
    await page.locator('button[aria-label^="New project"]').click();
    await page.locator(".message-warning", { hasText: "Click New again to go on" }).waitFor();
    assert.equal(await editorText(page), PROGRAM);
    await page.locator('button[aria-label^="New project"]').click();
    await page.locator(".message-success", { hasText: "New project: every script is empty" }).waitFor();
    await waitFor(async () => (await editorText(page)) === "", "robot 1's script emptied");
    await selectRobot(page, "0:2");
    assert.equal(await editorText(page), "");
    await waitFor(async () => {
        const saved = await savedProject(page);
        return !/<event |<constant |fromFile|typedHere/.test(saved) && saved;
    }, "the server's project to be empty");

    // Open recent: the file, as opened, from this browser's list; after a reload too.
    await page.reload();
    await page.locator('[data-testid="page-connection"][data-state="open"]').waitFor();
    await page.locator("button.recent-button").click();
    const entries = page.locator(".recent-menu .recent-entry");
    assert.deepEqual(await entries.allInnerTexts(), ["small.aesl"]);
    await entries.first().click();
    await selectRobot(page, "0:1");
    await waitFor(async () => (await editorText(page)) === PROGRAM, "robot 1's program back from the recent project");
    const saved = await savedProject(page);
    assert.match(saved, /<event size="1" name="ping"\s*\/>/);
    assert.match(saved, /<constant value="3" name="THREE"\s*\/>/);
    assert.deepEqual(page.errors, []);
    await page.context().close();
});
