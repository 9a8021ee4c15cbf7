// lsys studio's painting page (seed 004's interface): the user paints
// rectangles in five views (front, back, top, left, right), each a
// component of the palette the session's construction rules offer; the
// server gives each its third dimension (the configure rules), moves its
// edges onto the parts near it within the threshold (the automatic
// correction), builds the session's .lsys and reports the holes the
// constraint rule cut. A reference photo can lie under any view. The page
// keeps the session and its undo history and sends it whole after an undo,
// a deletion or a change of threshold or photo (docs/studio.md, "The
// painting page").
import { Viewer } from "./viewer.js";
import { api } from "./api.js";
import { el, Plane } from "./plane.js";

const $ = (id) => document.getElementById(id);
// What the browser tests read. `busy()`: a request is under way.
const page = (window.paintPage = { state: null, loads: 0, edits: 0, busy: () => asking > 0,
  deselect: () => { selected = null; draw(); } });

let state = null;       // the server's last answer
const undo = [], redo = [];
let selected = null;    // a part's index
let drag = null;        // {from, to} of the rectangle being dragged
let asking = 0;
let version = 0;
let photos = [];        // the folder's images (paths from the opened folder)
const plane = new Plane($("plane"), $("world"));
const viewer = new Viewer($("canvas"));
document.querySelectorAll("#views button").forEach((b) => b.addEventListener("click", () => viewer.view(b.dataset.view)));

const view = () => document.querySelector("input[name=view]:checked").value;
const tool = () => document.querySelector("input[name=tool]:checked").value;
const component = () => { const c = document.querySelector("input[name=component]:checked"); return c ? c.value : null; };
const session = () => state && state.session;
const clone = (x) => JSON.parse(JSON.stringify(x));
const round = (v) => Math.round(v * 1000) / 1000;
// The pointer snaps to a 5 cm grid (a painted rectangle is a drawing at
// that precision; the correction then joins it to its neighbours).
const GRID = 0.05;
const snap = (v) => round(Math.round(v / GRID) * GRID);
// A colour per component, in palette order.
const COLOURS = ["#c8b59a", "#d8cfc0", "#5d8aa8", "#9e2a22", "#2f5f5a", "#8a8478", "#7b5e3b", "#c9a23f", "#6c7a89", "#a569bd"];
const colour = (name) => {
  const i = state ? state.palette.findIndex((c) => c.name === name) : -1;
  return i < 0 ? "#999" : COLOURS[i % COLOURS.length];
};

// The session's folder ("" or "a/b/"): its rules and photos are there.
const folder = () => (state && state.name.includes("/") ? state.name.slice(0, state.name.lastIndexOf("/") + 1) : "");
const photoUrl = (file) => "/api/paint/photo?path=" + encodeURIComponent(folder() + file);

function message(p) {
  if (!p) return "";
  if (p.message) return p.message;
  return (p.diagnostics || []).map((d) => d.rendered || d.message).join("\n");
}

// ---- the server -------------------------------------------------------------
// Requests go one at a time, in the order the user made the changes: two
// edits sent at once could be answered out of order and the older session
// would win. `body` may be a function, called when the request's turn
// comes, so that a change applies to the session as the changes before it
// left it.
let queue = Promise.resolve();
function call(path, body) {
  asking++;
  const turn = queue.then(() => send(path, typeof body === "function" ? body() : body)).finally(() => asking--);
  queue = turn.catch(() => {});
  return turn;
}

// Why the server said no: a refused paint or edit (a diagnostic), an
// error, an unreadable session, or plain text.
function refusal(d) {
  if (d.refused) return message(d.refused);
  if (d.problem) return message(d.problem);
  return d.error || String(d);
}

async function send(path, body) {
  const r = await api(path, body);
  page.edits++;
  if (r.status === 200) { $("problem").textContent = ""; await show(r.data); }
  else {
    $("problem").textContent = refusal(r.data);
    if (r.data.state) await show(r.data.state);
  }
  return r;
}

// A change the page made to the session, `change(next)` applied to a copy
// of it when its turn comes: undoable, then sent whole.
function edit(change) {
  return call("/api/paint/edit", () => {
    undo.push(clone(session())); redo.length = 0;
    const next = clone(session());
    change(next);
    return { session: next };
  });
}

