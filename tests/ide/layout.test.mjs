// The page's layout at 1280×800 and 1920×1080 with a hundred simulated
// e-pucks in the arena: the robot filter keeps its size, placeholders and
// chosen options are not cut, a hovered primary button stays one, the plot
// has room and can be enlarged, the arena view can be enlarged and then
// labels every robot, error messages go by themselves without covering the
// bottom panel. IDE_LAYOUT_SHOTS=FOLDER also saves what each check saw.

import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { join } from "node:path";
import { startSession, stopSession, openIde, waitFor, sleep } from "./harness.mjs";

const ROBOTS = 100;
const SIZES = [
    [1280, 800],
    [1920, 1080],
];

let emulator;
let ide;
let browser;

before(async () => {
    ({ emulator, ide, browser } = await startSession({ robots: ROBOTS, arena: true }));
});

after(async () => {
    await stopSession({ emulator, ide, browser });
});

async function shot(page, name) {
    if (process.env.IDE_LAYOUT_SHOTS) await page.screenshot({ path: join(process.env.IDE_LAYOUT_SHOTS, `${name}.png`) });
}

function box(page, selector) {
    return page.locator(selector).first().evaluate((element) => {
        const rect = element.getBoundingClientRect();
        return { left: rect.left, top: rect.top, right: rect.right, bottom: rect.bottom, width: rect.width, height: rect.height };
    });
}

// Inputs whose placeholder is cut, and selects whose chosen option is,
// among those shown: [description].
function cutTexts(page) {
    return page.evaluate(() => {
        const measure = document.createElement("canvas").getContext("2d");
        const room = (element, extra) => {
            const style = getComputedStyle(element);
            return element.clientWidth - parseFloat(style.paddingLeft) - parseFloat(style.paddingRight) - extra;
        };
        const width = (element, text) => {
            measure.font = getComputedStyle(element).font;
            return measure.measureText(text).width;
        };
        const cut = [];
        for (const input of document.querySelectorAll("input[placeholder]")) {
            if (!input.checkVisibility() || input.value !== "") continue;
            if (width(input, input.placeholder) > room(input, 0) + 0.5) cut.push(`placeholder "${input.placeholder}"`);
        }
        for (const select of document.querySelectorAll("select")) {
            if (!select.checkVisibility() || select.selectedIndex < 0) continue;
            const text = select.options[select.selectedIndex].text;
            // The arrow takes about 20 px.
            if (width(select, text) > room(select, 20) + 0.5) cut.push(`option "${text}" of ${select.getAttribute("aria-label")}`);
        }
        return cut;
    });
}

