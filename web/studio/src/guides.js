// lsys studio's guides page (seed 002's interaction): a guided scene's
// guides, links and seeds drawn in the plane over what the seeds grew; the
// user draws, bends, moves and deletes them, or drags a vertex with the
// mass-spring system (the other guides follow their springs), and the
// server runs the scene again (only the guides downstream of a moved one)
// and sends the drawing, the 3D model and the scene file's text. The page
// keeps the scene (and its undo history) and sends it whole with every
// change (docs/studio.md, "The guides page").
import { Viewer } from "./viewer.js";
import { api } from "./api.js";
import { el, Plane } from "./plane.js";

const $ = (id) => document.getElementById(id);
// What the browser tests read.
// `busy()`: a drag, its last springs answer or an edit is still under way
// (the browser test waits for it to be false before it reads the state).
const page = (window.guidesPage = { state: null, loads: 0, edits: 0, springs: 0, doc: () => doc, held: () => [...held],
  busy: () => drag !== null || ending > 0 || inFlight });

let doc = null;            // the scene: {steps, seed?, guide: [], link: [], seeds: []}
const undo = [], redo = [];
const held = new Set();    // "g:k": vertices the springs hold
let selected = null;       // {kind: "guide" | "link" | "seed", index}
let sketch = [];           // the corners of a guide being drawn
let picked = null;         // a link's first edge: {g, k}
const plane = new Plane($("plane"), $("world"));
let drag = null;           // the drag under way
let version = 0;

const clone = (x) => JSON.parse(JSON.stringify(x));
const tool = () => document.querySelector("input[name=tool]:checked").value;

const viewer = new Viewer($("canvas"));
document.querySelectorAll("#views button").forEach((b) => b.addEventListener("click", () => viewer.view(b.dataset.view)));

function message(problem) {
  if (!problem) return "";
  if (problem.message) return problem.message;
  return (problem.diagnostics || []).map((d) => d.rendered || d.message).join("\n");
}

// ---- the scene's geometry --------------------------------------------------
const guideIndex = (name) => doc.guide.findIndex((g) => g.name === name);
const edge = (g, k) => { const p = doc.guide[g].points; return [p[k % p.length], p[(k + 1) % p.length]]; };
const mid = ([a, b]) => [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];

function inside(p, pts) {
  let c = false;
  for (let i = 0, j = pts.length - 1; i < pts.length; j = i++) {
    const [xi, yi] = pts[i], [xj, yj] = pts[j];
    if ((yi > p[1]) !== (yj > p[1]) && p[0] < ((xj - xi) * (p[1] - yi)) / (yj - yi) + xi) c = !c;
  }
  return c;
}

function fit() {
  plane.fit(doc ? doc.guide.flatMap((g) => g.points).concat(doc.seeds.map((s) => s.position)) : []);
}

const pixel = () => plane.pixel();
const at = (e) => plane.at(e);

