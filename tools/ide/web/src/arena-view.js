// The arena view: the simulated arena from above (areas, obstacles, walls)
// with each robot's position, heading and LEDs, live from `arena-state`.
// Clicking a robot opens its tab. Shown only when the server has an arena.

import { h, button, setChildren, iconElement } from "./dom.js";
import { icons } from "./icons.js";

const WALL_CM = 1.5;
const LED_OFF = "#3a3f46";
const LED_ON = "#ff3b30";

function rgb(color, alpha = 1) {
    const [r, g, b] = (color ?? [0.5, 0.5, 0.5]).map((value) => Math.round(255 * Math.min(1, Math.max(0, value))));
    return `rgba(${r}, ${g}, ${b}, ${alpha})`;
}

export class ArenaView {
    constructor(container, { model, onSelect }) {
        this.model = model;
        this.onSelect = onSelect;
        this.active = null;
        this.drawPending = false;
        // Robots whose label the last drawing had room for.
        this.labelsShown = 0;
        this.canvas = h("canvas", {
            class: "arena-canvas",
            attrs: { role: "img", "aria-label": "The arena seen from above" },
        });
        this.time = h("span", { class: "section-summary" });
        this.legend = h("div", { class: "arena-legend" });
        this.enlarged = false;
        this.sizeButton = button({
            icon: icons.enlarge,
            label: "Enlarge the arena view",
            className: "icon-only small arena-size",
            onClick: () => this.setEnlarged(!this.enlarged),
        });
        this.element = h(
            "section",
            { class: "sidebar-section arena-view", attrs: { "aria-label": "Arena" } },
            h(
                "h2",
                { class: "section-title" },
                h("span", { text: "Arena" }),
                h("span", { class: "section-tools" }, this.time, this.sizeButton),
            ),
            h("div", { class: "arena-frame" }, this.canvas),
            this.legend,
        );
        container.append(this.element);
        this.element.addEventListener("keydown", (event) => {
            if (event.key === "Escape" && this.enlarged) this.setEnlarged(false);
        });
        this.canvas.addEventListener("click", (event) => {
            const robot = this.robotAt(event);
            if (robot) this.onSelect(robot.robot);
        });
        this.canvas.addEventListener("mousemove", (event) => {
            const robot = this.robotAt(event);
            this.canvas.style.cursor = robot ? "pointer" : "default";
            this.canvas.title = robot ? `${this.model.label(robot.robot)}: open its tab` : "";
        });
        new ResizeObserver(() => this.requestDraw()).observe(this.element);
        model.on("arena", () => this.update());
        model.on("arena-state", () => this.requestDraw());
        model.on("robots", () => this.requestDraw());
        this.update();
    }

    update() {
        this.element.hidden = !this.model.arena;
        this.renderLegend();
        this.requestDraw();
    }

    setActive(name) {
        this.active = name;
        this.requestDraw();
    }

    // Enlarged, the view covers most of the page, over the editor: a
    // hundred robots get room for their labels.
    setEnlarged(enlarged) {
        this.enlarged = enlarged;
        this.element.classList.toggle("enlarged", enlarged);
        const label = enlarged ? "Shrink the arena view back into the side panel" : "Enlarge the arena view";
        this.sizeButton.setAttribute("aria-label", label);
        this.sizeButton.title = label;
        setChildren(this.sizeButton, iconElement(enlarged ? icons.shrink : icons.enlarge));
        this.requestDraw();
    }

    renderLegend() {
        const arena = this.model.arena;
        this.legend.replaceChildren();
        if (!arena) return;
        this.legend.append(`${arena.width} × ${arena.height} cm`);
        for (const area of arena.areas ?? [])
            if (area.shock > 0)
                this.legend.append(
                    h(
                        "span",
                        { class: "legend-shock" },
                        h("span", { class: "legend-swatch", style: { background: rgb(area.color) } }),
                        `knocks every ${area.shock} s`,
                    ),
                );
    }

    requestDraw() {
        if (this.drawPending) return;
        this.drawPending = true;
        requestAnimationFrame(() => {
            this.drawPending = false;
            this.draw();
        });
    }

