// Bundles the viewer into ONE self-contained HTML file (no CDN, no network at run time)
// shipped as package data, and the minimal MCP Apps host page the browser tests use.
import { build } from "esbuild";
import { readFileSync, writeFileSync } from "node:fs";

const here = new URL(".", import.meta.url);
// VIEWER_OUT_DIR: write both files there instead (the test that checks they are current).
const outDir = process.env.VIEWER_OUT_DIR;
const target = (committed, name) => outDir ? `${outDir}/${name}` : new URL(committed, here);
const read = (p) => readFileSync(new URL(p, here), "utf8");

async function bundle(entry) {
  const out = await build({ entryPoints: [new URL(entry, here).pathname], bundle: true,
    format: "iife", minify: true, write: false, target: "es2020", legalComments: "none",
    charset: "utf8" });
  // A closing script tag inside the inlined code would end the element early.
  return out.outputFiles[0].text.replaceAll("</script", "<\\/script");
}

const SCRIPT = await bundle("src/main.ts");
writeFileSync(target("../verigraph/viewer/static/episode.html", "episode.html"),
  read("src/index.html").replace("/*STYLE*/", () => read("src/style.css"))
    .replace("/*SCRIPT*/", () => SCRIPT));
const host = await bundle("test-host/host.ts");
writeFileSync(target("../tests/viewer_host/host.html", "host.html"),
  read("test-host/host.html").replace("/*SCRIPT*/", () => host));
console.log(`wrote episode.html and host.html${outDir ? ` to ${outDir}` : ""}`);
