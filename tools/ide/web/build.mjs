// Builds the page into OUTDIR: index.html, favicon.svg, app.js and app.css
// (one bundle each, minified), which aseba-ide serves and compiles into itself.
import { build } from "esbuild";
import { copyFileSync, mkdirSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const outdir = process.argv[2];
if (!outdir) {
    console.error("usage: node build.mjs OUTDIR");
    process.exit(2);
}
mkdirSync(outdir, { recursive: true });
await build({
    entryPoints: { app: join(here, "src/main.js") },
    bundle: true,
    minify: true,
    sourcemap: false,
    format: "iife",
    target: ["es2020"],
    outdir,
    logLevel: "warning",
});
for (const file of ["index.html", "favicon.svg"]) copyFileSync(join(here, "src", file), join(outdir, file));
