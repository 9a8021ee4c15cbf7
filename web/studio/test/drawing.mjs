// The drawing page in a real browser (issue 33, item 6: seed 003's
// interaction): a hand-made elevation with one line lost is opened from
// the folder; its shape tree is drawn over it and the 3D hall and the
// grammar appear; a separator stroke drawn with the mouse where the line
// was restores the lost bracket set; a window corrected to a wall changes
// the grammar; undo and redo walk the edits; a Pailou's front uploaded
// says the style it was read as. Screenshots: docs/images/studio-drawing.png,
// studio-drawing-pailou.png. Prints "N passed, N failed".
//
//   LSYS=path/to/lsys node test/drawing.mjs     (default: target/debug/lsys)
import { execFileSync } from "node:child_process";
import { mkdtempSync, readFileSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { check, images, lsys, repo, startStudio, launchBrowser, newPage, finish, openPage } from "./harness.mjs";

const dir = mkdtempSync(join(tmpdir(), "lsys-drawing-"));
// The five-bay hall (examples/drawings) without the line that quarters
// the second bracket block: read as 7 bracket sets, not 8.
const svg = readFileSync(join(repo, "examples/drawings/five-bay-hall.svg"), "utf8");
const lost = '<line x1="250.0" y1="277.5" x2="290.0" y2="277.5"/>';
if (!svg.includes(lost)) throw new Error("five-bay-hall.svg changed: pick another line to lose");
writeFileSync(join(dir, "lost-line.svg"), svg.replace(lost, ""));
const { server, url } = await startStudio(dir);
let browser, profile;
try {
  ({ browser, profile } = await launchBrowser());
  const page = await newPage(browser);
  await openPage(page, url + "drawing");
  const state = () => page.evaluate(() => window.drawingPage.state);
  const after = (key, n) => page.waitForFunction(([k, n]) => window.drawingPage[k] > n, [key, n], { timeout: 30000 });

  await page.waitForFunction(() => document.querySelectorAll("#open option").length > 1);
  await page.selectOption("#open", "lost-line.svg");
  await after("loads", 0);
  let s = await state();
  check("the drawing is read: 6 columns, 5 bays, 1 door, 4 windows", s.counts.column === 6 && s.counts.bay === 5 && s.counts.door === 1 && s.counts.window === 4, JSON.stringify(s.counts));
  check("with the line lost, 7 bracket sets", s.counts.bracket === 7, JSON.stringify(s.counts));
  const leaves = await page.$$eval("#overlay rect.leaf", (r) => r.length);
  check("the tree's leaves are drawn over the drawing", leaves > 20, `${leaves} leaves`);
  check("the hall is drawn in 3D", (await page.evaluate(() => window.drawingPage.parts)) > 0);
  check("the grammar is shown", (await page.textContent("#grammar")).includes("#define W "));
  const grammar0 = s.grammar;

  // A separator stroke with the mouse, in the drawing's pixels.
  const box = await page.locator("#overlay").boundingBox();
  const px = (x, y) => [box.x + (x * box.width) / s.width, box.y + (y * box.height) / s.height];
  await page.check('input[name=tool][value=stroke]');
  let edits = await page.evaluate(() => window.drawingPage.edits);
  await page.mouse.move(...px(248, 277.5));
  await page.mouse.down();
  for (let x = 255; x <= 292; x += 6) await page.mouse.move(...px(x, 277.5));
  await page.mouse.up();
  await after("edits", edits);
  s = await state();
  check("the stroke restores the lost line: 8 bracket sets", s.counts.bracket === 8, JSON.stringify(s.counts));
  check("the stroke is kept and drawn", s.strokes.length === 1 && (await page.$$eval("#overlay .stroke-line", (p) => p.length)) === 1);

  // Correct a label: the first window is a wall.
  await page.check('input[name=tool][value=select]');
  const win = await page.$('#overlay rect.leaf[data-label="window"]');
  const winBox = await win.getAttribute("data-box");
  await win.click();
  check("a click selects the part", (await page.textContent("#sel-label")) === "window");
  edits = await page.evaluate(() => window.drawingPage.edits);
  let loads = await page.evaluate(() => window.drawingPage.loads);
  await page.selectOption("#sel-set", "wall");
  await after("edits", edits);
  await after("loads", loads);
  s = await state();
  check("the corrected window is a wall: 3 windows", s.counts.window === 3, JSON.stringify(s.counts));
  check("the correction is marked on the drawing", (await page.getAttribute(`#overlay rect.leaf[data-box="${winBox}"]`, "class")).includes("corrected"));
  check("the grammar changed with it", s.grammar !== grammar0 && s.grammar.includes("EndFill --> Wall"), s.grammar.slice(0, 300));
  await page.screenshot({ path: join(images, "studio-drawing.png") });

  // Undo the correction, then the stroke; redo both.
  edits = await page.evaluate(() => window.drawingPage.edits);
  await page.click("#undo");
  await after("edits", edits);
  s = await state();
  check("undo takes the correction back", s.counts.window === 4 && s.counts.bracket === 8, JSON.stringify(s.counts));
  edits = await page.evaluate(() => window.drawingPage.edits);
  await page.click("#undo");
  await after("edits", edits);
  s = await state();
  check("undo again takes the stroke back", s.counts.bracket === 7 && s.strokes.length === 0, JSON.stringify(s.counts));
  for (let i = 0; i < 2; i++) {
    edits = await page.evaluate(() => window.drawingPage.edits);
    await page.click("#redo");
    await after("edits", edits);
  }
  s = await state();
  check("redo brings both back", s.counts.bracket === 8 && s.counts.window === 3, JSON.stringify(s.counts));

  // The grammar downloads as a file, named after the drawing.
  const [download] = await Promise.all([page.waitForEvent("download"), page.click("#download")]);
  const saved = join(dir, "downloaded.lsys");
  await download.saveAs(saved);
  check("the grammar downloads as lost-line.lsys", download.suggestedFilename() === "lost-line.lsys" && readFileSync(saved, "utf8") === s.grammar, download.suggestedFilename());

  // Not a line drawing: the reason, and the drawing before it stays.
  const photo = join(dir, "grey.svg");
  writeFileSync(photo, '<svg xmlns="http://www.w3.org/2000/svg" width="400" height="300"><rect width="400" height="300" fill="#222"/></svg>');
  await page.setInputFiles("#upload", photo);
  await page.waitForFunction(() => document.querySelector("#problem").textContent.includes("lsys::infer"), null, { timeout: 20000 });
  const problem = await page.textContent("#problem");
  check("a filled picture is refused with the reader's diagnostic", problem.includes("not a line drawing") && problem.includes("lsys::infer::not_a_line_drawing"), problem.slice(0, 200));
  check("the drawing before it stays open", (await page.textContent("#file")) === "lost-line.svg");

  // A Pailou's front (std:pailou's 4-3-7, drawn by lsys): the page says
  // which style, type and Toukung levels it read, beside the counts.
  const gate = join(dir, "gate.png");
  const grammar = execFileSync(lsys, ["pailou", "--style", "4-3-7", "--type", "ridge", "--emit-lsys"]);
  writeFileSync(join(dir, "gate.lsys"), grammar);
  execFileSync(lsys, ["render", join(dir, "gate.lsys"), "--view", "front", "--style", "lines", "--size", "1000x600", "-o", gate]);
  const before = await page.evaluate(() => window.drawingPage.loads);
  await page.setInputFiles("#upload", gate);
  await after("loads", before);
  const said = await page.textContent("#counts");
  check("a Pailou's front says its style: 4-3-7, ridge type, 5 Toukung levels", said.includes("style 4-3-7, ridge type, 5 Toukung levels") && said.includes("3 bays"), said);
  await page.screenshot({ path: join(images, "studio-drawing-pailou.png") });
} catch (e) {
  check("the scenario ran to its end", false, e.stack);
} finally {
  await finish({ browser, profile, server, dirs: [dir] });
}
