// The page's pure parts, without a browser: the Aseba mode's tokens against
// the language spec (§2.1 comments, §2.2 tokens, §2.3 words and keywords),
// the place of a compile error (columns count code points), and the
// numbers and CSV people type and export.

import { test } from "node:test";
import assert from "node:assert/strict";
import { Text } from "../../tools/ide/web/node_modules/@codemirror/state/dist/index.js";
import { asebaTokens, KEYWORDS } from "../../tools/ide/web/src/aseba-language.js";
import { tokenRange } from "../../tools/ide/web/src/editor.js";
import { parseIntegers, csv } from "../../tools/ide/web/src/format.js";

// [source, expected tokens as "text:kind"]
const TOKEN_CASES = [
    // A block comment ends at the first `*#` (comments do not nest); the
    // spec's example leaves `*` and a line comment after it.
    ["#* a #* b *# y = 2 *#", ["#* a #* b *#:blockComment", "y:variableName", "=:operator", "2:number", "*:operator", "#:lineComment"]],
    ["#**# x", ["#**#:blockComment", "x:variableName"]],
    // `#*#` opens a comment that the next `*#` closes, lines later.
    ["#*# x\n*# y", ["#*# x:blockComment", "*#:blockComment", "y:variableName"]],
    ["x = 1 # the rest", ["x:variableName", "=:operator", "1:number", "# the rest:lineComment"]],
    // Words: dots inside names, letters beyond ASCII, numbers in three bases.
    ["prox.horizontal _x.y_z é", ["prox.horizontal:variableName", "_x.y_z:variableName", "é:variableName"]],
    ["0x1F 0b101 12 12ab", ["0x1F:number", "0b101:number", "12:number", "12ab:number"]],
    // Longest operators first.
    ["a <<= b >= c != d ++", ["a:variableName", "<<=:operator", "b:variableName", ">=:operator", "c:variableName", "!=:operator", "d:variableName", "++:operator"]],
    // What the word after a keyword names.
    ["call math.fill(v, 0)", ["call:keyword", "math.fill:functionName", "(:bracket", "v:variableName", ",:punctuation", "0:number", "):bracket"]],
    ["sub turn callsub turn", ["sub:definitionKeyword", "turn:subroutineName", "callsub:keyword", "turn:subroutineName"]],
    // docs/language.md: locals, subroutines with parameters, calls in expressions.
    ["local front = prox[0]", ["local:definitionKeyword", "front:variableName", "=:operator", "prox:variableName", "[:bracket", "0:number", "]:bracket"]],
    ["local = 2", ["local:variableName", "=:operator", "2:number"]],
    ["sub clamp(v, low) return v", ["sub:definitionKeyword", "clamp:subroutineName", "(:bracket", "v:variableName", ",:punctuation", "low:variableName", "):bracket", "return:controlKeyword", "v:variableName"]],
    ["x = clamp(a, 0)", ["x:variableName", "=:operator", "clamp:functionName", "(:bracket", "a:variableName", ",:punctuation", "0:number", "):bracket"]],
    ["onevent ir_sensors emit bad 1", ["onevent:definitionKeyword", "ir_sensors:eventName", "emit:keyword", "bad:eventName", "1:number"]],
    ["v[0:2]", ["v:variableName", "[:bracket", "0:number", "::punctuation", "2:number", "]:bracket"]],
    ["x = @", ["x:variableName", "=:operator", "@:invalid"]],
];

test("the Aseba mode reads tokens as the spec does", () => {
    for (const [source, expected] of TOKEN_CASES)
        assert.deepEqual(
            asebaTokens(source).map(([text, kind]) => `${text}:${kind}`),
            expected,
            source,
        );
});

test("every keyword of the spec is coloured as a keyword, and only they", () => {
    const spec = ["when", "emit", "_emit", "for", "in", "step", "while", "do", "if", "then", "else", "elseif", "end", "var", "const", "call", "sub", "callsub", "onevent", "abs", "return", "or", "and", "not"];
    assert.deepEqual([...KEYWORDS].sort(), [...spec].sort());
    for (const word of spec) assert.match(asebaTokens(word)[0][1], /Keyword$|^keyword$/, word);
    for (const word of ["When", "ends", "variable", "callsubs"]) assert.equal(asebaTokens(word)[0][1], "variableName", word);
});

test("a compile error's column counts code points", () => {
    const doc = Text.of(["é😀 abc.d + 1", "x"]);
    // Column 4 is `a` (é, the emoji and the space before it are one each).
    assert.deepEqual(tokenRange(doc, 1, 4), { from: 4, to: 9 });
    assert.equal(doc.sliceString(4, 9), "abc.d");
    // An operator is one character; past the end of a line, nothing.
    assert.deepEqual(tokenRange(doc, 1, 10), { from: 10, to: 11 });
    assert.deepEqual(tokenRange(doc, 2, 5), { from: 15, to: 15 });
    // A line that is not there points at the end of the text.
    assert.deepEqual(tokenRange(doc, 9, 1), { from: doc.length, to: doc.length });
});

test("integers typed in the page are 16-bit words", () => {
    assert.deepEqual(parseIntegers("1, -2 0x10;0b11 65535 -32768"), [1, -2, 16, 3, -1, -32768]);
    assert.deepEqual(parseIntegers("  "), []);
    for (const bad of ["1.5", "70000", "-32769x", "abc", "0x"]) assert.throws(() => parseIntegers(bad), Error, bad);
});

test("CSV fields are quoted when they need it", () => {
    assert.equal(csv([["a", 'say "hi"', "x,y", 3, null]]), 'a,"say ""hi""","x,y",3,\r\n');
});
