// The message bar, at the right above the bottom panel (whose monitor it
// must not hide): what the server refused, what a command did. Never a modal
// dialog: every message goes by itself, errors and warnings after long
// enough to be read and never while the pointer is on them; at most a few
// at once, the oldest going first.

import { h, iconElement } from "./dom.js";
import { icons } from "./icons.js";

const INFO_DURATION_MS = 4000;
const ERROR_DURATION_MS = 15000;
const MAX_MESSAGES = 3;

export class MessageBar {
    constructor(container) {
        this.element = h("div", { class: "message-bar", attrs: { "aria-live": "polite" } });
        container.append(this.element);
    }

    // kind: "error", "warning", "info" or "success"; `details`: lines shown
    // under the text (e.g. one per robot).
    show(kind, text, details = []) {
        const close = h(
            "button",
            { type: "button", class: "message-close", label: "Dismiss this message", onClick: () => message.remove() },
            iconElement(icons.close),
        );
        const message = h(
            "div",
            { class: `message message-${kind}`, attrs: { role: kind === "error" ? "alert" : "status" } },
            h(
                "div",
                { class: "message-body" },
                h("div", { class: "message-text", text }),
                details.length
                    ? h(
                          "ul",
                          { class: "message-details" },
                          details.map((line) => h("li", { text: line })),
                      )
                    : null,
            ),
            close,
        );
        this.element.append(message);
        while (this.element.children.length > MAX_MESSAGES) this.element.firstElementChild.remove();
        const duration = kind === "error" || kind === "warning" ? ERROR_DURATION_MS : INFO_DURATION_MS;
        let timer = setTimeout(() => message.remove(), duration);
        message.addEventListener("pointerenter", () => clearTimeout(timer));
        message.addEventListener("pointerleave", () => {
            clearTimeout(timer);
            timer = setTimeout(() => message.remove(), INFO_DURATION_MS);
        });
        return message;
    }

    error(text, details) {
        return this.show("error", text, details);
    }

    info(text, details) {
        return this.show("info", text, details);
    }

    success(text, details) {
        return this.show("success", text, details);
    }

    warning(text, details) {
        return this.show("warning", text, details);
    }
}