// A rectangle the server places: undoable.
function paint(body) {
  return call("/api/paint/paint", () => {
    undo.push(clone(session())); redo.length = 0;
    return body;
  });
}

async function show(s) {
  const first = !state || state.name !== s.name;
  state = page.state = s;
  version++;
  if (selected !== null && selected >= s.session.parts.length) selected = null;
  buttons();
  palette();
  $("threshold").value = s.session.threshold;
  $("textures").checked = !!s.session.textures;
  $("threshold-value").textContent = s.session.threshold;
  $("file").textContent = s.name;
  $("text").textContent = s.text;
  $("counts").textContent = `${s.session.parts.length} parts, ${s.triangles} triangles`;
  const p = s.painted;
  const lines = [];
  if (p) lines.push(`placed: ${p.depth}`, ...p.corrections.map((c) => `corrected: ${c}`));
  lines.push(...s.holes.map((h) => `hole: ${h}`));
  if (s.constraints.length) lines.push(`the constraint rules: ${s.constraints.length} applied`);
  $("report").replaceChildren(...lines.map((l) => Object.assign(document.createElement("div"), { textContent: l, className: l.split(":")[0].replace(" ", "-") })));
  if (s.diagnostics.length) $("problem").textContent = s.diagnostics.map((d) => d.rendered || d.message).join("\n") + (s.current ? "" : "\n(the model shown is the last good one)");
  photoControls();
  if (first) fitView();
  draw();
  const meshes = await viewer.load("/api/paint/model.glb?v=" + version, [], "iso");
  if (meshes !== null) page.loads++;
}

function buttons() {
  $("undo").disabled = undo.length === 0;
  $("redo").disabled = redo.length === 0;
  $("save").disabled = !state;
}

function palette() {
  const had = component();
  const box = $("palette");
  box.replaceChildren(...state.palette.map((c, i) => {
    const l = document.createElement("label");
    l.title = `${c.name}: ${c.depth} deep${c.through ? ", into the part it is painted on (a hole)" : ""} (DEPTH_${c.name}${c.through ? ", THROUGH_" + c.name : ""})`;
    const r = Object.assign(document.createElement("input"), { type: "radio", name: "component", value: c.name, checked: had ? had === c.name : i === 0 });
    const sw = Object.assign(document.createElement("span"), { className: "swatch" });
    sw.style.background = colour(c.name);
    l.append(r, sw, c.name);
    return l;
  }));
  if (state.palette.length === 0) box.textContent = "the rules give no components (a module X needs `#define DEPTH_X d`)";
}

// ---- the plane --------------------------------------------------------------
function fitView() {
  const s = session();
  const pts = [];
  if (s) {
    for (const r of state.rects[view()]) pts.push([r[0], r[1]], [r[2], r[3]]);
    for (const ph of s.photos.filter((p) => p.view === view())) pts.push([ph.rect[0], ph.rect[1]], [ph.rect[2], ph.rect[3]]);
  }
  // At least a house's front at the origin.
  pts.push([-1, -0.5], [12, 8]);
  plane.fit(pts);
}

