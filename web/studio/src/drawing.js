// lsys studio's drawing page (seed 003's interaction): an elevation line
// drawing with its shape tree over it; the user corrects a part's label or
// draws a separator stroke where the drawing is ambiguous, and the server
// infers again (`lsys infer`'s reading), rebuilds the 3D hall and sends the
// emitted grammar. The page keeps the strokes and corrections (and their
// undo history) and sends them whole with every change (docs/studio.md).
import { Viewer } from "./viewer.js";
import { api } from "./api.js";

const $ = (id) => document.getElementById(id);
const NS = "http://www.w3.org/2000/svg";
// What the browser tests read.
const page = (window.drawingPage = { state: null, loads: 0, parts: 0, edits: 0 });

const COLOURS = {
  platform: "#8d6e63", stairs: "#bcaaa4", column: "#c0392b", bay: "#f5cba7", door: "#2e86c1",
  window: "#17a589", wall: "#d5dbdb", lintel: "#af7ac5", bracket: "#f39c12", rafter: "#b7950b",
  roof: "#5d6d7e", ridge: "#273746", ornament: "#e91e63", other: "#ffffff",
};

let edits = { strokes: [], corrections: [] };
const undo = [], redo = [];
let selected = null;   // a node of the tree (with .parent)
let version = 0;

const viewer = new Viewer($("canvas"));
document.querySelectorAll("#views button").forEach((b) => b.addEventListener("click", () => viewer.view(b.dataset.view)));

// ---- the state drawn ------------------------------------------------------
function message(problem) {
  if (!problem) return "";
  return (problem.diagnostics || []).map((d) => d.rendered || d.message).join("\n");
}

function withParents(n, parent) {
  n.parent = parent;
  for (const c of n.children || []) withParents(c, n);
  return n;
}

function leaves(n, out = []) {
  if (!n.children || n.children.length === 0) out.push(n);
  else n.children.forEach((c) => leaves(c, out));
  return out;
}

const same = (a, b) => a.length === 4 && a.every((v, i) => v === b[i]);
const corrected = (box) => edits.corrections.find((c) => same(c.box, box));

async function show(s, newDrawing) {
  page.state = s;
  version++;
  if (newDrawing) {
    $("drawing").src = "/api/drawing/image.png?v=" + version;
    $("file").textContent = s.name;
    $("gap").value = s.gap;
    selected = null;
    viewer.fitted = false;
  }
  if (s.tree) withParents(s.tree, null);
  $("problem").textContent = message(s.problem) + (s.current ? "" : "\n(the tree and hall shown are the last good reading)");
  const c = s.counts || {};
  $("counts").textContent = s.counts
    ? (s.summary ? `${s.summary} · ` : "") +
      `${c.column} columns, ${c.bay} bays, ${c.door} doors, ${c.window} windows, ${c.bracket} bracket sets, ${c.rafter} rafters` +
      (s.triangles ? ` · ${s.triangles} triangles` : "")
    : "";
  $("grammar").textContent = s.grammar || "";
  const missed = (s.missed || []).length;
  $("status").textContent = [
    s.unlabelled && s.unlabelled.length ? `${s.unlabelled.length} region(s) not labelled (red dashes)` : "",
    missed ? `${missed} of your labels name parts the tree no longer has` : "",
  ].filter(Boolean).join(" · ");
  // The selection survives a new reading when its box is still a node.
  if (selected && s.tree) selected = find(s.tree, selected.box);
  drawOverlay();
  drawSelected();
  const meshes = await viewer.load("/api/drawing/model.glb?v=" + version, [], "front");
  if (meshes !== null) { page.parts = meshes; page.loads++; }
}

function find(n, box) {
  if (same(n.box, box)) return n;
  for (const c of n.children || []) { const f = find(c, box); if (f) return f; }
  return null;
}

function rect(box, cls) {
  const r = document.createElementNS(NS, "rect");
  r.setAttribute("x", box[0]); r.setAttribute("y", box[1]);
  r.setAttribute("width", Math.max(box[2] - box[0], 1)); r.setAttribute("height", Math.max(box[3] - box[1], 1));
  r.setAttribute("class", cls);
  return r;
}

function drawOverlay() {
  const s = page.state, svg = $("overlay");
  svg.replaceChildren();
  if (!s) return;
  svg.setAttribute("viewBox", `0 0 ${s.width} ${s.height}`);
  svg.setAttribute("preserveAspectRatio", "none");
  if ($("show-tree").checked && s.tree) {
    for (const n of leaves(s.tree)) {
      const r = rect(n.box, "leaf" + (corrected(n.box) ? " corrected" : "") + (selected === n ? " selected" : ""));
      r.setAttribute("fill", COLOURS[n.label] || "#fff");
      r.setAttribute("stroke", n.label === "other" ? "#999" : COLOURS[n.label]);
      r.dataset.label = n.label;
      r.dataset.box = n.box.join(",");
      const t = document.createElementNS(NS, "title");
      t.textContent = `${n.label} [${n.box.join(", ")}]`;
      r.appendChild(t);
      r.addEventListener("click", () => { if (tool() === "select") { selected = n; drawOverlay(); drawSelected(); } });
      svg.appendChild(r);
    }
    if (selected && (selected.children || []).length) svg.appendChild(rect(selected.box, "node-selected"));
  }
  if ($("show-regions").checked) for (const b of s.regions || []) svg.appendChild(rect(b, "region"));
  for (const b of s.unlabelled || []) svg.appendChild(rect(b, "unlabelled"));
  for (const line of edits.strokes) svg.appendChild(polyline(line));
  $("legend").replaceChildren(...Object.entries(COLOURS).map(([l, col]) => {
    const e = document.createElement("span");
    e.innerHTML = `<i style="background:${col};border:1px solid #999"></i>${l}`;
    return e;
  }));
}