// ---- drawing the plane -----------------------------------------------------
function draw() {
  plane.clear();
  const w = plane.world;
  if (!doc) return;
  const px = pixel(), s = page.state, regrown = new Set(s ? s.regrown || [] : []);
  if ($("show-drawing").checked && s && s.drawing) {
    for (const segs of s.drawing) {
      if (segs.length === 0) continue;
      el("path", { class: "drawing", d: segs.map((q) => `M${q[0]} ${q[1]}L${q[2]} ${q[3]}`).join("") }, w);
    }
  }
  doc.guide.forEach((g, gi) => {
    const poly = el("polygon", { class: "guide" + (selected && selected.kind === "guide" && selected.index === gi ? " selected" : "") + (regrown.has(gi) ? " regrown" : ""), points: g.points.map((p) => p.join(",")).join(" ") }, w);
    poly.dataset.guide = gi;
    poly.addEventListener("pointerdown", (e) => guideDown(e, gi));
    const c = g.points.reduce((a, p) => [a[0] + p[0] / g.points.length, a[1] + p[1] / g.points.length], [0, 0]);
    el("text", { x: c[0], y: -c[1], transform: `scale(1,-1)`, style: `font-size:${11 * px}px`, "text-anchor": "middle" }, w).textContent = g.name;
    g.points.forEach((_, k) => {
      const [a, b] = edge(gi, k);
      const hit = el("line", { class: "edge-hit" + (picked && picked.g === gi && picked.k === k ? " picked" : ""), x1: a[0], y1: a[1], x2: b[0], y2: b[1] }, w);
      hit.dataset.guide = gi; hit.dataset.edge = k;
      hit.addEventListener("pointerdown", (e) => edgeDown(e, gi, k));
    });
  });
  doc.link.forEach((l, li) => {
    const g0 = guideIndex(l.from), g1 = guideIndex(l.to);
    if (g0 < 0 || g1 < 0 || !doc.guide[g0].points[l.from_edge] || !doc.guide[g1].points[l.to_edge]) return;
    const a = mid(edge(g0, l.from_edge)), b = mid(edge(g1, l.to_edge));
    const d = [b[0] - a[0], b[1] - a[1]], n = Math.hypot(...d) || 1, u = [d[0] / n, d[1] / n], h = 10 * px;
    const head = [[b[0] - u[0] * h - u[1] * h * 0.5, b[1] - u[1] * h + u[0] * h * 0.5], [b[0] - u[0] * h + u[1] * h * 0.5, b[1] - u[1] * h - u[0] * h * 0.5]];
    const path = el("path", { class: "link" + (l.tokens === 0 ? " navigation" : "") + (selected && selected.kind === "link" && selected.index === li ? " selected" : ""),
      d: `M${a[0]} ${a[1]}L${b[0]} ${b[1]}M${head[0][0]} ${head[0][1]}L${b[0]} ${b[1]}L${head[1][0]} ${head[1][1]}` }, w);
    path.dataset.link = li;
    path.addEventListener("pointerdown", (e) => linkDown(e, li));
  });
  doc.seeds.forEach((sd, si) => {
    const [x, y] = sd.position, r = 5 * px, t = (sd.heading * Math.PI) / 180;
    el("line", { class: "seed-heading", x1: x, y1: y, x2: x + Math.cos(t) * 18 * px, y2: y + Math.sin(t) * 18 * px }, w);
    const c = el("circle", { class: "seed", cx: x, cy: y, r }, w);
    c.dataset.seed = si;
    c.addEventListener("pointerdown", (e) => seedDown(e, si));
  });
  doc.guide.forEach((g, gi) => g.points.forEach((p, k) => {
    const c = el("circle", { class: "vertex" + (held.has(`${gi}:${k}`) ? " held" : ""), cx: p[0], cy: p[1], r: 4.5 * px }, w);
    c.dataset.guide = gi; c.dataset.vertex = k;
    c.addEventListener("pointerdown", (e) => vertexDown(e, gi, k));
  }));
  if (sketch.length) el("polyline", { class: "sketch", points: sketch.map((p) => p.join(",")).join(" ") }, w);
}

// ---- the server -------------------------------------------------------------
let inFlight = false, pending = false;
let ending = 0; // drags whose end is being committed

// Sends the scene; while an edit is under way only the latest scene waits.
async function send() {
  if (inFlight) { pending = true; return; }
  inFlight = true;
  try {
    do {
      pending = false;
      const r = await api("/api/guides/edit", { scene: doc });
      page.edits++;
      if (r.status === 200) await show(r.data);
      else {
        $("problem").textContent = r.data.refused ? message(r.data.refused) : String(r.data);
        if (r.data.state) await show(r.data.state);
      }
    } while (pending);
  } finally { inFlight = false; }
}

// A change the user made: undoable, then sent.
function commit(before) {
  undo.push(JSON.stringify(before)); redo.length = 0;
  buttons();
  draw(); showSelected();
  return send();
}

function buttons() {
  $("undo").disabled = undo.length === 0;
  $("redo").disabled = redo.length === 0;
  $("save").disabled = !doc;
}

