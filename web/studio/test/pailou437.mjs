// The Pailou editor in a real browser (issue 34, item 3): a 4-3-7 built
// by clicks from the default entrance, as the paper's Section 4 builds a
// Pailou: the central entrance's boards, queti and yundan and pillar bases
// through the palette, the entrance copied upward (#duplicate-up) and
// given its Toukungs and eaves roof, the whole group copied sideways
// (#duplicate), clipped roofs on the outer pillars; then one side
// entrance's own ratio (its `side[1]` slider) and one component's own size
// at its entrance (the central upper Toukungs' `tk[1,2]`). Every step is checked for
// structural warnings; the result must have `lsys pailou --style 4-3-7`'s
// layout chart, and the relation matrix must mark the active pair.
// Screenshot: docs/images/studio-pailou-437.png. Prints "N passed, N failed".
//
//   LSYS=path/to/lsys node test/pailou437.mjs     (default: target/debug/lsys)
import { mkdtempSync } from "node:fs";
import { execFileSync } from "node:child_process";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { check, images, lsys, startStudio, launchBrowser, newPage, finish, openPage } from "./harness.mjs";

const dir = mkdtempSync(join(tmpdir(), "lsys-pailou437-"));
const { server, url } = await startStudio(dir);
let browser, profile;
try {
  ({ browser, profile } = await launchBrowser());
  const page = await newPage(browser);
  await openPage(page, url);
  await page.waitForFunction(() => window.studio.state && window.studio.state.components.length === 3, null, { timeout: 60000 });
  const state = () => page.evaluate(() => window.studio.state);
  const edits = () => page.evaluate(() => window.studio.edits);
  const warnings = [];
  // One click and its answer; the structural problems after it recorded.
  const click = async (selector) => {
    const e = await edits();
    await page.click(selector);
    await page.waitForFunction((e) => window.studio.edits > e, e, { timeout: 120000 });
    const s = await state();
    if (s.problems.length) warnings.push(`${selector}: ${JSON.stringify(s.problems)}`);
    return s;
  };
  const select = (id) => click(`#graph g.node[data-id="${id}"]`);
  const add = (kind) => click(`#palette button[data-kind="${kind}"]`);
  const added = (before, after, kind) => after.components.filter((c) => c.kind === kind && !before.components.some((b) => b.id === c.id)).map((c) => c.id);

  let s = await select("L11");
  await add("flower_board");
  await select("L11");
  await add("inscribed_board");
  await select("L11");
  s = await add("queti");                 // the new queti is active
  await add("yundan");
  await select("P1R");
  await add("pillar_base");               // mirrored onto P1L
  // The central entrance copied upward: suspended pillars, a lintel and
  // the boards above it.
  let before = await select("L11");
  s = await click("#duplicate-up");
  const upper = Object.entries(s.lintels).find(([, at]) => at[0] === 1 && at[1] === 2);
  check("duplicate upward puts a copy of the central entrance above it", upper !== undefined && s.chart.startsWith("level 2  [G12 ]"), s.chart);
  await select(upper[0]);
  before = await add("middle_toukung");
  s = await add("eaves_roof");            // on the new Toukung
  // The relation matrix marks the new roof's row and the (middle Toukung,
  // eaves roof) pair that made it legal.
  const row = await page.textContent("#matrix tr.active-row th");
  const pair = await page.getAttribute('#matrix td[data-row="middle_toukung"][data-col="eaves_roof"]', "class");
  check("the relation matrix marks the eaves roof's row and the pair that made it legal", row === "RE" && pair.includes("pair"), `${row} ${pair}`);
  await select(upper[0]);
  await add("side_toukung");
  // The whole group copied sideways, on both halves.
  before = await select("L11");
  s = await click("#duplicate");
  const pillars = added(before, s, "pillar");
  check("duplication copies the central group sideways on both halves", pillars.length === 2 && s.chart.startsWith("level 2  [G22^][G12^][G22^]"), s.chart);
  await select("P1R");
  await add("clipped_roof");
  await select(pillars.find((p) => p.endsWith("R")));
  s = await add("clipped_roof");
  const want = execFileSync(lsys, ["pailou", "--style", "4-3-7", "--chart"], { encoding: "utf8" });
  check("the Pailou built by clicks has 4-3-7's layout: 4 pillars, 3 entrances, 7 roofs", s.chart.trim() === want.trim(), `${s.chart}\nvs\n${want}`);
  check("no click gave a structural warning", warnings.length === 0, warnings.join("\n"));

  // A side entrance's own ratio: lower than the others, still no warning.
  const side = Object.entries(s.lintels).find(([, at]) => at[0] === 2 && at[1] === 1)[0];
  await select(side);
  await page.waitForSelector('#entrance-params input[data-entrance="side[1]"]');
  const e = await edits();
  await page.$eval('#entrance-params input[data-entrance="side[1]"]', (i) => { i.value = "0.7"; i.dispatchEvent(new Event("change")); });
  await page.waitForFunction((e) => window.studio.edits > e, e, { timeout: 120000 });
  s = await state();
  check("the side entrances take a ratio of their own (side[1] = 0.7) with no structural warning", s.defines["side[1]"] === 0.7 && s.problems.length === 0,
    JSON.stringify(s.problems.slice(0, 2)));
  // A component's own sizes at its entrance (α^XW_ij ...): the central
  // upper entrance's middle Toukungs larger, which raises the main roof.
  const toukung = s.components.find((c) => c.kind === "middle_toukung" && JSON.stringify(s.entrance_of[c.id]) === "[1,2]");
  const top0 = s.bounds[1][1];
  await select(toukung.id);
  await page.waitForSelector('#entrance-params input[data-entrance="tk[1,2]"]');
  const fields = await page.$$eval("#entrance-params input", (l) => l.map((i) => i.dataset.entrance));
  check("a middle Toukung shows its entrance's ratio and its kind's sizes there", fields.join(" ") === "up[1,2] tk[1,2] lw[1,2]", fields.join(" "));
  const e2 = await edits();
  await page.$eval('#entrance-params input[data-entrance="tk[1,2]"]', (i) => { i.value = "0.15"; i.dispatchEvent(new Event("change")); });
  await page.waitForFunction((e) => window.studio.edits > e, e2, { timeout: 120000 });
  s = await state();
  check("the central upper Toukungs take a size of their own (tk[1,2] = 0.15): the main roof rises, no structural warning",
    s.defines["tk[1,2]"] === 0.15 && s.problems.length === 0 && s.bounds[1][1] > top0 + 0.1,
    `${top0} -> ${s.bounds[1][1]} ${JSON.stringify(s.problems.slice(0, 2))}`);
  check(`the 4-3-7 has ${s.components.length} components`, s.components.length === 57);
  await page.click('#views button[data-view="front"]');
  await page.waitForTimeout(500);
  await page.screenshot({ path: join(images, "studio-pailou-437.png") });
} catch (e) {
  check("the test ran to its end", false, e.stack);
} finally {
  await finish({ browser, profile, server, dirs: [dir] });
}
