// The e-puck's camera line as a strip of colour, live: its variables camR,
// camG and camB (60 pixels each, robots/epuck/epuck_description.h) hold
// red and blue in 0..93 and green in 0..94 (robots/epuck/devices/
// epuck_camera.h, as the upstream firmware scales them). Shown only for a
// robot that has the three.

import { h } from "./dom.js";

const CHANNELS = [
    { name: "camR", full: 93 },
    { name: "camG", full: 94 },
    { name: "camB", full: 93 },
];

/** @param {number} value @param {number} full */
function intensity(value, full) {
    return Math.round((Math.min(full, Math.max(0, value)) * 255) / full);
}

export class CameraStrip {
    /** @param {HTMLElement} container */
    constructor(container) {
        /** @type {{ address: number, size: number }[] | null} */
        this.channels = null;
        this.canvas = h("canvas", {
            class: "camera-canvas",
            attrs: { role: "img", "aria-label": "The camera's line, left to right" },
        });
        this.element = h(
            "div",
            { class: "camera-strip", hidden: true },
            h("span", { class: "camera-label", text: "Camera", title: "camR, camG, camB: the camera's line" }),
            this.canvas,
        );
        container.append(this.element);
    }

    // The robot shown (the server's robot object), or null.
    setRobot(robot) {
        const variables = robot?.variables ?? [];
        const found = CHANNELS.map(({ name }) =>
            variables.find((variable) => variable.name === name && !variable.user),
        );
        const complete = found.every(Boolean) && found.every((variable) => variable.size === found[0].size);
        const channels = complete ? found.map(({ address, size }) => ({ address, size })) : null;
        if (JSON.stringify(channels) === JSON.stringify(this.channels)) return;
        this.channels = channels;
        this.element.hidden = !channels;
        if (channels) {
            this.canvas.width = channels[0].size;
            this.canvas.height = 1;
            this.canvas.getContext("2d").clearRect(0, 0, channels[0].size, 1);
        }
    }

    // A robot's variables from address 0 (a `variables` message's values).
    /** @param {number[]} values */
    setValues(values) {
        if (!this.channels) return;
        const pixels = this.channels[0].size;
        const context = this.canvas.getContext("2d");
        const image = context.createImageData(pixels, 1);
        for (let pixel = 0; pixel < pixels; pixel++) {
            this.channels.forEach(({ address }, channel) => {
                image.data[pixel * 4 + channel] = intensity(values[address + pixel] ?? 0, CHANNELS[channel].full);
            });
            image.data[pixel * 4 + 3] = 255;
        }
        context.putImageData(image, 0, 0);
    }
}
