// The Aseba language for CodeMirror: tokens as the compiler reads them
// (the language spec, §2: comments `#` and `#* ... *#`, words with dots,
// numbers in three bases, operators), indentation of blocks, and
// completion of the robot's names.

import {
    StreamLanguage,
    StringStream,
    LanguageSupport,
    HighlightStyle,
    syntaxHighlighting,
} from "@codemirror/language";
import { tags } from "@lezer/highlight";

// Every keyword of the language, by role.
const CONTROL_KEYWORDS = ["if", "then", "else", "elseif", "end", "while", "do", "for", "in", "step", "when", "return"];
const DEFINITION_KEYWORDS = ["var", "const", "sub", "onevent"];
const CALL_KEYWORDS = ["call", "callsub", "emit", "_emit"];
const OPERATOR_KEYWORDS = ["or", "and", "not", "abs"];
export const KEYWORDS = [...CONTROL_KEYWORDS, ...DEFINITION_KEYWORDS, ...CALL_KEYWORDS, ...OPERATOR_KEYWORDS];
// docs/language.md: `local` declares a local variable, but only when a name
// follows it (a variable called `local` still works as in Aseba 1.6).
export const CONTEXTUAL_KEYWORDS = ["local"];
const LOCAL_DECLARATION = /^\s+[\p{L}_][\p{L}\p{N}_.]*/u;

// Each keyword's highlighting role.
/** @type {Map<string, string>} */
const ROLE = new Map();
for (const [words, role] of /** @type {[string[], string][]} */ ([
    [CONTROL_KEYWORDS, "controlKeyword"],
    [DEFINITION_KEYWORDS, "definitionKeyword"],
    [CALL_KEYWORDS, "keyword"],
    [OPERATOR_KEYWORDS, "operatorKeyword"],
]))
    for (const word of words) ROLE.set(word, role);

// What the word after a keyword names.
const NAMED_AFTER = {
    call: "functionName",
    callsub: "subroutineName",
    sub: "subroutineName",
    onevent: "eventName",
    emit: "eventName",
    _emit: "eventName",
};

// Keywords that open a block closed by `end`, and those that continue one.
const OPENS_BLOCK = new Set(["if", "while", "for", "when"]);
const CLOSES_LINE = /^\s*(end|else|elseif)\b/;
const OPENS_HANDLER = /^\s*(onevent|sub)\b/;

const WORD = /^[\p{L}\p{N}_][\p{L}\p{N}_.]*/u;
const NUMBER = /^\p{Nd}/u;
// Longest first, as the compiler's lexer matches them.
const OPERATOR = /^(<<=|>>=|\+=|-=|\*=|\/=|%=|\|=|\^=|&=|==|!=|<=|>=|<<|>>|\+\+|--|[-+*/%<>=|^&~!])/;

function skipBlockComment(stream, state) {
    while (!stream.eol()) {
        if (stream.match("*#")) {
            state.inBlockComment = false;
            return;
        }
        stream.next();
    }
}