async function show(s) {
  page.state = s;
  version++;
  $("problem").textContent = message(s.problem) + (s.current ? "" : "\n(the drawing and model shown are the last good run)");
  const t = s.timings_ms || {};
  $("counts").textContent = s.seeds_run === undefined ? "" :
    `${s.seeds_run} seeds, ${s.messages} messages, ${s.triangles} triangles · regrew ${(s.regrown || []).length} of ${doc.guide.length} guides in ${t.grow} ms`;
  $("text").textContent = s.text || "";
  $("grammar").replaceChildren(...(s.grammars || []).map((g) => new Option(g, g)));
  draw();
  const meshes = await viewer.load("/api/guides/model.glb?v=" + version, [], "front");
  if (meshes !== null) page.loads++;
}

// ---- tools -------------------------------------------------------------------
function hint() {
  $("hint").textContent = {
    move: "Drag a vertex or a seed; double-click an edge to bend it; click a guide, link or seed to edit it.",
    springs: "Drag a vertex: the guides follow their springs (links are stiff). Shift-click a vertex to hold it still.",
    guide: sketch.length ? `${sketch.length} corner(s): click the first one or press Enter to close, Escape to stop.` : "Click the new guide's corners.",
    link: picked ? `from ${doc.guide[picked.g].name}'s edge ${picked.k}: click an edge of another guide.` : "Click the edge a link leaves from.",
    seed: "Press inside a guide where the seed starts and drag toward its heading.",
    delete: "Click a vertex, a link, a seed or a guide to delete it.",
  }[tool()];
}
document.querySelectorAll("input[name=tool]").forEach((r) => r.addEventListener("change", () => {
  sketch = []; picked = null; hint(); draw();
}));

function vertexDown(e, g, k) {
  e.stopPropagation();
  const t = tool();
  if (t === "delete") return deleteVertex(g, k);
  if (t === "guide") return sketchClick(e);
  if (t === "springs" && e.shiftKey) {
    const key = `${g}:${k}`;
    held.has(key) ? held.delete(key) : held.add(key);
    return draw();
  }
  if (t !== "move" && t !== "springs") return;
  drag = { kind: t === "springs" ? "springs" : "vertex", g, k, before: clone(doc), to: null, asking: false };
  $("plane").setPointerCapture(e.pointerId);
}

function seedDown(e, si) {
  e.stopPropagation();
  const t = tool();
  if (t === "delete") { const b = clone(doc); doc.seeds.splice(si, 1); selected = null; return commit(b); }
  selected = { kind: "seed", index: si }; showSelected();
  if (t === "move") { drag = { kind: "seed", si, before: clone(doc) }; $("plane").setPointerCapture(e.pointerId); }
  draw();
}

function linkDown(e, li) {
  e.stopPropagation();
  if (tool() === "delete") { const b = clone(doc); doc.link.splice(li, 1); selected = null; return commit(b); }
  selected = { kind: "link", index: li }; showSelected(); draw();
}

function edgeDown(e, g, k) {
  const t = tool();
  if (t === "link") {
    e.stopPropagation();
    if (!picked) { picked = { g, k }; hint(); return draw(); }
    if (picked.g === g) { picked = { g, k }; hint(); return draw(); }
    const b = clone(doc);
    doc.link.push({ from: doc.guide[picked.g].name, from_edge: picked.k, to: doc.guide[g].name, to_edge: k,
      tokens: Number($("tokens").value) || 0, continuity: $("continuity").value });
    picked = null; hint();
    selected = { kind: "link", index: doc.link.length - 1 };
    return commit(b);
  }
  if (t === "guide") { e.stopPropagation(); return sketchClick(e); }
  // Other tools: the guide under the edge takes the press.
  guideDown(e, g);
}

function guideDown(e, gi) {
  const t = tool();
  if (t === "guide") return;          // the plane's handler adds a corner
  e.stopPropagation();
  if (t === "delete") return deleteGuide(gi);
  if (t === "seed") {
    drag = { kind: "new-seed", g: gi, from: at(e), before: clone(doc) };
    $("plane").setPointerCapture(e.pointerId);
    return;
  }
  selected = { kind: "guide", index: gi }; showSelected(); draw();
}

