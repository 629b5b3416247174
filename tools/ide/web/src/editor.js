// The script editor: CodeMirror 6 with the Aseba language, a breakpoint
// gutter, the robot's current line, run-time errors at their line, and
// compile errors as lint diagnostics. One EditorView shows the robot of the
// current tab; every robot keeps its own EditorState (text, undo history,
// breakpoints), so that switching tabs is instant even with 100 robots.

import { EditorState, StateField, StateEffect, RangeSet, Annotation } from "@codemirror/state";
import {
    EditorView,
    keymap,
    lineNumbers,
    highlightActiveLineGutter,
    highlightSpecialChars,
    drawSelection,
    highlightActiveLine,
    rectangularSelection,
    crosshairCursor,
    dropCursor,
    gutter,
    GutterMarker,
    Decoration,
    WidgetType,
    placeholder,
} from "@codemirror/view";
import { defaultKeymap, history, historyKeymap, indentWithTab } from "@codemirror/commands";
import { indentOnInput, bracketMatching, indentUnit } from "@codemirror/language";
import { searchKeymap, highlightSelectionMatches, search } from "@codemirror/search";
import { autocompletion, completionKeymap, closeBrackets, closeBracketsKeymap } from "@codemirror/autocomplete";
import { lintGutter, setDiagnostics, lintKeymap } from "@codemirror/lint";
import { aseba } from "./aseba-language.js";

// Marks changes that come from the server (another tab, a project), not
// from the user's typing: they are not sent back.
export const fromServer = Annotation.define();

// --- breakpoints ---------------------------------------------------------

// A breakpoint's marker: `status` is "wanted" (not confirmed yet), "set"
// (the robot has it) or "refused" (no code on that line, or the robot said no).
class BreakpointMarker extends GutterMarker {
    constructor(status) {
        super();
        this.status = status;
    }
    eq(other) {
        return other.status === this.status;
    }
    toDOM() {
        const dot = document.createElement("span");
        dot.className = `cm-breakpoint cm-breakpoint-${this.status}`;
        dot.title =
            this.status === "refused"
                ? "breakpoint not set: no code on this line"
                : this.status === "set"
                  ? "breakpoint (click to remove)"
                  : "breakpoint, set at the next load";
        return dot;
    }
}

// Keeps the gutter as wide as a marker when no line has one.
class BreakpointSpacer extends GutterMarker {
    toDOM() {
        const space = document.createElement("span");
        space.className = "cm-breakpoint-space";
        return space;
    }
}

const markers = {
    wanted: new BreakpointMarker("wanted"),
    set: new BreakpointMarker("set"),
    refused: new BreakpointMarker("refused"),
};

/** @type {import("@codemirror/state").StateEffectType<number>} */
const toggleBreakpointEffect = StateEffect.define({ map: (position, mapping) => mapping.mapPos(position) });
// Replaces the markers' statuses: {line: "set" | "refused"}.
/** @type {import("@codemirror/state").StateEffectType<Record<number, string>>} */
const breakpointStatusEffect = StateEffect.define();

const breakpointField = StateField.define({
    create: () => RangeSet.empty,
    update(set, transaction) {
        set = set.map(transaction.changes);
        for (const effect of transaction.effects) {
            if (effect.is(toggleBreakpointEffect)) {
                const position = effect.value;
                let present = false;
                set.between(position, position, () => {
                    present = true;
                });
                set = present
                    ? set.update({ filter: (from) => from !== position })
                    : set.update({ add: [markers.wanted.range(position)] });
            } else if (effect.is(breakpointStatusEffect)) {
                const statuses = effect.value;
                const doc = transaction.state.doc;
                const ranges = [];
                const cursor = set.iter();
                for (; cursor.value; cursor.next()) {
                    const line = doc.lineAt(cursor.from).number;
                    ranges.push(markers[statuses[line] ?? cursor.value.status].range(cursor.from));
                }
                set = RangeSet.of(ranges);
            }
        }
        if (!transaction.docChanged) return set;
        // Two breakpoints that an edit merged onto one line become one.
        const seen = new Set();
        return set.update({
            filter: (from) => {
                const line = transaction.state.doc.lineAt(from).number;
                if (seen.has(line)) return false;
                seen.add(line);
                return true;
            },
        });
    },
});

// The lines (1-based) that carry a breakpoint.
export function breakpointLines(state) {
    const lines = [];
    const cursor = state.field(breakpointField).iter();
    for (; cursor.value; cursor.next()) lines.push(state.doc.lineAt(cursor.from).number);
    return lines;
}

// A transaction spec that puts breakpoints on `lines` (a new state's).
export function breakpointsAt(state, lines) {
    const effects = [];
    for (const line of new Set(lines))
        if (line >= 1 && line <= state.doc.lines) effects.push(toggleBreakpointEffect.of(state.doc.line(line).from));
    return { effects };
}

