// What the studio's browser tests share: `lsys studio` started on a free
// port in a folder, Debian's headless Chromium driven by playwright-core
// with a fresh profile, and "ok - " / "FAILED - " lines with a count.
//
//   LSYS=path/to/lsys (default: target/debug/lsys), CHROMIUM (default
//   /usr/bin/chromium), STUDIO_SHOTS (screenshots; default docs/images)
import { spawn } from "node:child_process";
import { mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve, dirname } from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";

const here = dirname(fileURLToPath(import.meta.url));
export const repo = resolve(here, "../../..");
export const lsys = process.env.LSYS || join(repo, "target/debug/lsys");
export const images = process.env.STUDIO_SHOTS || join(repo, "docs/images");

let passed = 0, failed = 0;
export function check(name, ok, detail = "") {
  if (ok) { passed++; console.log(`ok - ${name}`); }
  else { failed++; console.log(`FAILED - ${name} ${detail}`); }
}

// Starts the studio on `dir` with the built front end; resolves to
// { server, url } once it prints its address.
export async function startStudio(dir) {
  const server = spawn(lsys, ["studio", dir, "--port", "0", "--assets", join(repo, "web/studio/dist")], { stdio: ["ignore", "pipe", "inherit"] });
  const url = await new Promise((res, rej) => {
    let out = "";
    server.stdout.on("data", (d) => { out += d; const m = out.match(/http:\/\/\S+\//); if (m) res(m[0]); });
    server.on("exit", (c) => rej(new Error(`lsys studio exited with ${c}`)));
    setTimeout(() => rej(new Error("lsys studio printed no URL in 20 s")), 20000);
  });
  return { server, url };
}

// Headless Chromium with a fresh profile (the persistent context is how
// Playwright takes --user-data-dir); { browser, profile }.
export async function launchBrowser() {
  const profile = mkdtempSync(join(tmpdir(), "lsys-studio-chromium-"));
  const browser = await chromium.launchPersistentContext(profile, {
    executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
    headless: true,
    viewport: { width: 1400, height: 800 },
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
      "--disable-background-networking", "--disable-component-update", "--disable-sync",
      "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
  });
  return { browser, profile };
}

// A new tab of `browser` that reports the page's errors.
export async function newPage(browser) {
  const page = await browser.newPage();
  page.on("pageerror", (e) => console.log("page error:", e.message));
  return page;
}

// Opens `url` in `page` and waits for its "load" (the tests count model
// loads from there; waiting only for the document let browser.mjs count
// the first model's second load as its edit's). On CI a page opened right
// after another test's browser closed missed "load" within 30 s
// (guides.mjs; paint.mjs twice locally), so the wait is 90 s and a failed
// one is tried again once.
export async function openPage(page, url) {
  for (let attempt = 1; ; attempt++) {
    try {
      await page.goto(url, { waitUntil: "load", timeout: 90000 });
      return;
    } catch (e) {
      if (attempt >= 2) throw e;
      console.log(`(opening ${url} failed: ${e.message.split("\n")[0]}; once more)`);
    }
  }
}

// Closes what a test opened and exits with its count.
export async function finish({ browser, profile, server, dirs }) {
  if (browser) await browser.close();
  if (server) server.kill();
  for (const d of [profile, ...dirs]) if (d) rmSync(d, { recursive: true, force: true });
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed ? 1 : 0);
}
