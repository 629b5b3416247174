// The page's WebSocket to the IDE server (docs/ide-protocol.md): requests
// with ids and their replies as promises, the server's messages as events,
// and a connection that comes back by itself, with a growing delay, when the
// server or the network drops it. It never asks the user anything.

import { Emitter } from "./emitter.js";

// Delays before reconnecting, in ms; the last one repeats.
const RECONNECT_DELAYS = [250, 500, 1000, 2000, 4000, 5000];

// A reply with ok: false, or a request that could not be sent.
export class RequestFailed extends Error {
    constructor(message, reply = null) {
        super(message);
        this.reply = reply;
        // True when the server never saw the request.
        this.unsent = reply === null;
    }
}

export class Connection extends Emitter {
    constructor(url) {
        super();
        this.url = url;
        this.socket = null;
        this.nextId = 1;
        this.pending = new Map(); // id -> {resolve, reject}
        this.attempt = 0;
        this.retryTimer = null;
        // "connecting", "open" (after hello), "waiting" (to reconnect)
        this.state = "connecting";
        this.retryAt = 0;
        this.lastClose = "";
    }

    start() {
        this.connect();
    }

    get open() {
        return this.state === "open";
    }

    // Sends a request and resolves with the server's reply; rejects with
    // RequestFailed when the server refuses it or the connection is down.
    request(message) {
        if (!this.socket || this.socket.readyState !== WebSocket.OPEN)
            return Promise.reject(new RequestFailed("not connected to the IDE server (reconnecting)"));
        const id = this.nextId++;
        return new Promise((resolve, reject) => {
            this.pending.set(id, { resolve, reject });
            this.socket.send(JSON.stringify({ ...message, id }));
        });
    }

    // Reconnects now instead of waiting for the next attempt.
    retryNow() {
        if (this.state !== "waiting") return;
        clearTimeout(this.retryTimer);
        this.connect();
    }

    connect() {
        this.setState("connecting");
        let socket;
        try {
            socket = new WebSocket(this.url);
        } catch (error) {
            this.lastClose = String(error.message ?? error);
            this.scheduleRetry();
            return;
        }
        this.socket = socket;
        socket.addEventListener("message", (event) => this.received(event.data));
        socket.addEventListener("close", (event) => {
            if (this.socket !== socket) return;
            this.socket = null;
            this.lastClose =
                event.reason || (event.code === 1006 ? "the server is unreachable" : `closed (${event.code})`);
            this.failPending("the connection to the IDE server was lost before its answer");
            this.scheduleRetry();
        });
    }

    scheduleRetry() {
        const delay = RECONNECT_DELAYS[Math.min(this.attempt, RECONNECT_DELAYS.length - 1)];
        this.attempt++;
        this.retryAt = Date.now() + delay;
        this.setState("waiting");
        this.retryTimer = setTimeout(() => this.connect(), delay);
    }

    failPending(reason) {
        const pending = [...this.pending.values()];
        this.pending.clear();
        for (const { reject } of pending) reject(new RequestFailed(reason));
    }

    received(text) {
        let message;
        try {
            message = JSON.parse(text);
        } catch {
            console.error("the IDE server sent a message that is not JSON:", text.slice(0, 200));
            return;
        }
        if (message.type === "reply") {
            const waiting = this.pending.get(message.id);
            if (!waiting) {
                // Bad requests whose id could not be read come back with id 0.
                if (!message.ok) this.emit("orphan-error", message.error);
                return;
            }
            this.pending.delete(message.id);
            if (message.ok) waiting.resolve(message);
            else waiting.reject(new RequestFailed(message.error ?? "the IDE server refused the request", message));
            return;
        }
        if (message.type === "hello") {
            this.attempt = 0;
            this.setState("open");
        }
        this.emit(message.type, message);
    }

    setState(state) {
        this.state = state;
        this.emit("state", state);
    }
}
