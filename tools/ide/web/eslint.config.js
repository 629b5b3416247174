// The page's lint rules (npm run lint): ESLint's recommended ones for
// browser modules, and a few that keep the code plain.
import js from "@eslint/js";
import globals from "globals";

export default [
    js.configs.recommended,
    {
        files: ["src/**/*.js"],
        languageOptions: {
            ecmaVersion: 2022,
            sourceType: "module",
            globals: globals.browser,
        },
        rules: {
            "no-unused-vars": ["error", { args: "none" }],
            eqeqeq: ["error", "smart"],
            "no-var": "error",
            "prefer-const": "error",
        },
    },
    {
        files: ["*.js", "*.mjs"],
        languageOptions: { ecmaVersion: 2022, sourceType: "module", globals: globals.node },
    },
];
