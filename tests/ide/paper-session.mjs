// The paper's setup in the IDE, for the screenshots and the benchmark: six
// simulated e-pucks in the default arena (with its feed for the arena
// view), the IDE on them, a browser page that opened
// examples/paper-annex.aesl through its Open button.

import { join } from "node:path";
import { ROOT, startEmulator, startIde, launchBrowser, openIde, waitFor } from "./harness.mjs";

export const PAPER_PROJECT = join(ROOT, "examples/paper-annex.aesl");
export const ROBOTS = 6;

// Starts everything; `close()` stops it all.
export async function paperSession({ viewport = { width: 1920, height: 1080 }, settings = {} } = {}) {
    const emulator = await startEmulator({ robots: ROBOTS, arena: "default" });
    const ide = await startIde({ targets: [`tcp:localhost;${emulator.port}`], arenaFeed: emulator.feedPort });
    const browser = await launchBrowser();
    const close = async () => {
        await browser.close();
        await ide.stop();
        await emulator.stop();
    };
    try {
        const page = await openIde(browser, ide.url, { robots: ROBOTS, viewport, settings });
        await waitFor(() => page.evaluate((count) => window.asebaIde.model.readyRobots().length === count, ROBOTS), `${ROBOTS} described robots`, 20000);
        const [chooser] = await Promise.all([page.waitForEvent("filechooser"), page.locator('button[aria-label^="Open project"]').click()]);
        await chooser.setFiles(PAPER_PROJECT);
        // The project has one program, for node 1: every robot gets it.
        await page.locator('.robot-tab[data-robot="0:1"]').click();
        await waitFor(() => page.evaluate(() => window.asebaIde.sessions.get("0:1").text().includes("part A")), "robot 1's program", 10000);
        await page.locator('button[aria-label="Copy this script to every robot\'s editor"]').click();
        await waitFor(
            () => page.evaluate((count) => window.asebaIde.sessions.all().filter((session) => session.text().includes("part A") && session.status.kind === "ok").length === count, ROBOTS),
            "the paper's controller in every editor, compiled",
            20000,
        );
        return { emulator, ide, browser, page, close };
    } catch (error) {
        await close();
        throw error;
    }
}

// Clicks Load all and resolves with the milliseconds, measured in the page,
// from the click to every robot running the program just loaded.
export function loadAllAndWait(page) {
    return page.evaluate(
        ({ count }) =>
            new Promise((resolve, reject) => {
                const { model, sessions } = window.asebaIde;
                const button = document.querySelector('button[aria-label^="Load all"]');
                let start = 0;
                const running = () =>
                    model.readyRobots().filter((robot) => robot.state === "running" && robot.program && robot.program.source === sessions.get(robot.robot).text()).length === count;
                const check = () => {
                    if (running()) resolve(performance.now() - start);
                    else if (performance.now() - start > 20000) reject(new Error("the robots did not all run within 20 s"));
                    else requestAnimationFrame(check);
                };
                button.addEventListener(
                    "click",
                    () => {
                        start = performance.now();
                        requestAnimationFrame(check);
                    },
                    { once: true, capture: true },
                );
                button.click();
            }),
        { count: ROBOTS },
    );
}