function polyline(points) {
  const p = document.createElementNS(NS, "polyline");
  p.setAttribute("class", "stroke-line");
  p.setAttribute("points", points.map((q) => q.join(",")).join(" "));
  return p;
}

function drawSelected() {
  $("selected").hidden = !selected;
  if (!selected) return;
  $("sel-label").textContent = selected.label;
  $("sel-box").textContent = `[${selected.box.join(", ")}]` + ((selected.children || []).length ? ` · ${selected.children.length} parts` : "");
  $("sel-set").replaceChildren(...page.state.labels.map((l) => new Option(l, l, false, l === selected.label)));
  $("sel-parent").disabled = !selected.parent;
  $("sel-forget").hidden = !corrected(selected.box);
}

// ---- edits ----------------------------------------------------------------
async function send(next) {
  undo.push(edits); redo.length = 0;
  edits = next;
  await apply();
}

async function apply() {
  $("undo").disabled = undo.length === 0;
  $("redo").disabled = redo.length === 0;
  const r = await api("/api/drawing/edit", { ...edits, gap: Number($("gap").value) });
  page.edits++;
  if (r.status === 200) await show(r.data, false);
  else {
    $("problem").textContent = r.data.refused ? r.data.refused.message : String(r.data);
    if (r.data.state) await show(r.data.state, false);
  }
}

$("sel-set").addEventListener("change", () => {
  const label = $("sel-set").value, box = selected.box;
  const rest = edits.corrections.filter((c) => !same(c.box, box));
  send({ strokes: edits.strokes, corrections: [...rest, { box, label }] });
});
$("sel-parent").addEventListener("click", () => { if (selected && selected.parent) { selected = selected.parent; drawOverlay(); drawSelected(); } });
$("sel-forget").addEventListener("click", () => {
  send({ strokes: edits.strokes, corrections: edits.corrections.filter((c) => !same(c.box, selected.box)) });
});
$("undo").addEventListener("click", () => { if (undo.length) { redo.push(edits); edits = undo.pop(); apply(); } });
$("redo").addEventListener("click", () => { if (redo.length) { undo.push(edits); edits = redo.pop(); apply(); } });
$("gap").addEventListener("change", () => apply());
$("show-regions").addEventListener("change", drawOverlay);
$("show-tree").addEventListener("change", drawOverlay);

// Separator strokes: drawn in the drawing's pixels.
const tool = () => document.querySelector("input[name=tool]:checked").value;
document.querySelectorAll("input[name=tool]").forEach((r) => r.addEventListener("change", () => {
  $("overlay").classList.toggle("stroke", tool() === "stroke");
}));
let drawing = null;
function at(e) {
  const svg = $("overlay"), m = svg.getScreenCTM().inverse();
  const p = new DOMPoint(e.clientX, e.clientY).matrixTransform(m);
  return [Math.round(p.x * 10) / 10, Math.round(p.y * 10) / 10];
}
$("overlay").addEventListener("pointerdown", (e) => {
  if (tool() !== "stroke" || !page.state) return;
  drawing = [at(e)];
  $("overlay").setPointerCapture(e.pointerId);
  $("overlay").appendChild(polyline(drawing)).id = "live";
});
$("overlay").addEventListener("pointermove", (e) => {
  if (!drawing) return;
  drawing.push(at(e));
  $("live").setAttribute("points", drawing.map((q) => q.join(",")).join(" "));
});
$("overlay").addEventListener("pointerup", () => {
  if (!drawing) return;
  const line = drawing;
  drawing = null;
  send({ strokes: [...edits.strokes, line], corrections: edits.corrections });
});

// ---- opening --------------------------------------------------------------
function opened(r) {
  if (r.status !== 200) {
    $("problem").textContent = r.data.error || message(r.data.problem) || String(r.data);
    return;
  }
  edits = { strokes: [], corrections: [] };
  undo.length = 0; redo.length = 0;
  $("undo").disabled = true; $("redo").disabled = true;
  return show(r.data, true);
}
$("open").addEventListener("change", async () => {
  if ($("open").value) await opened(await api("/api/drawing/open", { path: $("open").value }));
});
$("upload").addEventListener("change", async () => {
  const f = $("upload").files[0];
  if (f) await opened(await api("/api/drawing/upload?name=" + encodeURIComponent(f.name), await f.arrayBuffer(), true));
});

viewer.resize();
api("/api/drawings").then((r) => {
  $("open").replaceChildren(new Option("open drawing…", ""), ...r.data.files.map((f) => new Option(f, f)));
});
// A drawing already open (another tab, a reload) is shown.
api("/api/drawing/state").then((r) => {
  if (r.status !== 200) return;
  edits = { strokes: r.data.strokes, corrections: r.data.corrections };
  show(r.data, true);
});
