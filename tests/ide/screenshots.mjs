// Takes the IDE's screenshots for the documentation: six e-pucks of the
// default arena running the paper's controller, loaded from the page.
// Usage: node tests/ide/screenshots.mjs [OUTDIR]   (default docs/)
// Prints one line per picture, and "N passed, N failed" at the end, as the
// tests do.

import { join, resolve } from "node:path";
import { ROOT, waitFor, sleep } from "./harness.mjs";
import { paperSession, loadAllAndWait, ROBOTS } from "./paper-session.mjs";

const outdir = resolve(process.argv[2] ?? join(ROOT, "docs"));
let passed = 0;
let failed = 0;

async function shoot(name, take) {
    const path = join(outdir, `ide-${name}.png`);
    try {
        await take(path);
        console.log(`ide-${name}.png: written to ${path}`);
        passed++;
    } catch (error) {
        console.log(`ide-${name}.png: FAILED: ${error.message}`);
        failed++;
    }
}

const session = await paperSession({ settings: { "bottom-height": 330 } });
const { page } = session;
try {
    await loadAllAndWait(page);
    // The robots drive about; their alarms ("bad") come when one is knocked
    // on red, and this IDE sends one of its own.
    await page.locator('.bottom-tab[data-pane="events"]').click();
    await page.selectOption('select[aria-label="Event to send"]', "bad");
    await page.fill('input[aria-label="Arguments of the event"]', "0");
    await page.locator('button[aria-label="Send the event"]').click();
    await waitFor(async () => (await page.locator(".monitor-row").count()) >= 4, "events in the monitor", 90000, 500).catch(() => {});

    // Plot two robots' wheel speeds and an alarm's colour.
    await page.locator('.bottom-tab[data-pane="plot"]').click();
    for (const [robot, source, index] of [
        ["0:1", "variable:leftSpeed", 0],
        ["0:2", "variable:leftSpeed", 0],
        ["0:3", "variable:prox", 0],
    ]) {
        await page.selectOption('select[aria-label="Robot of the new series"]', robot);
        await page.selectOption('select[aria-label="Variable or event of the new series"]', source);
        await page.fill('input[aria-label="Index in the variable or argument of the event"]', String(index));
        await page.locator('button[aria-label="Add the series to the plot"]').click();
    }
    await page.locator('.segment[data-seconds="30"]').click();
    await sleep(12000);

    // The editor of robot 1 with its variables, an array open.
    await page.locator('.robot-tab[data-robot="0:1"]').click();
    await page.locator('.array-toggle[aria-label="Open the array badness"]').click();
    await page.locator('.bottom-tab[data-pane="events"]').click();
    await sleep(500);

    await shoot("overview", (path) => page.screenshot({ path }));
    await shoot("editor", (path) => page.locator(".robot-panel").screenshot({ path }));
    await shoot("network", (path) => page.locator(".network-view").screenshot({ path }));
    await shoot("arena", (path) => page.locator(".arena-view").screenshot({ path }));
    await shoot("monitor", (path) => page.locator(".bottom-panel").screenshot({ path }));
    // The plot enlarged over the editor, as one studies it.
    await page.locator('.bottom-tab[data-pane="plot"]').click();
    await page.locator(".bottom-size").click();
    await sleep(600);
    await shoot("plot", (path) => page.locator(".bottom-panel").screenshot({ path }));
    await page.locator(".bottom-size").click();
    // The help on robot 1's own description.
    await page.keyboard.press("F1");
    await page.locator('.help-section-tab[data-section="robot"]').click();
    await page.locator(".help-variables").waitFor();
    await shoot("help", (path) => page.locator(".help-panel").screenshot({ path }));
    await page.keyboard.press("Escape");
    if (page.errors.length) {
        console.log(`the page reported errors: ${page.errors.join("; ")}`);
        failed++;
    }
} finally {
    await session.close();
}
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