// A new corner of the guide being drawn (closing it on the first corner).
function sketchClick(e) {
  const p = at(e), px = pixel();
  if (sketch.length >= 3 && Math.hypot(p[0] - sketch[0][0], p[1] - sketch[0][1]) < 8 * px) return closeSketch();
  sketch.push(p); hint(); draw();
}

function closeSketch() {
  if (sketch.length < 3) return;
  const b = clone(doc);
  let n = doc.guide.length + 1;
  while (doc.guide.some((g) => g.name === `g${n}`)) n++;
  const grammar = $("grammar").value || (doc.guide[0] && doc.guide[0].grammar) || "";
  doc.guide.push({ name: `g${n}`, grammar, points: sketch.map((p) => p.map(round)) });
  sketch = []; hint();
  selected = { kind: "guide", index: doc.guide.length - 1 };
  return commit(b);
}

const round = (v) => Math.round(v * 1e4) / 1e4;

// The edge nearest `p` within `radius`: {g, k, q} (q: the point on it).
function nearestEdge(p, radius) {
  let best = null;
  doc.guide.forEach((_, g) => doc.guide[g].points.forEach((__, k) => {
    const [a, b] = edge(g, k), d = [b[0] - a[0], b[1] - a[1]];
    const t = Math.max(0, Math.min(1, ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1] || 1)));
    const q = [a[0] + d[0] * t, a[1] + d[1] * t], r = Math.hypot(p[0] - q[0], p[1] - q[1]);
    if (r <= radius && (!best || r < best.r)) best = { g, k, q, r };
  }));
  return best;
}

// Bending: a new vertex where an edge is double-clicked. Told by two
// presses close in time and place, seen before any part's handler (the
// first press may redraw the plane under the pointer, and a browser sends
// no dblclick across a redrawn element); the links on the guide's later
// edges keep their edges.
let lastPress = null;
$("plane").addEventListener("pointerdown", (e) => {
  const now = performance.now(), before = lastPress;
  lastPress = { t: now, x: e.clientX, y: e.clientY };
  if (tool() !== "move" || !doc || !before) return;
  if (now - before.t > 450 || Math.hypot(e.clientX - before.x, e.clientY - before.y) > 6) return;
  const hit = nearestEdge(at(e), 8 * pixel());
  if (!hit) return;
  e.stopPropagation();
  lastPress = null;
  drag = null;
  bend(hit.g, hit.k, hit.q);
}, true);

function bend(g, k, p) {
  const b = clone(doc), name = doc.guide[g].name;
  doc.guide[g].points.splice(k + 1, 0, p.map(round));
  for (const l of doc.link) {
    if (l.from === name && l.from_edge > k) l.from_edge++;
    if (l.to === name && l.to_edge > k) l.to_edge++;
  }
  return commit(b);
}

// Removing vertex i joins edges i-1 and i; the links on them stay on the
// joined edge, the later edges' links follow their edges.
function deleteVertex(g, i) {
  const pts = doc.guide[g].points, n = pts.length;
  if (n <= 3) { $("hint").textContent = "A guide keeps at least three vertices: delete the guide instead."; return; }
  const b = clone(doc), name = doc.guide[g].name;
  const joined = i === 0 ? n - 2 : i - 1;
  const renumber = (e) => (e === i || e === (i + n - 1) % n ? joined : e < i ? e : e - 1);
  pts.splice(i, 1);
  for (const l of doc.link) {
    if (l.from === name) l.from_edge = renumber(l.from_edge);
    if (l.to === name) l.to_edge = renumber(l.to_edge);
  }
  held.clear();
  return commit(b);
}

function deleteGuide(gi) {
  const b = clone(doc), name = doc.guide[gi].name;
  doc.guide.splice(gi, 1);
  doc.link = doc.link.filter((l) => l.from !== name && l.to !== name);
  doc.seeds = doc.seeds.filter((s) => s.guide !== name);
  selected = null; held.clear();
  return commit(b);
}

