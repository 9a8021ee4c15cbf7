// The guides page in a real browser (issue 34, item 2: seed 002's
// interaction): the palm of examples/guided is opened; a leaf guide's tip
// is dragged and only that leaf grows again; a new guide is drawn by
// clicks, a seed pressed and dragged into it grows a line, a link is drawn
// between two edges; a bend adds a vertex; with the trunk's foot held,
// the crown is dragged with the mass-spring system and the guides follow;
// things are deleted, undone and redone; the scene is saved and
// `lsys build` runs the saved file. Screenshot: docs/images/studio-guides.png.
// Prints "N passed, N failed".
//
//   LSYS=path/to/lsys node test/guides.mjs     (default: target/debug/lsys)
import { copyFileSync, mkdtempSync, readFileSync } from "node:fs";
import { execFileSync } from "node:child_process";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { check, images, lsys, repo, startStudio, launchBrowser, newPage, finish, openPage } from "./harness.mjs";

const dir = mkdtempSync(join(tmpdir(), "lsys-guides-"));
for (const f of ["palm.toml", "palm_trunk.lsys", "palm_crown.lsys", "palm_leaf.lsys", "line.lsys",
  "bridge.toml", "bridge_deck.lsys", "bridge_tower.lsys", "bridge_cable.lsys"]) {
  copyFileSync(join(repo, "examples/guided", f), join(dir, f));
}
const { server, url } = await startStudio(dir);
let browser, profile;
try {
  ({ browser, profile } = await launchBrowser());
  const page = await newPage(browser);
  await openPage(page, url + "guides");
  const state = () => page.evaluate(() => window.guidesPage.state);
  const doc = () => page.evaluate(() => window.guidesPage.doc());
  const count = (k) => page.evaluate((k) => window.guidesPage[k], k);
  // Waits until the page has sent an edit after `n`, nothing is under way
  // (a drag's end, the springs' last answer, an edit) and the answer shows
  // the page's own scene (an edit sent while dragging may answer first).
  const settled = async (n) => {
    await page.waitForFunction((n) => {
      const p = window.guidesPage;
      // Keys sorted: the server's JSON orders them its own way.
      const canon = (v) => JSON.stringify(v, (k, x) => (x && typeof x === "object" && !Array.isArray(x)
        ? Object.fromEntries(Object.entries(x).sort(([a], [b]) => (a < b ? -1 : 1))) : x));
      return p.edits > n && !p.busy() && p.state && canon(p.state.scene) === canon(p.doc());
    }, n, { timeout: 60000 }).catch(async (e) => {
      const [st, d, edits] = await page.evaluate(() => [window.guidesPage.state && window.guidesPage.state.scene, window.guidesPage.doc(), window.guidesPage.edits]);
      throw new Error(`no answer showing the page's scene after edit ${n} (edits ${edits}):\n${JSON.stringify(st)}\n${JSON.stringify(d)}`);
    });
    return state();
  };
  // A point of the plane (world units) on the screen.
  const screen = (x, y) => page.evaluate(([x, y]) => {
    const p = new DOMPoint(x, y).matrixTransform(document.getElementById("world").getScreenCTM());
    return [p.x, p.y];
  }, [x, y]);
  const segments = (s, g) => (s.drawing[g] || []).length;
  const names = (d) => d.guide.map((g) => g.name);

  await page.waitForFunction(() => document.querySelectorAll("#open option").length > 1);
  await page.selectOption("#open", "palm.toml");
  await page.waitForFunction(() => window.guidesPage.loads > 0, null, { timeout: 60000 });
  let s = await state();
  const guides0 = s.scene.guide.length;
  check("the palm opens: 7 guides, 6 seeds, a drawing and a model", guides0 === 7 && s.seeds_run === 6 && s.drawing.flat().length > 50 && s.triangles > 0,
    `${guides0} guides, ${s.seeds_run} seeds, ${s.drawing.flat().length} segments`);
  check("guides, links, seeds and vertices are drawn", (await page.$$eval("#plane .guide", (e) => e.length)) === 7 &&
    (await page.$$eval("#plane .link", (e) => e.length)) === s.scene.link.length && (await page.$$eval("#plane .vertex", (e) => e.length)) > 40);

  // Move: drag leaf_right's tip; only that leaf grows again.
  const leaf = names(s.scene).indexOf("leaf_right");
  const drawing0 = s.drawing;
  let n = await count("edits");
  let [x, y] = await screen(7.059, 7.682);
  await page.mouse.move(x, y); await page.mouse.down();
  [x, y] = await screen(7.6, 6.6);
  await page.mouse.move(x, y, { steps: 4 }); await page.mouse.up();
  s = await settled(n);
  const moved = s.scene.guide[leaf].points[4];
  check("dragging a vertex moves it", Math.abs(moved[0] - 7.6) < 0.05 && Math.abs(moved[1] - 6.6) < 0.05, JSON.stringify(moved));
  check("only the moved leaf grows again", JSON.stringify(s.regrown) === JSON.stringify([leaf]), JSON.stringify(s.regrown));
  const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);
  check("the leaf's drawing changes, the other guides' stay", !same(s.drawing[leaf], drawing0[leaf]) &&
    s.drawing.every((d, i) => i === leaf || same(d, drawing0[i])));
  check("the scene file shows the new point", s.text.includes("7.6"));

  // Draw a guide by clicks, with the line grammar.
  await page.check('input[name=tool][value=guide]');
  await page.selectOption("#grammar", "line.lsys");
  for (const [px, py] of [[5, 1], [8, 1], [8, 4], [5, 4]]) {
    [x, y] = await screen(px, py);
    await page.mouse.click(x, y);
  }
  n = await count("edits");
  await page.keyboard.press("Enter");
  s = await settled(n);
  const g = s.scene.guide.length - 1;
  check("a guide drawn by four clicks is added", s.scene.guide.length === guides0 + 1 && s.scene.guide[g].points.length === 4 && s.scene.guide[g].grammar === "line.lsys",
    JSON.stringify(s.scene.guide[g]));

  // A seed pressed in it and dragged upward grows a line to its top.
  await page.check('input[name=tool][value=seed]');
  n = await count("edits");
  [x, y] = await screen(6.5, 1.5);
  await page.mouse.move(x, y); await page.mouse.down();
  [x, y] = await screen(6.5, 2.5);
  await page.mouse.move(x, y, { steps: 3 }); await page.mouse.up();
  s = await settled(n);
  const seed = s.scene.seeds[s.scene.seeds.length - 1];
  check("the seed is placed with the heading dragged", seed.guide === s.scene.guide[g].name && Math.abs(seed.heading - 90) < 1, JSON.stringify(seed));
  const top = Math.max(...s.drawing[g].map((q) => Math.max(q[1], q[3])));
  check("the seed grows a line up to the guide's top", s.seeds_run === 7 && top > 3.9 && top <= 4.0001, `top ${top}, ${s.seeds_run} seeds`);

  // A link from the new guide's left edge to the trunk's right edge.
  await page.check('input[name=tool][value=link]');
  const links0 = s.scene.link.length;
  [x, y] = await screen(5, 2.5);
  await page.mouse.click(x, y);
  n = await count("edits");
  [x, y] = await screen(1.6, 4);
  await page.mouse.click(x, y);
  s = await settled(n);
  const link = s.scene.link[s.scene.link.length - 1];
  check("a link is drawn between two edges", s.scene.link.length === links0 + 1 && link.from === s.scene.guide[g].name && link.from_edge === 3 && link.to === "trunk" && link.to_edge === 1,
    JSON.stringify(link));

  // Bend: a double-click on the new guide's top edge adds a vertex; the
  // link on its left edge (now edge 4) follows.
  await page.check('input[name=tool][value=move]');
  n = await count("edits");
  [x, y] = await screen(6.5, 4);
  await page.mouse.dblclick(x, y);
  s = await settled(n);
  const after = s.scene.link[s.scene.link.length - 1];
  check("a double-click bends an edge: a vertex is added, the link keeps its edge", s.scene.guide[g].points.length === 5 && after.from_edge === 4, JSON.stringify([s.scene.guide[g].points, after]));

  // Springs: hold the trunk's foot, drag the crown's top left corner.
  await page.check('input[name=tool][value=springs]');
  for (const [px, py] of [[-0.6, 0], [0.6, 0]]) {
    [x, y] = await screen(px, py);
    await page.keyboard.down("Shift"); await page.mouse.click(x, y); await page.keyboard.up("Shift");
  }
  check("shift-clicks hold the trunk's foot", (await page.evaluate(() => window.guidesPage.held())).length === 2);
  const before = await doc();
  const springs0 = await count("springs");
  n = await count("edits");
  [x, y] = await screen(1.6, 10.6);
  await page.mouse.move(x, y); await page.mouse.down();
  [x, y] = await screen(0.4, 10.9);
  await page.mouse.move(x, y, { steps: 6 }); await page.mouse.up();
  s = await settled(n);
  const dist = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1]);
  const crown = names(s.scene).indexOf("crown"), trunk = names(s.scene).indexOf("trunk"), top_ = names(s.scene).indexOf("leaf_top");
  check("the springs answered the drag", (await count("springs")) > springs0);
  check("the trunk's foot stays", JSON.stringify(s.scene.guide[trunk].points.slice(0, 2)) === JSON.stringify(before.guide[trunk].points.slice(0, 2)));
  check("the crown and a leaf it is linked to follow the drag", dist(s.scene.guide[crown].points[2], before.guide[crown].points[2]) > 0.3 &&
    dist(s.scene.guide[top_].points[3], before.guide[top_].points[3]) > 0.3);
  check("the palm grows again along the moved guides", s.regrown.length >= 6 && s.seeds_run >= 6, JSON.stringify(s.regrown));
  const seedNow = s.scene.seeds[s.scene.seeds.length - 1].position;
  check("the new guide, linked to the trunk, moved with it and carried its seed", s.current && !s.problem &&
    dist(s.scene.guide[g].points[0], before.guide[g].points[0]) > 0.05 && dist(seedNow, before.seeds[before.seeds.length - 1].position) > 0.05,
    JSON.stringify([s.problem, seedNow]));

  // Delete the bend's vertex (the springs moved the new guide with the
  // trunk it is linked to), then the link; undo both; redo one.
  await page.check('input[name=tool][value=delete]');
  n = await count("edits");
  [x, y] = await screen(...s.scene.guide[g].points[3]);
  await page.mouse.click(x, y);
  s = await settled(n);
  check("delete removes a vertex; the link stays on the joined edge", s.scene.guide[g].points.length === 4 && s.scene.link[s.scene.link.length - 1].from_edge === 3,
    JSON.stringify(s.scene.link[s.scene.link.length - 1]));
  n = await count("edits");
  await page.locator(`#plane .link[data-link="${s.scene.link.length - 1}"]`).dispatchEvent("pointerdown");
  s = await settled(n);
  check("delete removes a link", s.scene.link.length === links0);
  n = await count("edits");
  await page.click("#undo"); s = await settled(n);
  n = await count("edits");
  await page.click("#undo"); s = await settled(n);
  check("undo twice brings the link and the vertex back", s.scene.link.length === links0 + 1 && s.scene.guide[g].points.length === 5);
  n = await count("edits");
  await page.click("#redo"); s = await settled(n);
  check("redo deletes the vertex again", s.scene.guide[g].points.length === 4);

  await page.screenshot({ path: join(images, "studio-guides.png") });

  // Save, then build the saved file from the command line.
  await page.click("#save");
  await page.waitForFunction(() => document.getElementById("status").textContent.startsWith("saved"), null, { timeout: 20000 });
  const saved = readFileSync(join(dir, "palm.toml"), "utf8");
  check("save writes the scene: the new guide and its link", saved.includes(`name = "${s.scene.guide[g].name}"`) && saved.includes('grammar = "line.lsys"'));
  const out = execFileSync(lsys, ["build", join(dir, "palm.toml"), "-o", join(dir, "palm.glb"), "--stats"], { encoding: "utf8" });
  const stats = JSON.parse(out.slice(out.indexOf("{")));
  check("lsys build runs the saved scene: the page's seeds and messages", stats.seeds === s.seeds_run && stats.messages === s.messages, `${out.trim()} vs ${s.seeds_run}/${s.messages}`);

  // A scene without links or seeds tables (the server leaves empty tables
  // out, as the file does) opens and draws.
  const loads = await count("loads");
  await page.selectOption("#open", "bridge.toml");
  await page.waitForFunction((l) => window.guidesPage.loads > l && !window.guidesPage.busy(), loads, { timeout: 60000 });
  s = await state();
  const drawn = await page.evaluate(() => document.querySelectorAll("#plane .guide").length);
  check("a scene without links opens: the bridge's guides are drawn and its seeds grow", !s.problem && s.seeds_run === 15 && s.triangles > 0 && drawn === s.scene.guide.length,
    `${drawn} drawn, ${s.scene.guide.length} guides, ${s.seeds_run} seeds, problem ${JSON.stringify(s.problem)}`);
} catch (e) {
  check("the test ran to its end", false, e.stack);
} finally {
  await finish({ browser, profile, server, dirs: [dir] });
}
