// Small helpers to build the page's DOM without a framework.

// Creates an element. `props`: class, text, title, label (aria-label and
// title), dataset, style, attrs, on{Event} handlers, and any DOM property.
export function h(tag, props = {}, ...children) {
    const element = document.createElement(tag);
    for (const [key, value] of Object.entries(props)) {
        if (value === undefined || value === null || value === false) continue;
        if (key === "class") element.className = value;
        else if (key === "text") element.textContent = value;
        else if (key === "label") {
            element.setAttribute("aria-label", value);
            if (!props.title) element.title = value;
        } else if (key === "dataset") Object.assign(element.dataset, value);
        else if (key === "style") Object.assign(element.style, value);
        else if (key === "attrs")
            for (const [name, attribute] of Object.entries(value)) element.setAttribute(name, attribute);
        else if (key.startsWith("on") && typeof value === "function")
            element.addEventListener(key.slice(2).toLowerCase(), value);
        else element[key] = value;
    }
    append(element, children);
    return element;
}

function append(element, children) {
    for (const child of children.flat(Infinity)) {
        if (child === undefined || child === null || child === false) continue;
        element.append(child instanceof Node ? child : document.createTextNode(String(child)));
    }
}

// Replaces every child of `element`.
export function setChildren(element, ...children) {
    element.replaceChildren();
    append(element, children);
}

// A button with an icon (an SVG path from icons.js), a text, and an
// accessible name.
/**
 * @param {{ icon?: string, text?: string, label?: string, onClick?: (event: MouseEvent) => void,
 *           className?: string, disabled?: boolean }} options
 */
export function button({ icon, text, label, onClick, className = "", disabled = false }) {
    return h(
        "button",
        { type: "button", class: `button ${className}`.trim(), label: label ?? text, onClick, disabled },
        icon ? iconElement(icon) : null,
        text ? h("span", { class: "button-text", text }) : null,
    );
}

export function iconElement(path) {
    const svg = document.createElementNS("http://www.w3.org/2000/svg", "svg");
    svg.setAttribute("viewBox", "0 0 24 24");
    svg.setAttribute("aria-hidden", "true");
    svg.classList.add("icon");
    const shape = document.createElementNS("http://www.w3.org/2000/svg", "path");
    shape.setAttribute("d", path);
    svg.append(shape);
    return svg;
}

// Offers `content` to the user as a file download.
export function download(fileName, content, type = "text/plain") {
    const blob = content instanceof Blob ? content : new Blob([content], { type });
    const url = URL.createObjectURL(blob);
    const link = h("a", { href: url, download: fileName, style: { display: "none" } });
    document.body.append(link);
    link.click();
    link.remove();
    setTimeout(() => URL.revokeObjectURL(url), 10000);
}

// Asks the user for a file and resolves with {name, text}, or null.
export function pickTextFile(accept) {
    return new Promise((resolve) => {
        const input = h("input", { type: "file", accept, style: { display: "none" } });
        input.addEventListener("cancel", () => {
            input.remove();
            resolve(null);
        });
        input.addEventListener("change", async () => {
            const file = input.files[0];
            input.remove();
            resolve(file ? { name: file.name, text: await file.text() } : null);
        });
        document.body.append(input);
        input.click();
    });
}
