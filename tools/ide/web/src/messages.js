// The message bar under the top bar: what the server refused, what a
// command did. Never a modal dialog: errors stay until closed, other
// messages go by themselves.

import { h, iconElement } from "./dom.js";
import { icons } from "./icons.js";

const INFO_DURATION_MS = 4000;
const MAX_MESSAGES = 5;

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
        if (kind !== "error" && kind !== "warning") setTimeout(() => message.remove(), INFO_DURATION_MS);
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
