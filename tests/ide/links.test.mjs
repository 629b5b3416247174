// A network the IDE cannot reach: said in the terminal that started it and
// on the page, once and in full; the group's buttons wait for a robot; the
// network that comes back is said too.

import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { startEmulator, startIde, launchBrowser, openIde, freePort, waitFor, sleep } from "./harness.mjs";

const TIMEOUT = { timeout: 40000 };
// RFC 6761: no name under .invalid resolves.
const NOWHERE = "tcp:nowhere.invalid;1";

let browser;
const started = [];

before(async () => {
    browser = await launchBrowser();
});

after(async () => {
    await browser?.close();
    for (const child of started.reverse()) await child.stop();
});

function occurrences(text, part) {
    return text.split(part).length - 1;
}

// Whether an element's text is shown whole: nothing clipped.
function shownWhole(page, selector) {
    return page.locator(selector).evaluate((element) => element.scrollWidth <= element.clientWidth && element.scrollHeight <= element.clientHeight);
}

test("a target that cannot be resolved is said in the terminal and on the page, in full, its target once", TIMEOUT, async () => {
    const ide = await startIde({ targets: [NOWHERE] });
    started.push(ide);
    // The resolver's own words vary; what failed and where does not.
    const said = new RegExp(`^aseba-ide: ${NOWHERE.replace(/[.;]/g, "\\$&")}: (cannot resolve 'nowhere\\.invalid'|timed out).* \\(trying again\\)$`, "m");
    await waitFor(() => said.test(ide.output), `the terminal to say why ${NOWHERE} is down`, 15000);

    const page = await openIde(browser, ide.url);
    const problem = page.locator(`.link-problem[data-target="${NOWHERE}"]`);
    await problem.waitFor();
    const text = await problem.innerText();
    assert.match(text, /^tcp:nowhere\.invalid;1 cannot be reached: (cannot resolve 'nowhere\.invalid'|timed out)/);
    assert.equal(occurrences(text, NOWHERE), 1, text);
    assert.ok(await shownWhole(page, `.link-problem[data-target="${NOWHERE}"]`), "the reason is not cut off");
    // The top bar: the target and "unreachable", whole.
    const pill = `.link-state[data-target="${NOWHERE}"]`;
    assert.deepEqual(await page.locator(`${pill} span:not(.dot)`).allInnerTexts(), [NOWHERE, "unreachable"]);
    assert.ok(await shownWhole(page, pill), "the top bar's link state is not cut off");

    // Nothing to load, run or stop: the group's buttons say so.
    for (const action of ["load", "run", "pause", "stop", "reset", "store", "reboot"])
        assert.equal(await page.locator(`.topbar button.group-${action}`).isDisabled(), true, `${action} all is disabled`);

    // The link is tried again, but the terminal says it once.
    await sleep(3000);
    assert.equal(ide.output.match(new RegExp(said.source, "gm")).length, 1, ide.output);
    assert.deepEqual(page.errors, []);
    await page.context().close();
});

test("a target that refuses is said; when its robots come, the link is said up and Load all is enabled", TIMEOUT, async () => {
    const port = await freePort();
    const target = `tcp:127.0.0.1;${port}`;
    const ide = await startIde({ targets: [target] });
    started.push(ide);
    await waitFor(() => ide.output.includes(`aseba-ide: ${target}: `) && /refused/i.test(ide.output), "the terminal to say the connection is refused", 15000);
    const page = await openIde(browser, ide.url);
    await page.locator(`.link-problem[data-target="${target}"]`, { hasText: /refused/i }).waitFor();
    assert.equal(await page.locator(".topbar button.group-load").isDisabled(), true);

    const emulator = await startEmulator({ robots: 2, port });
    started.push(emulator);
    await waitFor(() => ide.output.includes(`aseba-ide: ${target}: connected`), "the terminal to say the link is up", 20000);
    await page.locator(`.link-state[data-target="${target}"][data-up="true"]`).waitFor({ timeout: 20000 });
    await waitFor(async () => (await page.locator(".robot-tab").count()) === 2, "two robots");
    await waitFor(async () => !(await page.locator(".topbar button.group-load").isDisabled()), "Load all to be enabled");
    assert.equal(await page.locator(".link-problem").count(), 0);
    assert.deepEqual(page.errors, []);
    await page.context().close();
});
