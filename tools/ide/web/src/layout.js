// Resizable parts of the page: a handle between two panes that the user
// drags (or moves with the arrow keys); the size is remembered.

import { h } from "./dom.js";
import { loadSetting, saveSetting } from "./storage.js";

// `target`: the element whose size the handle sets; `axis`: "x" (width)
// or "y" (height); `direction`: +1 when dragging right/down grows it, -1
// when it shrinks it.
export function splitter({ target, axis, direction = 1, min, max, setting, initial, label }) {
    const property = axis === "x" ? "width" : "height";
    const apply = (size) => {
        const limit = typeof max === "function" ? max() : max;
        const clamped = Math.round(Math.max(min, Math.min(limit, size)));
        target.style[property] = `${clamped}px`;
        return clamped;
    };
    let size = apply(loadSetting(setting, initial));
    const handle = h("div", {
        class: `splitter splitter-${axis}`,
        tabIndex: 0,
        label,
        attrs: { role: "separator", "aria-orientation": axis === "x" ? "vertical" : "horizontal" },
    });
    handle.addEventListener("pointerdown", (event) => {
        event.preventDefault();
        handle.setPointerCapture(event.pointerId);
        const start = axis === "x" ? event.clientX : event.clientY;
        const startSize = target.getBoundingClientRect()[property];
        const move = (moveEvent) => {
            const delta = (axis === "x" ? moveEvent.clientX : moveEvent.clientY) - start;
            size = apply(startSize + direction * delta);
        };
        const up = () => {
            handle.removeEventListener("pointermove", move);
            handle.removeEventListener("pointerup", up);
            saveSetting(setting, size);
        };
        handle.addEventListener("pointermove", move);
        handle.addEventListener("pointerup", up);
    });
    handle.addEventListener("keydown", (event) => {
        const keys = axis === "x" ? { ArrowLeft: -1, ArrowRight: 1 } : { ArrowUp: -1, ArrowDown: 1 };
        if (!(event.key in keys)) return;
        event.preventDefault();
        size = apply(size + direction * keys[event.key] * 24);
        saveSetting(setting, size);
    });
    window.addEventListener("resize", () => apply(size));
    return handle;
}