    // The transform from arena cm (y up) to canvas pixels.
    geometry() {
        const arena = this.model.arena;
        const frame = this.canvas.parentElement;
        const margin = 4;
        // Enlarged, the whole arena fits the frame's height too.
        const width = this.enlarged
            ? Math.min(
                  frame.clientWidth,
                  Math.floor(((frame.clientHeight - 2 * margin) * arena.width) / arena.height + 2 * margin),
              )
            : frame.clientWidth;
        const scale = (width - 2 * margin) / arena.width;
        const height = Math.round(arena.height * scale + 2 * margin);
        return { width, height, scale, x: (x) => margin + x * scale, y: (y) => margin + (arena.height - y) * scale };
    }

    robotAt(event) {
        const state = this.model.arenaState;
        if (!this.model.arena || !state) return null;
        const { scale, x, y } = this.geometry();
        const bounds = this.canvas.getBoundingClientRect();
        const px = event.clientX - bounds.left;
        const py = event.clientY - bounds.top;
        const reach = Math.max(8, (this.model.arena.robotRadius ?? 3.7) * scale * 1.3);
        return state.robots.find((robot) => Math.hypot(x(robot.x) - px, y(robot.y) - py) <= reach) ?? null;
    }

    draw() {
        const arena = this.model.arena;
        if (!arena || this.element.hidden) return;
        const g = this.geometry();
        const ratio = window.devicePixelRatio || 1;
        if (this.canvas.width !== Math.round(g.width * ratio) || this.canvas.height !== Math.round(g.height * ratio)) {
            this.canvas.width = Math.round(g.width * ratio);
            this.canvas.height = Math.round(g.height * ratio);
        }
        this.canvas.style.width = `${g.width}px`;
        this.canvas.style.height = `${g.height}px`;
        const context = this.canvas.getContext("2d");
        context.setTransform(ratio, 0, 0, ratio, 0, 0);
        context.clearRect(0, 0, g.width, g.height);

        context.fillStyle = rgb(arena.floor);
        context.fillRect(g.x(0), g.y(arena.height), arena.width * g.scale, arena.height * g.scale);
        for (const area of arena.areas ?? []) this.drawArea(context, g, area);
        for (const obstacle of arena.obstacles ?? []) this.drawObstacle(context, g, obstacle);
        for (const sound of arena.sounds ?? []) this.drawSound(context, g, sound);
        context.strokeStyle = rgb(arena.walls);
        context.lineWidth = WALL_CM * g.scale;
        context.strokeRect(g.x(0), g.y(arena.height), arena.width * g.scale, arena.height * g.scale);

        const state = this.model.arenaState;
        this.time.textContent = state ? `t = ${state.time.toFixed(1)} s` : "waiting for positions…";
        const radius = arena.robotRadius ?? 3.7;
        const robots = state?.robots ?? [];
        for (const robot of robots) this.drawRobot(context, g, robot, radius);
        this.drawLabels(context, g, robots, radius);
    }

    // Each robot's id above it, unless it would cover a label already
    // drawn (robots in a crowd): the selected robot's first, then by id.
    drawLabels(context, g, robots, radius) {
        context.font = "600 11px system-ui, sans-serif";
        context.textAlign = "center";
        context.textBaseline = "bottom";
        context.lineWidth = 3;
        const placed = [];
        const order = [...robots].sort(
            (a, b) => Number(b.robot === this.active) - Number(a.robot === this.active) || a.id - b.id,
        );
        for (const robot of order) {
            const label = String(this.model.robots.get(robot.robot)?.id ?? robot.id ?? robot.robot);
            const cx = g.x(robot.x);
            const bottom = g.y(robot.y) - Math.max(5, radius * g.scale) - 2;
            const width = context.measureText(label).width + 4;
            const box = { left: cx - width / 2, right: cx + width / 2, top: bottom - 12, bottom };
            const overlaps = placed.some(
                (other) =>
                    box.left < other.right &&
                    other.left < box.right &&
                    box.top < other.bottom &&
                    other.top < box.bottom,
            );
            if (overlaps) continue;
            placed.push(box);
            context.strokeStyle = "rgba(0, 0, 0, 0.7)";
            context.strokeText(label, cx, bottom);
            context.fillStyle = "#ffffff";
            context.fillText(label, cx, bottom);
        }
        this.labelsShown = placed.length;
    }

