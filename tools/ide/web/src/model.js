// What the page knows of the server's world: links, robots, definitions,
// the arena, event rates. It follows the server's messages and tells the
// views what changed. Robots are the server's JSON objects
// (docs/ide-protocol.md, "A robot"), keyed by their name "TARGET:ID".

import { Emitter } from "./emitter.js";

export class Model extends Emitter {
    constructor() {
        super();
        this.links = [];
        this.robots = new Map();
        this.definitions = { events: [], constants: [] };
        this.waitingPrograms = [];
        this.projectFile = "";
        this.arena = null;
        this.arenaState = null;
        this.eventRates = {};
    }

    // A hello replaces everything but the robots this page has seen: those
    // the server does not know (it restarted) stay, offline.
    applyHello(hello) {
        this.links = hello.links ?? [];
        const known = new Set();
        for (const robot of hello.robots ?? []) {
            known.add(robot.robot);
            this.robots.set(robot.robot, robot);
        }
        for (const [name, robot] of this.robots)
            if (!known.has(name)) this.robots.set(name, { ...robot, present: false, alive: false, state: "offline" });
        this.definitions = hello.definitions ?? { events: [], constants: [] };
        this.waitingPrograms = hello.waitingPrograms ?? [];
        this.projectFile = hello.projectFile ?? "";
        this.arena = hello.arena ?? null;
        this.arenaState = null;
        this.emit("links", this.links);
        this.emit("robots");
        this.emit("definitions", this.definitions);
        this.emit("project");
        this.emit("arena", this.arena);
    }

    applyRobot(robot) {
        const previous = this.robots.get(robot.robot);
        this.robots.set(robot.robot, robot);
        if (!previous) this.emit("robots");
        this.emit("robot", robot, previous);
    }

    applyLinks(links) {
        this.links = links;
        this.emit("links", links);
    }

    applyDefinitions(definitions) {
        this.definitions = definitions;
        this.emit("definitions", definitions);
    }

    applyProject(project) {
        this.waitingPrograms = project.waitingPrograms ?? [];
        this.projectFile = project.projectFile ?? "";
        this.applyDefinitions(project.definitions);
        this.emit("project");
    }

    applyArena(arena) {
        this.arena = arena;
        this.arenaState = null;
        this.emit("arena", arena);
    }

    applyArenaState(state) {
        this.arenaState = state;
        this.emit("arena-state", state);
    }

    applyStatus(status) {
        this.eventRates = status.eventRates ?? {};
        this.emit("status", this.eventRates);
    }

    // The robots in a stable order: by network, then by node id.
    sortedRobots() {
        return [...this.robots.values()].sort((a, b) => a.target - b.target || a.id - b.id);
    }

    // Robots that can take commands now.
    readyRobots() {
        return this.sortedRobots().filter((robot) => robot.present && robot.described && robot.compatible);
    }

    // How people see a robot: its name and node id, and its network when
    // the server joined several.
    label(robotOrName) {
        const robot = typeof robotOrName === "string" ? this.robots.get(robotOrName) : robotOrName;
        if (!robot) return String(robotOrName);
        const name = robot.name || "robot";
        const several = this.links.length > 1;
        return several ? `${name} ${robot.id} (network ${robot.target})` : `${name} ${robot.id}`;
    }

    // The name of a log entry's event: the server's, else the current
    // definitions', else its number.
    eventName(entry) {
        return entry.name ?? this.definitions.events[entry.event]?.name ?? `event ${entry.event}`;
    }
}

// The state a robot shows: offline robots and stale ones say so.
export function robotState(robot) {
    if (!robot.present) return "offline";
    if (!robot.described) return "waiting";
    if (!robot.alive) return "silent";
    return robot.state;
}

export const STATE_TEXT = {
    running: "running",
    stepping: "stopped in an event",
    stopped: "stopped",
    unknown: "state unknown",
    offline: "offline",
    waiting: "waiting for its description",
    silent: "not heard from",
};
