// A minimal event emitter: the page's model and connection tell the views
// what changed through it.

export class Emitter {
    constructor() {
        this.handlers = new Map();
    }

    // Calls `handler(...args)` on every emit(name, ...args); returns a
    // function that removes it.
    on(name, handler) {
        if (!this.handlers.has(name)) this.handlers.set(name, new Set());
        this.handlers.get(name).add(handler);
        return () => this.handlers.get(name).delete(handler);
    }

    emit(name, ...args) {
        const handlers = this.handlers.get(name);
        if (!handlers) return;
        for (const handler of [...handlers]) {
            try {
                handler(...args);
            } catch (error) {
                // One broken view must not stop the others from updating.
                console.error(`while handling "${name}":`, error);
            }
        }
    }
}
