// The project's common definitions, edited once for every robot: global
// events (name, size) and constants (name, value); and the form that sends
// a global event with its arguments.

import { h, button, setChildren, iconElement } from "./dom.js";
import { icons } from "./icons.js";
import { parseIntegers } from "./format.js";

const IDENTIFIER = /^[\p{L}_][\p{L}\p{N}_.]*$/u;
// Protocol 5's longest event: 258 words of arguments.
const MAX_EVENT_SIZE = 258;

const KINDS = {
    events: {
        title: "Global events",
        field: "size",
        fieldText: "Size",
        hint: "words of arguments, 0 to 258",
        check: (value) =>
            Number.isInteger(value) && value >= 0 && value <= MAX_EVENT_SIZE
                ? null
                : `an event's size is 0 to ${MAX_EVENT_SIZE} words`,
        empty: "No global events: add one to emit it from a robot or from here.",
        fallback: 0,
    },
    constants: {
        title: "Constants",
        field: "value",
        fieldText: "Value",
        hint: "-32768 to 32767",
        check: (value) =>
            Number.isInteger(value) && value >= -32768 && value <= 32767 ? null : "a constant is -32768 to 32767",
        empty: "No constants: what you add here is known to every robot's script.",
        fallback: 0,
    },
};

// The list of one kind of definition, with its add form.
export class DefinitionList {
    constructor(container, { kind, model, commands, messages }) {
        this.kind = kind;
        this.spec = KINDS[kind];
        this.model = model;
        this.commands = commands;
        this.messages = messages;
        this.list = h("div", { class: "definition-list", attrs: { role: "list", "aria-label": this.spec.title } });
        this.nameInput = h("input", {
            class: "text-input",
            placeholder: "name",
            label: `Name of the new ${kind === "events" ? "event" : "constant"}`,
        });
        this.valueInput = h("input", {
            class: "text-input number",
            type: "number",
            value: "0",
            label: `${this.spec.fieldText} of the new ${kind === "events" ? "event" : "constant"}`,
            title: this.spec.hint,
        });
        const add = (event) => {
            event.preventDefault();
            this.add();
        };
        this.element = h(
            "section",
            { class: `definitions definitions-${kind}` },
            h("h3", { class: "group-title", text: this.spec.title }),
            this.list,
            h(
                "form",
                { class: "definition-form", onSubmit: add },
                this.nameInput,
                this.valueInput,
                h(
                    "button",
                    { type: "submit", class: "button", label: `Add the ${kind === "events" ? "event" : "constant"}` },
                    iconElement(icons.add),
                    h("span", { class: "button-text", text: "Add" }),
                ),
            ),
        );
        container.append(this.element);
        model.on("definitions", () => this.render());
        this.render();
    }

    entries() {
        return this.model.definitions[this.kind] ?? [];
    }

    render() {
        const entries = this.entries();
        setChildren(
            this.list,
            entries.length === 0 ? h("div", { class: "panel-note", text: this.spec.empty }) : null,
            entries.map((entry, index) => {
                const value = h("input", {
                    class: "text-input number",
                    type: "number",
                    value: String(entry[this.spec.field]),
                    label: `${this.spec.fieldText} of ${entry.name}`,
                    title: this.spec.hint,
                    onChange: () => this.change(index, Number(value.value)),
                });
                return h(
                    "div",
                    { class: "definition-row", attrs: { role: "listitem" }, dataset: { name: entry.name } },
                    h("span", { class: "definition-name", text: entry.name }),
                    value,
                    button({
                        icon: icons.close,
                        label: `Remove ${entry.name}`,
                        className: "icon-only",
                        onClick: () => this.remove(index),
                    }),
                );
            }),
        );
    }

    async send(entries) {
        const definitions = { ...this.model.definitions, [this.kind]: entries };
        return this.commands.setDefinitions({ events: definitions.events, constants: definitions.constants });
    }

    async add() {
        const name = this.nameInput.value.trim();
        const value = Number(this.valueInput.value);
        let problem = null;
        if (!IDENTIFIER.test(name))
            problem = `"${name}" is not a name: letters, digits, _ and ., starting with a letter or _`;
        else if (this.entries().some((entry) => entry.name === name)) problem = `${name} is already defined`;
        else problem = this.spec.check(value);
        if (problem) {
            this.messages.error(`Not added: ${problem}.`);
            return;
        }
        if (await this.send([...this.entries(), { name, [this.spec.field]: value }])) {
            this.nameInput.value = "";
            this.valueInput.value = String(this.spec.fallback);
        }
    }

    async change(index, value) {
        const problem = this.spec.check(value);
        const entries = this.entries().map((entry) => ({ ...entry }));
        if (problem) {
            this.messages.error(`Not changed: ${problem}.`);
            this.render();
            return;
        }
        entries[index][this.spec.field] = value;
        if (!(await this.send(entries))) this.render();
    }

    async remove(index) {
        await this.send(this.entries().filter((_, position) => position !== index));
    }
}

// Sends a global event with arguments typed by the user.
export class EventSender {
    constructor(container, { model, commands, messages }) {
        this.model = model;
        this.commands = commands;
        this.messages = messages;
        this.select = h("select", { class: "select", label: "Event to send" });
        this.args = h("input", {
            class: "text-input",
            placeholder: "arguments: 1, 2, 3",
            label: "Arguments of the event",
        });
        this.element = h(
            "section",
            { class: "event-sender" },
            h("h3", { class: "group-title", text: "Send an event" }),
            h(
                "form",
                {
                    class: "sender-form",
                    onSubmit: (event) => {
                        event.preventDefault();
                        this.send();
                    },
                },
                this.select,
                this.args,
                h(
                    "button",
                    { type: "submit", class: "button primary", label: "Send the event" },
                    iconElement(icons.send),
                    h("span", { class: "button-text", text: "Send" }),
                ),
            ),
        );
        container.append(this.element);
        model.on("definitions", () => this.render());
        this.render();
    }

    render() {
        const selected = this.select.value;
        const events = this.model.definitions.events;
        setChildren(
            this.select,
            events.length === 0 ? h("option", { value: "", text: "(no global events)" }) : null,
            events.map((event) => h("option", { value: event.name, text: `${event.name} (${event.size})` })),
        );
        if (events.some((event) => event.name === selected)) this.select.value = selected;
    }

    async send() {
        const name = this.select.value;
        const definition = this.model.definitions.events.find((event) => event.name === name);
        if (!definition) {
            this.messages.error("Define a global event first.");
            return;
        }
        let args;
        try {
            args = parseIntegers(this.args.value);
        } catch (error) {
            this.messages.error(`Event ${name} not sent: ${error.message}.`);
            return;
        }
        if (args.length > definition.size) {
            this.messages.error(
                `Event ${name} not sent: it takes ${definition.size} argument${definition.size === 1 ? "" : "s"}, not ${args.length}.`,
            );
            return;
        }
        await this.commands.emit(name, args);
    }
}