function draw() {
  plane.clear();
  const w = plane.world;
  if (!state) return;
  const px = plane.pixel(), v = view(), s = session();
  for (const ph of s.photos.filter((p) => p.view === v)) {
    const [u0, v0, u1, v1] = ph.rect;
    el("image", { href: photoUrl(ph.file), x: u0, y: -v1, width: u1 - u0, height: v1 - v0,
      preserveAspectRatio: "none", transform: "scale(1,-1)", opacity: $("photo-opacity").value, class: "photo" }, w);
  }
  // A metre grid and the ground.
  const [x0, y0, x1, y1] = plane.box;
  let d = "";
  for (let x = Math.ceil(x0); x <= x1; x++) d += `M${x} ${y0}V${y1}`;
  for (let y = Math.ceil(y0); y <= y1; y++) d += `M${x0} ${y}H${x1}`;
  el("path", { class: "grid", d }, w);
  if (v !== "top") el("line", { class: "ground", x1: x0, y1: 0, x2: x1, y2: 0 }, w);
  // The parts, far to near; the threshold as a band around each.
  const t = s.threshold;
  const order = state.rects[v].map((r, i) => [r, i]).sort((a, b) => a[0][4] - b[0][4]);
  for (const [r, i] of order) {
    const part = s.parts[i];
    if (t > 0) el("rect", { class: "band", x: r[0] - t, y: r[1] - t, width: r[2] - r[0] + 2 * t, height: r[3] - r[1] + 2 * t }, w);
    const rect = el("rect", { class: "part" + (i === selected ? " selected" : "") + (part.view === v ? "" : " other-view"),
      x: r[0], y: r[1], width: r[2] - r[0], height: r[3] - r[1], fill: colour(part.component) }, w);
    rect.dataset.part = i;
    rect.addEventListener("pointerdown", (e) => partDown(e, i));
    const label = el("text", { x: r[0] + 3 * px, y: -(r[3] - 3 * px), transform: "scale(1,-1)", "font-size": 11 * px, "dominant-baseline": "hanging" }, w);
    label.textContent = `${part.component} ${i + 1}`;
  }
  if (drag && drag.to) {
    const [a, b] = [drag.from, drag.to];
    el("rect", { class: "rubber", x: Math.min(a[0], b[0]), y: Math.min(a[1], b[1]), width: Math.abs(b[0] - a[0]), height: Math.abs(b[1] - a[1]) }, w);
  }
  showSelected();
}

function showSelected() {
  const box = $("selected");
  if (selected === null || !session()) { box.hidden = true; return; }
  const p = session().parts[selected];
  const size = [0, 1, 2].map((k) => round(p.max[k] - p.min[k]));
  box.hidden = false;
  box.textContent = `${p.component} ${selected + 1}, painted in the ${p.view} view: at (${p.min.map(round).join(", ")}), ${size.join(" × ")} (x × y × z). Reshape it from another view to set its depth.`;
}

function partDown(e, i) {
  const t = tool();
  if (t === "select") { selected = i; draw(); e.stopPropagation(); return; }
  if (t === "delete") {
    e.stopPropagation();
    selected = null;
    edit((next) => next.parts.splice(i, 1));
  }
}

$("plane").addEventListener("pointerdown", (e) => {
  const t = tool();
  if (t !== "paint" && t !== "reshape") return;
  if (t === "reshape" && selected === null) { $("hint").textContent = "select a part first (the select tool), then drag its rectangle in another view"; return; }
  drag = { from: plane.at(e).map(snap), to: null };
  $("plane").setPointerCapture(e.pointerId);
});

$("plane").addEventListener("pointermove", (e) => {
  if (!drag) return;
  drag.to = plane.at(e).map(snap);
  draw();
});

$("plane").addEventListener("pointerup", async () => {
  const d = drag;
  drag = null;
  if (!d || !d.to) { draw(); return; }
  const rect = [d.from[0], d.from[1], d.to[0], d.to[1]];
  if (tool() === "reshape") await paint({ part: selected, view: view(), rect });
  else if (component()) await paint({ view: view(), rect, component: component(), ...(selected !== null ? { on: selected } : {}) });
  else $("hint").textContent = "choose a component in the palette";
});

// ---- the controls ------------------------------------------------------------
document.querySelectorAll("input[name=view]").forEach((r) => r.addEventListener("change", () => { fitView(); photoControls(); draw(); }));
document.querySelectorAll("input[name=tool]").forEach((r) => r.addEventListener("change", () => {
  const hints = {
    paint: "Drag a rectangle (on a 5 cm grid): a part of the chosen component, painted on the selected part if there is one (else on the nearest it covers). Its depth comes from the rules; edges near other parts move onto them.",
    reshape: "Drag a rectangle: the selected part's size in this view (how a part painted in the front view gets its depth).",
    select: "Click a part.",
    delete: "Click a part to delete it.",
  };
  $("hint").textContent = hints[tool()];
}));
$("fit").addEventListener("click", () => { fitView(); draw(); });
$("threshold").addEventListener("change", () => {
  const t = Number($("threshold").value);
  edit((next) => { next.threshold = t; });
});
$("textures").addEventListener("change", () => {
  const on = $("textures").checked;
  edit((next) => { next.textures = on; });
});
$("threshold").addEventListener("input", () => { $("threshold-value").textContent = $("threshold").value; });
$("photo-opacity").addEventListener("input", draw);