for (const [width, height] of SIZES) {
    test(`at ${width}×${height} with ${ROBOTS} robots: the filter, the texts, the buttons, the plot, the arena, the messages`, { timeout: 120000 }, async () => {
        const page = await openIde(browser, ide.url, { viewport: { width, height } });
        try {
            await waitFor(async () => (await page.locator(".network-row").count()) === ROBOTS, `${ROBOTS} robots`, 60000);
            await waitFor(() => page.evaluate((count) => window.asebaIde.model.arenaState?.robots?.length === count, ROBOTS), "the arena's robots", 60000);
            await sleep(500);
            await shot(page, `${width}-default`);

            // The filter keeps its size beside a hundred rows; the help's
            // button is in the top bar.
            const filter = await box(page, ".network-view .panel-filter");
            const view = await box(page, ".network-view");
            assert.ok(filter.height >= 26, `the filter's height: ${filter.height}`);
            assert.ok(filter.width >= view.width - 2 * 12, `the filter's width ${filter.width} in ${view.width}`);
            const help = await box(page, ".topbar .help-button");
            assert.ok(help.right <= width && help.width > 0, `Help in the top bar: ${JSON.stringify(help)}`);

            // Texts whole, in every pane of the bottom panel.
            for (const pane of ["events", "plot", "constants"]) {
                await page.locator(`.bottom-tab[data-pane="${pane}"]`).click();
                assert.deepEqual(await cutTexts(page), [], `cut texts with ${pane} shown`);
            }

            // A hovered primary button keeps its colour, darker; a plain one turns grey.
            await page.locator('.bottom-tab[data-pane="events"]').click();
            const send = page.locator('button[aria-label="Send the event"]');
            const resting = await send.evaluate((element) => getComputedStyle(element).backgroundColor);
            await send.hover();
            await sleep(200);
            const hovered = await send.evaluate((element) => getComputedStyle(element).backgroundColor);
            const plain = page.locator('button[aria-label^="Add the event"]');
            await plain.hover();
            await sleep(200);
            const plainHovered = await plain.evaluate((element) => getComputedStyle(element).backgroundColor);
            // rgb(R, G, B) in 0..255, or color(srgb R G B) in 0..1 (color-mix's).
            const channels = (color) => {
                const values = color.match(/[\d.]+/g).map(Number);
                return color.startsWith("color(srgb") ? values.map((value) => value * 255) : values;
            };
            const [red, green, blue] = channels(hovered);
            assert.notEqual(hovered, plainHovered, "the primary button does not take the plain buttons' hover");
            assert.ok(blue > red + 60 && blue > green, `hovered, still the accent's blue: ${hovered} (resting ${resting})`);
            assert.ok(channels(hovered)[2] < channels(resting)[2] || channels(hovered)[1] < channels(resting)[1], `darker when hovered: ${resting} → ${hovered}`);

            // The plot: room by default, most of the page when enlarged, and the chart follows.
            await page.locator('.bottom-tab[data-pane="plot"]').click();
            await page.selectOption('select[aria-label="Variable or event of the new series"]', "variable:prox");
            await page.locator('button[aria-label^="Add the series"]').click();
            const chartHeight = () => page.evaluate(() => window.asebaIde.bottom.plot.plot?.height ?? 0);
            await waitFor(async () => (await chartHeight()) > 0, "the chart");
            const normal = await chartHeight();
            assert.ok(normal >= 180, `the plot's height by default: ${normal}`);
            await page.locator(".bottom-size").click();
            await waitFor(async () => (await chartHeight()) >= height * 0.6, `the enlarged plot (${await chartHeight()})`);
            await sleep(1500);
            await shot(page, `${width}-plot-enlarged`);
            await page.locator(".bottom-size").click();
            await waitFor(async () => (await chartHeight()) === normal, "the plot back to its height");
            await page.locator('.series-chip button[aria-label^="Remove"]').click();

            // The arena: enlarged, every robot labelled.
            const small = await box(page, ".arena-canvas");
            await page.locator(".arena-size").click();
            await waitFor(async () => (await box(page, ".arena-canvas")).width >= Math.min(width, height) * 0.7, "the enlarged arena");
            await waitFor(() => page.evaluate((count) => window.asebaIde.controller.views.arena.labelsShown === count, ROBOTS), "every robot's label");
            await shot(page, `${width}-arena-enlarged`);
            await page.keyboard.press("Escape");
            await waitFor(async () => Math.abs((await box(page, ".arena-canvas")).width - small.width) < 1, "the arena back in the side panel");

            // Errors: above the bottom panel, three at most, gone by themselves.
            await page.locator('.bottom-tab[data-pane="events"]').click();
            for (let i = 1; i <= 4; i++) await page.evaluate((n) => window.asebaIde.commands.messages.error(`Error number ${n}`), i);
            assert.deepEqual(await page.locator(".message").allInnerTexts(), ["Error number 2", "Error number 3", "Error number 4"]);
            const messages = await box(page, ".message-bar");
            const bottom = await box(page, ".bottom-panel");
            assert.ok(messages.bottom <= bottom.top, `the messages (${messages.bottom}) end above the bottom panel (${bottom.top})`);
            await shot(page, `${width}-messages`);
            await page.locator(".message").first().waitFor({ state: "detached", timeout: 20000 });
            await waitFor(async () => (await page.locator(".message").count()) === 0, "the messages to go", 5000);
            assert.deepEqual(page.errors, []);
        } finally {
            await page.context().close();
        }
    });
}