const asebaParser = {
    name: "aseba",
    startState: () => ({ inBlockComment: false, expect: null, depth: 0, inHandler: false }),
    copyState: (state) => ({ ...state }),
    token(stream, state) {
        if (state.inBlockComment) {
            skipBlockComment(stream, state);
            return "blockComment";
        }
        if (stream.eatSpace()) return null;
        if (stream.match("#*")) {
            state.inBlockComment = true;
            skipBlockComment(stream, state);
            return "blockComment";
        }
        if (stream.eat("#")) {
            stream.skipToEnd();
            return "lineComment";
        }
        const word = stream.match(WORD);
        if (word) {
            const text = word[0];
            const expected = state.expect;
            state.expect = null;
            if (NUMBER.test(text)) return "number";
            if (text === "local" && stream.match(LOCAL_DECLARATION, false)) return "definitionKeyword";
            const role = ROLE.get(text);
            if (role) {
                state.expect = NAMED_AFTER[text] ?? null;
                if (OPENS_BLOCK.has(text)) state.depth++;
                else if (text === "end") state.depth = Math.max(0, state.depth - 1);
                else if (text === "onevent" || text === "sub") {
                    state.inHandler = true;
                    state.depth = 0;
                }
                return role;
            }
            if (expected) return expected;
            // A call in an expression: a subroutine with parameters
            // (docs/language.md) or a native.
            if (stream.match(/^\s*\(/, false)) return "functionName";
            return "variableName";
        }
        state.expect = null;
        if (stream.match(OPERATOR)) return "operator";
        const punctuation = stream.next();
        if ("()[]".includes(punctuation)) return "bracket";
        if (":,".includes(punctuation)) return "punctuation";
        return "invalid";
    },
    indent(state, textAfter, context) {
        if (state.inBlockComment) return null;
        if (OPENS_HANDLER.test(textAfter)) return 0;
        let level = state.depth + (state.inHandler ? 1 : 0);
        if (CLOSES_LINE.test(textAfter)) level--;
        return Math.max(0, level) * context.unit;
    },
    languageData: {
        commentTokens: { line: "#", block: { open: "#*", close: "*#" } },
        indentOnInput: /^\s*(end|else|elseif|onevent|sub)$/,
        closeBrackets: { brackets: ["(", "["] },
    },
    tokenTable: {
        functionName: tags.function(tags.variableName),
        subroutineName: tags.function(tags.definition(tags.variableName)),
        eventName: tags.labelName,
    },
};

export const asebaLanguage = StreamLanguage.define(asebaParser);

// The tokens of `text` as the editor colours them: [[text, kind], ...],
// spaces left out (for tests).
export function asebaTokens(text) {
    const state = asebaParser.startState();
    const tokens = [];
    for (const line of text.split("\n")) {
        const stream = new StringStream(line, 4, 4);
        while (!stream.eol()) {
            const kind = asebaParser.token(stream, state);
            if (kind) tokens.push([stream.current(), kind]);
            stream.start = stream.pos;
        }
    }
    return tokens;
}

// Colours by CSS variables, so that the page's theme decides.
const highlightStyle = HighlightStyle.define([
    { tag: [tags.controlKeyword, tags.keyword], color: "var(--syntax-keyword)", fontWeight: "600" },
    { tag: tags.definitionKeyword, color: "var(--syntax-definition)", fontWeight: "600" },
    { tag: tags.operatorKeyword, color: "var(--syntax-operator-word)", fontWeight: "600" },
    { tag: [tags.lineComment, tags.blockComment], color: "var(--syntax-comment)", fontStyle: "italic" },
    { tag: tags.number, color: "var(--syntax-number)" },
    { tag: tags.operator, color: "var(--syntax-operator)" },
    { tag: [tags.bracket, tags.punctuation], color: "var(--syntax-punctuation)" },
    { tag: tags.function(tags.variableName), color: "var(--syntax-function)" },
    { tag: tags.function(tags.definition(tags.variableName)), color: "var(--syntax-function)" },
    { tag: tags.labelName, color: "var(--syntax-event)" },
    { tag: tags.invalid, color: "var(--syntax-invalid)", textDecoration: "underline wavy" },
]);

// Completion of keywords and of the names the robot knows: its variables,
// native functions, local events, and the project's events and constants.
// `namesOf()` returns {variables, natives, events, constants} for the robot
// being edited.
function completionSource(namesOf) {
    return (context) => {
        const word = context.matchBefore(/[\p{L}\p{N}_.]+/u);
        if (!word || (word.from === word.to && !context.explicit)) return null;
        const before = context.state.doc.sliceString(Math.max(0, word.from - 12), word.from);
        const names = namesOf();
        let options;
        if (/\bcall\s+$/.test(before))
            options = names.natives.map((native) => ({ label: native.name, type: "function", info: native.info }));
        else if (/\b(onevent|emit)\s+$/.test(before))
            options = names.events.map((name) => ({ label: name, type: "event" }));
        else
            options = [
                ...KEYWORDS.map((label) => ({ label, type: "keyword" })),
                ...names.variables.map((label) => ({ label, type: "variable" })),
                ...names.constants.map((label) => ({ label, type: "constant" })),
            ];
        return { from: word.from, options, validFor: /^[\p{L}\p{N}_.]*$/u };
    };
}

// The language, its colours and its completions, for one editor.
export function aseba(namesOf) {
    return [
        new LanguageSupport(asebaLanguage, asebaLanguage.data.of({ autocomplete: completionSource(namesOf) })),
        syntaxHighlighting(highlightStyle),
    ];
}
