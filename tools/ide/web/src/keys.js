// The page's keys. The group's are Aseba Studio 1.6's (its Debug menu: F7
// Load all, F8 Reset all, F9 Run all, F10 Pause all) and F1 its help; the
// editor's own (Ctrl+B, Ctrl+D, Ctrl+Shift+D as in Studio, and CodeMirror's)
// are bound in editor.js. SHORTCUTS is the list the help shows.

/** @typedef {{ section: string, keys: [string, string][] }} ShortcutSection */

/** @type {ShortcutSection[]} */
export const SHORTCUTS = [
    {
        section: "The whole group, as in Aseba Studio",
        keys: [
            ["F7", "Load all: compile every robot's script, load them and run them"],
            ["F8", "Reset all: restart every robot's program from its start"],
            ["F9", "Run all"],
            ["F10", "Pause all"],
        ],
    },
    {
        section: "The script",
        keys: [
            ["Ctrl+B", "Set or clear the breakpoint of the cursor's line"],
            ["Ctrl+D", "Comment the selected lines"],
            ["Ctrl+Shift+D", "Uncomment the selected lines"],
            ["Ctrl+Space", "Complete: keywords, variables, functions, events, constants"],
            ["Ctrl+F", "Find and replace"],
            ["Ctrl+Alt+G", "Go to a line"],
            ["Ctrl+Z, Ctrl+Shift+Z", "Undo, redo (each robot has its own history)"],
            ["Tab, Shift+Tab", "Indent, unindent the selected lines"],
        ],
    },
    {
        section: "The page",
        keys: [
            ["F1", "Open or close this help"],
            ["Escape", "Close the help"],
            ["←, →", "The previous, the next robot (on the focused robot tabs)"],
        ],
    },
];

// The group's action of each function key.
const GROUP_KEYS = { F7: "load", F8: "reset", F9: "run", F10: "pause" };

/**
 * Handles the page's keys wherever the focus is (the editor included).
 * @param {object} parts
 * @param {import("./commands.js").Commands} parts.commands
 * @param {{ isOpen: boolean, toggle: () => void, close: () => void }} parts.help
 */
export function installKeys({ commands, help }) {
    window.addEventListener(
        "keydown",
        (event) => {
            if (event.ctrlKey || event.altKey || event.metaKey || event.shiftKey) return;
            if (event.key === "F1") {
                event.preventDefault();
                help.toggle();
                return;
            }
            if (event.key === "Escape" && help.isOpen) {
                event.preventDefault();
                help.close();
                return;
            }
            const action = GROUP_KEYS[event.key];
            if (!action) return;
            // The browser's own use of the key (F7: caret browsing, F10: its menu) gives way.
            event.preventDefault();
            if (event.repeat) return;
            const names = commands.readyNames();
            if (action === "load") commands.load(names);
            else commands.control(names, action);
        },
        true,
    );
}