function photoControls() {
  const s = session();
  const here = photos.filter((f) => f.startsWith(folder()) && !f.slice(folder().length).includes("/")).map((f) => f.slice(folder().length));
  $("photo").replaceChildren(new Option("none", ""), ...here.map((f) => new Option(f, f)));
  const ph = s && s.photos.find((p) => p.view === view());
  $("photo").value = ph ? ph.file : "";
  $("photo-rect").hidden = !ph;
  if (ph) $("photo-rect").querySelectorAll("input").forEach((i) => { i.value = ph.rect[Number(i.dataset.k)]; });
}

$("photo").addEventListener("change", () => {
  const file = $("photo").value, v = view();
  const others = (next) => { next.photos = next.photos.filter((p) => p.view !== v); };
  if (file) {
    // Stretched over the parts this view shows, or 12 × 8 at the origin.
    const img = new Image();
    img.onload = () => {
      const r = state.rects[v];
      const u0 = r.length ? Math.min(...r.map((q) => q[0])) : 0, v0 = r.length ? Math.min(...r.map((q) => q[1])) : 0;
      const width = r.length ? Math.max(...r.map((q) => q[2])) - u0 : 12;
      const height = width * (img.naturalHeight / img.naturalWidth || 0.66);
      edit((next) => { others(next); next.photos.push({ view: v, file, rect: [u0, v0, u0 + width, v0 + height].map(round) }); });
    };
    img.onerror = () => { $("problem").textContent = `${file} does not load as an image`; };
    img.src = photoUrl(file);
  } else edit(others);
});
$("photo-rect").querySelectorAll("input").forEach((i) => i.addEventListener("change", () => {
  const x = Number(i.value), k = Number(i.dataset.k), v = view();
  if (!Number.isFinite(x)) return;
  edit((next) => {
    const ph = next.photos.find((p) => p.view === v);
    if (ph) ph.rect[k] = x;
  });
}));

$("undo").addEventListener("click", () => call("/api/paint/edit", () => {
  if (!undo.length) return { session: session() };
  redo.push(clone(session()));
  return { session: undo.pop() };
}));
$("redo").addEventListener("click", () => call("/api/paint/edit", () => {
  if (!redo.length) return { session: session() };
  undo.push(clone(session()));
  return { session: redo.pop() };
}));
document.addEventListener("keydown", (e) => {
  if (e.target.tagName === "INPUT") return;
  if ((e.ctrlKey || e.metaKey) && e.key === "z") $(e.shiftKey ? "redo" : "undo").click();
  if ((e.key === "Delete" || e.key === "Backspace") && selected !== null) partDown({ stopPropagation() {} }, selected);
});

// ---- files -------------------------------------------------------------------
async function opened(r) {
  if (r.status !== 200) { $("problem").textContent = refusal(r.data); return; }
  undo.length = 0; redo.length = 0; selected = null; state = null;
  viewer.fitted = false;
  await show(r.data);
  $("status").textContent = "";
}

$("open").addEventListener("change", async () => {
  if ($("open").value) await opened(await api("/api/paint/open", { path: $("open").value }));
});
$("new").addEventListener("click", async () => {
  const path = $("new-path").value.trim();
  if (!path) { $("problem").textContent = "name the new session: folder/name.lsys"; return; }
  const rules = $("rules").value.split("/").pop();
  await opened(await api("/api/paint/open", { path, rules }));
});
$("save").addEventListener("click", async () => {
  const r = await api("/api/paint/save", {});
  $("status").textContent = r.status === 200 ? `saved ${r.data.saved}` : "";
  if (r.status !== 200) $("problem").textContent = r.data.error || String(r.data);
  else list();
});

async function list() {
  const r = await api("/api/paintings");
  if (r.status !== 200) return;
  const keep = $("open").value;
  $("open").replaceChildren(new Option("open session…", ""), ...r.data.sessions.map((f) => new Option(f, f)));
  $("open").value = keep;
  $("rules").replaceChildren(...r.data.rules.map((f) => new Option(f, f)));
  photos = r.data.photos;
}
list();
window.addEventListener("resize", draw);