$("plane").addEventListener("pointerdown", (e) => {
  if (tool() === "guide" && doc) sketchClick(e);
});

$("plane").addEventListener("pointermove", async (e) => {
  if (!drag) return;
  const p = at(e).map(round);
  if (drag.kind === "vertex") {
    doc.guide[drag.g].points[drag.k] = p;
    draw(); send();
  } else if (drag.kind === "seed") {
    doc.seeds[drag.si].position = p;
    draw(); send();
  } else if (drag.kind === "new-seed") {
    drag.to = p;
    draw();
    const a = drag.from;
    el("line", { class: "seed-heading", x1: a[0], y1: a[1], x2: p[0], y2: p[1] }, $("world"));
  } else if (drag.kind === "springs") {
    drag.to = p;
    if (!drag.asking) relax(drag);
  }
});

// Asks the server where the guides rest with the dragged vertex at the
// pointer (from the scene as it was when the drag began); the latest
// pointer is asked again once an answer is in.
async function relax(d) {
  d.asking = true;
  try {
    let to;
    do {
      to = d.to;
      const held_ = [...held].map((h) => h.split(":").map(Number));
      const r = await api("/api/guides/springs", { scene: d.before, vertex: [d.g, d.k], to, held: held_ });
      page.springs++;
      if (r.status !== 200) { $("problem").textContent = message(r.data.refused); return; }
      r.data.points.forEach((pts, g) => { doc.guide[g].points = pts.map((q) => q.map(round)); });
      r.data.seeds.forEach((sd, i) => { doc.seeds[i].position = sd.position.map(round); doc.seeds[i].heading = round(sd.heading); });
      draw(); send();
    } while (d.to !== to);
  } finally { d.asking = false; }
}

$("plane").addEventListener("pointerup", async () => {
  const d = drag;
  drag = null;
  if (!d) return;
  ending++;
  try { await endDrag(d); } finally { ending--; }
});

// Ends a drag: the springs' last answer is awaited, then the change is
// committed as one undoable step.
async function endDrag(d) {
  if (d.kind === "springs") {
    while (d.asking) await new Promise((r) => setTimeout(r, 10));
    if (d.to === null) return;
  }
  if (d.kind === "new-seed") {
    const to = d.to || d.from, dx = to[0] - d.from[0], dy = to[1] - d.from[1];
    const heading = Math.hypot(dx, dy) > 0 ? round((Math.atan2(dy, dx) * 180) / Math.PI) : 90;
    doc.seeds.push({ guide: doc.guide[d.g].name, position: d.from.map(round), heading });
    selected = { kind: "seed", index: doc.seeds.length - 1 };
  }
  if (JSON.stringify(d.before) !== JSON.stringify(doc)) await commit(d.before);
}

document.addEventListener("keydown", (e) => {
  if (e.target.tagName === "INPUT") return;
  if (tool() === "guide" && e.key === "Enter") closeSketch();
  if (e.key === "Escape") { sketch = []; picked = null; hint(); draw(); }
});

// ---- the selected guide, link or seed -----------------------------------------
function field(label, value, onchange, attrs = {}) {
  const l = document.createElement("label");
  l.textContent = label + " ";
  const i = document.createElement(attrs.options ? "select" : "input");
  if (attrs.options) attrs.options.forEach((o) => i.appendChild(new Option(o, o, false, o === value)));
  else { i.value = value; i.size = attrs.size || 8; }
  i.addEventListener("change", () => { const b = clone(doc); if (onchange(i.value) !== false) commit(b); });
  l.appendChild(i);
  return l;
}

