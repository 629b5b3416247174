// What the page adds to the browser's window: its parts, for the browser
// tests that open it as /?test (main.js, tests/ide/harness.mjs).
interface Window {
    asebaIde?: object;
}