    drawArea(context, g, area) {
        context.fillStyle = rgb(area.color);
        context.beginPath();
        if (area.shape === "disc") context.arc(g.x(area.x), g.y(area.y), area.radius * g.scale, 0, 2 * Math.PI);
        else context.rect(g.x(area.x), g.y(area.y + area.height), area.width * g.scale, area.height * g.scale);
        context.fill();
        if (area.shock > 0) {
            context.setLineDash([4, 3]);
            context.strokeStyle = "rgba(255, 255, 255, 0.8)";
            context.lineWidth = 1.5;
            context.stroke();
            context.setLineDash([]);
        }
    }

    drawObstacle(context, g, obstacle) {
        context.fillStyle = rgb(obstacle.color);
        context.strokeStyle = "rgba(0, 0, 0, 0.5)";
        context.lineWidth = 1;
        context.beginPath();
        if (obstacle.shape === "cylinder")
            context.arc(g.x(obstacle.x), g.y(obstacle.y), obstacle.radius * g.scale, 0, 2 * Math.PI);
        else {
            context.save();
            context.translate(g.x(obstacle.x), g.y(obstacle.y));
            context.rotate((-obstacle.heading * Math.PI) / 180);
            context.rect(
                (-obstacle.length / 2) * g.scale,
                (-obstacle.width / 2) * g.scale,
                obstacle.length * g.scale,
                obstacle.width * g.scale,
            );
            context.restore();
        }
        context.fill();
        context.stroke();
    }

    // A loudspeaker: a dot and two arcs of waves, with its frequency.
    drawSound(context, g, sound) {
        const cx = g.x(sound.x);
        const cy = g.y(sound.y);
        context.fillStyle = "#6e40c9";
        context.strokeStyle = "#6e40c9";
        context.lineWidth = 1.5;
        context.beginPath();
        context.arc(cx, cy, 3, 0, 2 * Math.PI);
        context.fill();
        for (const radius of [7, 11]) {
            context.beginPath();
            context.arc(cx, cy, radius, -Math.PI / 4, Math.PI / 4);
            context.stroke();
            context.beginPath();
            context.arc(cx, cy, radius, (3 * Math.PI) / 4, (5 * Math.PI) / 4);
            context.stroke();
        }
        context.font = "10px system-ui, sans-serif";
        context.textAlign = "center";
        context.textBaseline = "top";
        context.fillText(`${Math.round(sound.frequency)} Hz`, cx, cy + 12);
    }

    drawRobot(context, g, robot, radius) {
        const cx = g.x(robot.x);
        const cy = g.y(robot.y);
        const r = Math.max(5, radius * g.scale);
        // Canvas angles turn clockwise: the arena's counter-clockwise degrees
        // are negated.
        const heading = (-robot.heading * Math.PI) / 180;
        const selected = robot.robot === this.active;

        context.beginPath();
        context.arc(cx, cy, r, 0, 2 * Math.PI);
        context.fillStyle = robot.body ? "#2fbf71" : "#d9dde3";
        context.fill();
        context.lineWidth = selected ? 3 : 1.5;
        context.strokeStyle = selected ? "#2f81f7" : "#1f2328";
        context.stroke();

        // Ring LEDs: LED 0 at the front, then clockwise seen from above.
        for (let led = 0; led < 8; led++) {
            const angle = heading + (led * Math.PI) / 4;
            context.beginPath();
            context.arc(
                cx + Math.cos(angle) * r * 0.78,
                cy + Math.sin(angle) * r * 0.78,
                Math.max(1.5, r * 0.16),
                0,
                2 * Math.PI,
            );
            context.fillStyle = robot.leds?.[led] ? LED_ON : LED_OFF;
            context.fill();
        }
        // The heading, and the front LED at its tip.
        context.beginPath();
        context.moveTo(cx, cy);
        context.lineTo(cx + Math.cos(heading) * r * 0.55, cy + Math.sin(heading) * r * 0.55);
        context.strokeStyle = "#1f2328";
        context.lineWidth = 2;
        context.stroke();
        if (robot.front) {
            context.beginPath();
            context.arc(
                cx + Math.cos(heading) * r * 0.55,
                cy + Math.sin(heading) * r * 0.55,
                Math.max(1.5, r * 0.14),
                0,
                2 * Math.PI,
            );
            context.fillStyle = LED_ON;
            context.fill();
        }
    }
}