function showSelected() {
  const box_ = $("selected");
  box_.replaceChildren();
  box_.hidden = !selected || !doc;
  if (box_.hidden) return;
  const { kind, index } = selected;
  if (kind === "guide" && doc.guide[index]) {
    const g = doc.guide[index];
    box_.append(`guide ${g.name} · ${g.points.length} vertices `,
      field("name", g.name, (v) => {
        if (!v || doc.guide.some((x) => x.name === v)) return false;
        for (const l of doc.link) { if (l.from === g.name) l.from = v; if (l.to === g.name) l.to = v; }
        for (const s of doc.seeds) if (s.guide === g.name) s.guide = v;
        g.name = v;
      }),
      field("grammar", g.grammar, (v) => { g.grammar = v; }, { options: [...new Set([g.grammar, ...[...$("grammar").options].map((o) => o.value)])] }));
  } else if (kind === "link" && doc.link[index]) {
    const l = doc.link[index];
    box_.append(`link ${l.from}:${l.from_edge} → ${l.to}:${l.to_edge} `,
      field("tokens", l.tokens, (v) => { l.tokens = Math.max(0, Math.round(Number(v)) || 0); }, { size: 3 }),
      field("continuity", l.continuity, (v) => { l.continuity = v; }, { options: ["C1", "C0"] }),
      field("heading", l.heading || 0, (v) => { l.heading = Number(v) || 0; }, { size: 4 }));
  } else if (kind === "seed" && doc.seeds[index]) {
    const s = doc.seeds[index];
    box_.append(`seed in ${s.guide} `,
      field("heading", s.heading, (v) => { s.heading = Number(v) || 0; }, { size: 4 }),
      field("parameters", (s.parameters || []).join(", "), (v) => {
        s.parameters = v.split(",").map((x) => x.trim()).filter(Boolean).map(Number).filter((x) => Number.isFinite(x));
      }, { size: 12 }));
  } else box_.hidden = true;
}

// ---- undo, steps, save, opening -------------------------------------------------
$("undo").addEventListener("click", () => {
  if (!undo.length) return;
  redo.push(JSON.stringify(doc)); doc = JSON.parse(undo.pop());
  selected = null; held.clear(); buttons(); showSelected(); draw(); send();
});
$("redo").addEventListener("click", () => {
  if (!redo.length) return;
  undo.push(JSON.stringify(doc)); doc = JSON.parse(redo.pop());
  selected = null; held.clear(); buttons(); showSelected(); draw(); send();
});
$("steps").addEventListener("change", () => {
  const n = Math.round(Number($("steps").value));
  if (!doc || !(n >= 1)) return;
  const b = clone(doc); doc.steps = n; commit(b);
});
$("fit").addEventListener("click", () => { fit(); draw(); });
$("show-drawing").addEventListener("change", draw);
$("save").addEventListener("click", async () => {
  const r = await api("/api/guides/save", {});
  $("status").textContent = r.status === 200 ? `saved ${r.data.saved} (${r.data.bytes} bytes)` : (r.data.error || String(r.data));
});

async function opened(r) {
  if (r.status !== 200) {
    $("problem").textContent = r.data.error || message(r.data.problem) || String(r.data);
    return;
  }
  // The server leaves out empty tables (as the file does): a scene
  // without links or seeds has none to draw.
  doc = { guide: [], link: [], seeds: [], ...r.data.scene };
  undo.length = 0; redo.length = 0; held.clear();
  selected = null; sketch = []; picked = null;
  $("file").textContent = r.data.name;
  $("steps").value = doc.steps;
  viewer.fitted = false;
  buttons(); fit(); hint(); showSelected();
  await show(r.data);
}
$("open").addEventListener("change", async () => {
  if ($("open").value) await opened(await api("/api/guides/open", { path: $("open").value }));
});
$("new").addEventListener("click", async () => {
  const path = $("new-path").value.trim();
  if (path) await opened(await api("/api/guides/open", { path, new: true }));
});

viewer.resize();
hint();
api("/api/scenes").then((r) => {
  $("open").replaceChildren(new Option("open scene…", ""), ...r.data.files.map((f) => new Option(f, f)));
});
// A scene already open (another tab, a reload) is shown.
api("/api/guides/state").then((r) => { if (r.status === 200) opened(r); });