// A transaction spec giving the robot's answer about each breakpoint:
// results is [{line, set}].
export function breakpointStatus(results) {
    /** @type {Record<number, string>} */
    const statuses = {};
    for (const result of results) statuses[result.line] = result.set ? "set" : "refused";
    return { effects: breakpointStatusEffect.of(statuses) };
}

// Toggles the breakpoint of the cursor's line (Ctrl+B, as in Aseba Studio).
/** @param {EditorView} view */
export function toggleBreakpointAtCursor(view) {
    const line = view.state.doc.lineAt(view.state.selection.main.head);
    view.dispatch({ effects: toggleBreakpointEffect.of(line.from) });
}

// Removes every breakpoint of the script; false when it had none.
/** @param {EditorView} view */
export function clearBreakpoints(view) {
    const effects = [];
    const cursor = view.state.field(breakpointField).iter();
    for (; cursor.value; cursor.next()) effects.push(toggleBreakpointEffect.of(cursor.from));
    if (effects.length) view.dispatch({ effects });
    return effects.length > 0;
}

// --- comments ------------------------------------------------------------------

// The lines the selection touches, each once.
function selectedLines(state) {
    const lines = new Map();
    for (const range of state.selection.ranges) {
        const first = state.doc.lineAt(range.from).number;
        // A selection ending at a line's start does not take that line.
        let last = state.doc.lineAt(range.to).number;
        if (last > first && state.doc.lineAt(range.to).from === range.to) last--;
        for (let number = first; number <= last; number++) lines.set(number, state.doc.line(number));
    }
    return [...lines.values()];
}

// Ctrl+D, as in Aseba Studio: a # at the start of each selected line.
/** @param {EditorView} view */
export function commentLines(view) {
    const changes = selectedLines(view.state).map((line) => ({ from: line.from, insert: "#" }));
    view.dispatch({ changes, userEvent: "input.comment" });
    return true;
}

// Ctrl+Shift+D: the # that starts each selected line goes (indented ones
// too); a block comment's #* stays, its end would be left alone.
/** @param {EditorView} view */
export function uncommentLines(view) {
    const changes = [];
    for (const line of selectedLines(view.state)) {
        const match = /^\s*#(?!\*)/.exec(line.text);
        if (match) changes.push({ from: line.from + match[0].length - 1, to: line.from + match[0].length });
    }
    if (changes.length) view.dispatch({ changes, userEvent: "delete.uncomment" });
    return true;
}

// Clicking beside a line toggles its breakpoint; `onToggle(view)` follows.
function breakpointGutter(onToggle) {
    return gutter({
        class: "cm-breakpoint-gutter",
        markers: (view) => view.state.field(breakpointField),
        initialSpacer: () => new BreakpointSpacer(),
        domEventHandlers: {
            mousedown(view, line) {
                view.dispatch({ effects: toggleBreakpointEffect.of(line.from) });
                onToggle(view);
                return true;
            },
        },
    });
}

// --- the robot's current line and its run-time error ----------------------

class RuntimeErrorWidget extends WidgetType {
    constructor(message) {
        super();
        this.message = message;
    }
    eq(other) {
        return other.message === this.message;
    }
    toDOM() {
        const box = document.createElement("div");
        box.className = "cm-runtime-error-message";
        box.setAttribute("role", "alert");
        box.textContent = this.message;
        return box;
    }
}

// {line, message} or null; and the execution line or 0.
/** @type {import("@codemirror/state").StateEffectType<{ line: number, message: string } | null>} */
const runtimeErrorEffect = StateEffect.define();
/** @type {import("@codemirror/state").StateEffectType<number>} */
const executionLineEffect = StateEffect.define();

const robotLinesField = StateField.define({
    create: () => ({ executionLine: 0, runtimeError: null, decorations: Decoration.none }),
    update(value, transaction) {
        let { executionLine, runtimeError } = value;
        let changed = false;
        for (const effect of transaction.effects) {
            if (effect.is(executionLineEffect)) {
                executionLine = effect.value;
                changed = true;
            } else if (effect.is(runtimeErrorEffect)) {
                runtimeError = effect.value;
                changed = true;
            }
        }
        if (!changed && !transaction.docChanged) return value;
        // An edit moves the marks with their text; a new mark is placed by line.
        if (!changed) return { executionLine, runtimeError, decorations: value.decorations.map(transaction.changes) };
        const doc = transaction.state.doc;
        const ranges = [];
        if (runtimeError && runtimeError.line >= 1 && runtimeError.line <= doc.lines) {
            const line = doc.line(runtimeError.line);
            ranges.push(Decoration.line({ class: "cm-runtime-error-line" }).range(line.from));
            ranges.push(
                Decoration.widget({ widget: new RuntimeErrorWidget(runtimeError.message), block: true, side: 1 }).range(
                    line.to,
                ),
            );
        }
        if (executionLine >= 1 && executionLine <= doc.lines)
            ranges.push(Decoration.line({ class: "cm-execution-line" }).range(doc.line(executionLine).from));
        ranges.sort((a, b) => a.from - b.from);
        return { executionLine, runtimeError, decorations: Decoration.set(ranges, true) };
    },
    provide: (field) => EditorView.decorations.from(field, (value) => value.decorations),
});

export function executionLine(line) {
    return { effects: executionLineEffect.of(line) };
}

export function runtimeError(error) {
    return {
        effects: runtimeErrorEffect.of(error && error.line > 0 ? { line: error.line, message: error.message } : null),
    };
}

// --- compile errors ----------------------------------------------------------

// The document range of the token at `line`, `column` (1-based; the column
// counts code points, as the compiler does): a word, or one character.
export function tokenRange(doc, line, column) {
    if (line < 1 || line > doc.lines) return { from: doc.length, to: doc.length };
    const text = doc.line(line);
    let offset = 0;
    let codePoints = 1;
    for (const character of text.text) {
        if (codePoints >= column) break;
        offset += character.length;
        codePoints++;
    }
    const from = text.from + offset;
    const rest = text.text.slice(offset);
    const word = /^[\p{L}\p{N}_][\p{L}\p{N}_.]*/u.exec(rest);
    const length = word ? word[0].length : rest.length > 0 ? [...rest][0].length : 0;
    return { from, to: from + length };
}

// A transaction spec showing a compile error, or none.
export function compileDiagnostics(state, error) {
    if (!error || !error.line) return setDiagnostics(state, []);
    const { from, to } = tokenRange(state.doc, error.line, error.column);
    return setDiagnostics(state, [{ from, to, severity: "error", message: error.message, source: "compiler" }]);
}

// --- the editor ----------------------------------------------------------------

const theme = EditorView.theme({
    "&": { height: "100%", fontSize: "13.5px" },
    ".cm-scroller": { fontFamily: "var(--font-code)", lineHeight: "1.55" },
    ".cm-content": { caretColor: "var(--text)" },
    ".cm-gutters": {
        background: "var(--editor-gutter)",
        color: "var(--text-faint)",
        borderRight: "1px solid var(--border)",
    },
    ".cm-activeLineGutter": { background: "var(--editor-active-gutter)", color: "var(--text)" },
    ".cm-activeLine": { background: "var(--editor-active-line)" },
    "&.cm-focused .cm-selectionBackground, .cm-selectionBackground, ::selection": {
        background: "var(--editor-selection) !important",
    },
    ".cm-tooltip": { background: "var(--surface)", border: "1px solid var(--border)", color: "var(--text)" },
    ".cm-panels": { background: "var(--surface-2)", color: "var(--text)" },
});

// The extensions of every robot's state. `hooks`: onChange(update),
// onBreakpointsChanged(view), namesOf() for completions.
export function editorExtensions(hooks) {
    return [
        highlightSpecialChars(),
        history(),
        drawSelection(),
        dropCursor(),
        EditorState.allowMultipleSelections.of(true),
        indentUnit.of("    "),
        indentOnInput(),
        bracketMatching(),
        closeBrackets(),
        autocompletion({ activateOnTyping: true }),
        rectangularSelection(),
        crosshairCursor(),
        highlightActiveLine(),
        highlightSelectionMatches(),
        search({ top: true }),
        placeholder("Write this robot's program here: onevent, var, call, emit…"),
        breakpointField,
        robotLinesField,
        breakpointGutter(hooks.onBreakpointsChanged),
        lineNumbers(),
        highlightActiveLineGutter(),
        lintGutter(),
        aseba(hooks.namesOf),
        theme,
        keymap.of([
            // Aseba Studio's keys first: Ctrl+D is also CodeMirror's "select
            // the next occurrence".
            {
                key: "Mod-b",
                preventDefault: true,
                run: (view) => {
                    toggleBreakpointAtCursor(view);
                    hooks.onBreakpointsChanged(view);
                    return true;
                },
            },
            { key: "Mod-d", preventDefault: true, run: commentLines },
            { key: "Shift-Mod-d", preventDefault: true, run: uncommentLines },
            ...closeBracketsKeymap,
            ...defaultKeymap,
            ...searchKeymap,
            ...historyKeymap,
            ...completionKeymap,
            // F8 is Studio's Reset all (keys.js).
            ...lintKeymap.filter((binding) => binding.key !== "F8"),
            indentWithTab,
        ]),
        EditorView.updateListener.of((update) => {
            if (update.docChanged && !update.transactions.some((transaction) => transaction.annotation(fromServer)))
                hooks.onChange(update);
        }),
    ];
}

export function createState(text, extensions) {
    return EditorState.create({ doc: text, extensions });
}
