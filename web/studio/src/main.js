// lsys studio's page: the component graph (SVG icons), the palette and
// parameters from the server's state, and a three.js view of the GLB the
// server builds. Every change goes to the server; the server's state is
// drawn again (docs/studio.md).
import { Viewer } from "./viewer.js";
import { icon } from "./icons.js";
import { drawChart, drawMatrix } from "./chart.js";
import { api } from "./api.js";

const $ = (id) => document.getElementById(id);
const NS = "http://www.w3.org/2000/svg";
// What the browser tests read.
// `edits` counts the edits whose answer (and its model) has been drawn.
const studio = (window.studio = { parts: 0, version: 0, loads: 0, loading: 0, edits: 0, state: null, refused: null });

// ---- 3D view ------------------------------------------------------------
const viewer = new Viewer($("canvas"));
document.querySelectorAll("#views button").forEach((b) => b.addEventListener("click", () => viewer.view(b.dataset.view)));

async function loadModel(problemParts) {
  // `loading`: model loads under way (a big one takes seconds to parse).
  studio.loading++;
  let meshes;
  try {
    meshes = await viewer.load("/api/model.glb?v=" + studio.version, problemParts);
  } finally {
    studio.loading--;
  }
  if (meshes === null) return;
  studio.parts = meshes;
  studio.loads++;
  $("parts").textContent = `${meshes} drawn parts`;
  $("parts").dataset.parts = meshes;
}

// ---- Pailou mode ----------------------------------------------------------
let dragging = null;
// The grammar's drawing symbols and the graph kinds they draw
// (src/pailou/kinds.rs).
const SYMBOL_KIND = {
  MP: "pillar", ML: "lintel", MLS: "lintel", MLO: "lintel", MPB: "pillar_base", MFB: "flower_board",
  MQ: "queti", MY: "yundan", MIB: "inscribed_board", TM: "middle_toukung", TS: "side_toukung",
  RC: "clipped_roof", RE: "eaves_roof",
};
// Edits in flight: their own answer redraws, so pushed updates wait.
let pending = 0;
function drawGraph(s) {
  const svg = $("graph");
  svg.replaceChildren();
  const at = Object.fromEntries(s.components.map((c) => [c.id, c]));
  // Collapsed entrances hide what rests on their lintel (all the way up).
  const hidden = new Set();
  const under = (id) => s.components.filter((c) => c.on.includes(id)).map((c) => c.id);
  const countUnder = (id) => {
    const seen = new Set(), stack = under(id);
    while (stack.length) { const u = stack.pop(); if (!seen.has(u)) { seen.add(u); stack.push(...under(u)); } }
    return seen.size;
  };
  for (const id of collapsed) {
    if (!at[id]) continue;
    const stack = under(id);
    while (stack.length) { const u = stack.pop(); if (!hidden.has(u)) { hidden.add(u); stack.push(...under(u)); } }
  }
  const shown = s.components.filter((c) => !hidden.has(c.id));
  const xs = shown.map((c) => c.x), ys = shown.map((c) => c.y);
  const pad = 50;
  const minx = Math.min(...xs, -200) - pad, maxx = Math.max(...xs, 200) + pad;
  const miny = Math.min(...ys, 200) - pad, maxy = Math.max(...ys, 460) + pad;
  fit = { x: minx, y: miny, w: maxx - minx, h: maxy - miny };
  setViewBox(svg);
  // Kinds named by the structural problems (their GLB parts are
  // `SYMBOL#n`), and the component where a placement was refused.
  const warned = new Set(s.problems.flatMap((p) => p.parts.map((n) => SYMBOL_KIND[n.split("#")[0]])));
  const refusedAt = studio.refused && studio.refused.at;
  for (const c of shown)
    for (const t of c.on) {
      if (!at[t] || hidden.has(t)) continue;
      const l = document.createElementNS(NS, "line");
      l.setAttribute("class", "edge");
      l.setAttribute("x1", c.x); l.setAttribute("y1", c.y);
      l.setAttribute("x2", at[t].x); l.setAttribute("y2", at[t].y);
      l.dataset.from = c.id; l.dataset.to = t;
      svg.appendChild(l);
    }
  for (const c of shown) {
    const g = document.createElementNS(NS, "g");
    g.setAttribute("class", "node" + (c.id === s.active ? " active" : "") + (warned.has(c.kind) || c.id === refusedAt ? " warn" : ""));
    g.setAttribute("transform", `translate(${c.x},${c.y})`);
    g.dataset.id = c.id;
    g.dataset.kind = c.kind;
    const folded = collapsed.has(c.id) ? under(c.id).length && countUnder(c.id) : 0;
    g.innerHTML = `<rect class="box" x="-24" y="-24" width="48" height="48" rx="6"></rect>${icon(c.kind)}<text y="36">${c.id}</text><title>${c.id}: ${c.kind.replace("_", " ")}${c.kind === "lintel" ? " (double-click: collapse or open what rests on it)" : ""}</title>` +
      (folded ? `<g class="badge"><circle cx="22" cy="-22" r="11"></circle><text x="22" y="-18">+${folded}</text></g>` : "");

    g.addEventListener("pointerdown", (e) => {
      dragging = { id: c.id, g, x0: e.clientX, y0: e.clientY, cx: c.x, cy: c.y, moved: false };
      svg.setPointerCapture(e.pointerId);
    });
    svg.appendChild(g);
  }
  svg.dataset.warned = [...warned].join(" ");
}
// Zoom (the wheel, about the pointer) and pan (drag the background) of the
// graph, so that a Pailou of 200 components stays readable; "fit" shows
// it all again.
let fit = { x: -250, y: 150, w: 500, h: 360 };
let zoom = { k: 1, x: 0, y: 0 };  // scale, and the view's centre offset from the fit's
let collapsed = new Set();
function setViewBox(svg) {
  const w = fit.w / zoom.k, h = fit.h / zoom.k;
  const cx = fit.x + fit.w / 2 + zoom.x, cy = fit.y + fit.h / 2 + zoom.y;
  svg.setAttribute("viewBox", `${cx - w / 2} ${cy - h / 2} ${w} ${h}`);
  svg.dataset.zoom = zoom.k.toFixed(3);
}
$("graph").addEventListener("wheel", (e) => {
  e.preventDefault();
  const svg = $("graph"), vb = svg.viewBox.baseVal, r = svg.getBoundingClientRect();
  // The point under the pointer stays put.
  const px = vb.x + ((e.clientX - r.left) / r.width) * vb.width, py = vb.y + ((e.clientY - r.top) / r.height) * vb.height;
  const k = Math.min(20, Math.max(0.5, zoom.k * Math.pow(1.2, -Math.sign(e.deltaY))));
  const f = zoom.k / k;
  const cx = fit.x + fit.w / 2 + zoom.x, cy = fit.y + fit.h / 2 + zoom.y;
  zoom = { k, x: zoom.x + (px - cx) * (1 - f), y: zoom.y + (py - cy) * (1 - f) };
  setViewBox(svg);
}, { passive: false });
let panning = null;
$("graph").addEventListener("pointerdown", (e) => {
  if (e.target.closest("g.node")) return;
  panning = { x0: e.clientX, y0: e.clientY, zx: zoom.x, zy: zoom.y };
  $("graph").setPointerCapture(e.pointerId);
});
$("graph").addEventListener("dblclick", (e) => {
  // The pointer is captured by the graph while a click runs: the node is
  // the one under it.
  const g = document.elementsFromPoint(e.clientX, e.clientY).map((el) => el.closest("g.node")).find(Boolean);
  if (!g || g.dataset.kind !== "lintel") return;
  const id = g.dataset.id;
  if (collapsed.has(id)) collapsed.delete(id); else collapsed.add(id);
  drawGraph(studio.state);
});
$("graph-fit").addEventListener("click", () => { zoom = { k: 1, x: 0, y: 0 }; collapsed.clear(); drawGraph(studio.state); });
$("graph").addEventListener("pointermove", (e) => {
  if (panning) {
    const svg = $("graph"), k = svg.viewBox.baseVal.width / svg.clientWidth;
    zoom.x = panning.zx - (e.clientX - panning.x0) * k;
    zoom.y = panning.zy - (e.clientY - panning.y0) * k;
    setViewBox(svg);
    return;
  }
  if (!dragging) return;
  const svg = $("graph");
  const k = svg.viewBox.baseVal.width / svg.clientWidth;
  const dx = (e.clientX - dragging.x0) * k, dy = (e.clientY - dragging.y0) * k;
  if (Math.abs(dx) + Math.abs(dy) > 3) dragging.moved = true;
  dragging.x = dragging.cx + dx; dragging.y = dragging.cy + dy;
  dragging.g.setAttribute("transform", `translate(${dragging.x},${dragging.y})`);
  svg.querySelectorAll(`line[data-from="${dragging.id}"]`).forEach((l) => { l.setAttribute("x1", dragging.x); l.setAttribute("y1", dragging.y); });
  svg.querySelectorAll(`line[data-to="${dragging.id}"]`).forEach((l) => { l.setAttribute("x2", dragging.x); l.setAttribute("y2", dragging.y); });
});
$("graph").addEventListener("pointerup", async () => {
  panning = null;
  const d = dragging;
  dragging = null;
  if (!d) return;
  if (d.moved) await edit({ op: "move", id: d.id, x: d.x, y: d.y });
  else await edit({ op: "select", id: d.id });
});

// name, meaning, default, range and step of the Pailou grammar's sliders.
const PARAMS = [
  ["ω", "ground pillar height of the central entrance", 9, 2, 30, 0.5],
  ["αUp", "an entrance above / the one below", 0.5, 0.2, 1, 0.01],
  ["αSide", "an entrance beside / the inner one", 0.8, 0.3, 1, 0.01],
  ["αEW", "entrance width / pillar height", 0.8333, 0.4, 1.5, 0.01],
  ["αPW", "pillar width / pillar height", 0.1148, 0.05, 0.2, 0.001],
  ["αLW", "Toukung row / entrance width", 1, 0.5, 1.5, 0.01],
  ["NTL", "Toukung levels", 5, 3, 9, 1],
];
function drawParams(s) {
  const box = $("params");
  if (box.dataset.built !== "1") {
    box.innerHTML = PARAMS.map(([n, title, v, lo, hi, step]) =>
      `<label title="${title}">${n}<input type="range" data-name="${n}" min="${lo}" max="${hi}" step="${step}" value="${v}"><output></output></label>`).join("");
    box.querySelectorAll("input").forEach((i) => {
      i.addEventListener("input", () => (i.nextElementSibling.textContent = i.value));
      i.addEventListener("change", () => edit({ op: "define", name: i.dataset.name, value: Number(i.value) }));
    });
    box.dataset.built = "1";
  }
  box.querySelectorAll("input").forEach((i) => {
    const v = s.defines[i.dataset.name];
    if (v !== undefined) i.value = v;
    i.nextElementSibling.textContent = v === undefined ? "default" : v;
  });
  drawEntranceParams(s);
}

// The active component's entrance's own ratios (the paper's α^Up_ij and
// α^Side_ij: the grammar's `up[i,j]` and `side[i-1]` tables) and the
// sizes of its kind at that entrance (α^XW_ij, α^XH_ij, α^XD_ij: `pw`,
// `lh`, `lw`, `tk`, `rd`, `rh`), set as defines of the graph; both halves
// (the grammar mirrors one). Slider bounds lie inside the server's ranges
// (src/pailou/ranges.rs); the fallback is the grammar's global default.
const SIZES = {
  pw: ["αPW", 7 / 61, 0.05, 0.3, "pillar diameter / pillar height"],
  lh: ["αLH", 6 / 7, 0.4, 1.5, "big lintel's height / pillar diameter"],
  lw: ["αLW", 1, 0.5, 1.5, "Toukung row's length / entrance width"],
  tk: ["κT", 0.12, 0.05, 0.25, "Toukung size per unit of column height"],
  rd: ["αRD", 0.45, 0.2, 1, "roof depth per unit of column height"],
  rh: ["αRH", 0.25, 0.1, 0.6, "roof height per unit of column height"],
};
const SIZES_OF = {
  pillar: ["pw"], suspended_pillar: ["pw"], pillar_base: ["pw"],
  lintel: ["lh"], flower_board: ["lh"], inscribed_board: ["lh"], queti: ["lh"], yundan: ["lh"],
  middle_toukung: ["tk", "lw"], side_toukung: ["tk", "lw"],
  eaves_roof: ["rd", "rh"], clipped_roof: ["rd", "rh"],
};

function drawEntranceParams(s) {
  const box = $("entrance-params");
  const at = (s.entrance_of || {})[s.active];
  box.replaceChildren();
  if (!at) { box.textContent = "select a component for its entrance's ratios and sizes"; return; }
  const [i, j] = at;
  const kind = (s.components.find((c) => c.id === s.active) || {}).kind || "";
  const field = (name, title, fallback, min = 0.2, max = 1) => {
    const v = s.defines[name];
    const l = document.createElement("label");
    l.title = title;
    l.innerHTML = `${name}<input type="range" data-entrance="${name}" min="${min}" max="${max}" step="0.005"><output></output>`;
    const input = l.querySelector("input"), out = l.querySelector("output");
    input.value = v !== undefined ? v : fallback;
    out.textContent = v !== undefined ? v : "as all";
    input.addEventListener("input", () => (out.textContent = input.value));
    input.addEventListener("change", () => edit({ op: "define", name, value: Number(input.value) }));
    const reset = document.createElement("button");
    reset.textContent = "as all";
    reset.disabled = v === undefined;
    reset.addEventListener("click", () => edit({ op: "define", name, value: null }));
    box.append(l, reset);
  };
  const head = document.createElement("div");
  head.textContent = `entrance G${i}${j} (both halves)`;
  box.append(head);
  if (j > 1) field(`up[${i},${j}]`, "this entrance's pillar height / the one below (αUp of this entrance)", s.defines["αUp"] ?? 0.5);
  else if (i > 1) field(`side[${i - 1}]`, "this entrance's pillar height / the inner one (αSide of this entrance)", s.defines["αSide"] ?? 0.8);
  else box.append("the central entrance: ω sets its height");
  const sizes = SIZES_OF[kind] || [];
  if (sizes.length) {
    const sub = document.createElement("div");
    sub.textContent = `${kind.replace("_", " ")}s of G${i}${j}`;
    box.append(sub);
  }
  for (const t of sizes) {
    const [ratio, dflt, min, max, what] = SIZES[t];
    field(`${t}[${i},${j}]`, `${what} at this entrance (${ratio} of this entrance)`, s.defines[ratio] ?? dflt, min, max);
  }
}

function showPailou(s) {
  drawGraph(s);
  $("active").textContent = `${s.active} (${(s.components.find((c) => c.id === s.active) || {}).kind || ""})`;
  $("palette").replaceChildren(...s.palette.map((k) => {
    const b = document.createElement("button");
    b.dataset.kind = k;
    b.innerHTML = `<svg viewBox="-24 -24 48 48" width="22" height="22">${icon(k)}</svg> add ${k.replace("_", " ")}`;
    b.addEventListener("click", () => edit({ op: "add", id: s.active, kind: k }));
    b.addEventListener("pointerenter", () => matrixOf(s, k));
    b.addEventListener("pointerleave", () => matrixOf(s, null));
    return b;
  }));
  matrixOf(s, null);
  drawChart($("layout-chart"), s.entrances);
  $("type").value = s.type;
  $("chart").textContent = s.chart;
  $("unplaced").replaceChildren(...s.unplaced.map((u) => Object.assign(document.createElement("li"), { textContent: u })));
  if (s.error) showRefused(s.error); else if (!studio.refused) $("refused").hidden = true;
  drawParams(s);
}

// The relation matrix: the active component's row; outlined, the cell of
// each host it attaches to and its kind (the pair that made it legal),
// and the palette kind under the pointer.
function matrixOf(s, hovered) {
  const active = s.components.find((c) => c.id === s.active);
  const kind = active && active.kind;
  const attached = new Set(s.components.filter((c) => c.on.includes(s.active)).map((c) => c.kind));
  const kindOf = Object.fromEntries(s.components.map((c) => [c.id, c.kind]));
  const pairs = (active ? active.on : []).map((h) => [kindOf[h], kind]);
  if (hovered) pairs.push([kind, hovered]);
  drawMatrix($("matrix"), s.matrix, kind, attached, pairs);
}

function showRefused(e) {
  studio.refused = e;
  $("refused").hidden = false;
  $("refused").textContent = e.rendered || e.message || JSON.stringify(e);
}

async function edit(body) {
  // The page stays live while the server builds (large models take a while).
  if (body.op !== "move" && body.op !== "select") $("status").textContent = "building…";
  // A new style is a new graph: what was collapsed named the old one's
  // lintels (a lintel of the same id in the new graph stays open).
  if (body.op === "style") collapsed.clear();
  pending++;
  try {
    const r = await api("/api/edit", body);
    if (r.status === 422) showRefused(r.data.refused);
    else { studio.refused = null; $("refused").hidden = true; }
    if (r.data && r.data.state) await show(r.data.state, body.op !== "move" && body.op !== "select");
  } finally {
    pending--;
    studio.edits++;
  }
}
$("remove").addEventListener("click", () => edit({ op: "remove", id: studio.state.active }));
$("duplicate").addEventListener("click", () => edit({ op: "duplicate", id: studio.state.active }));
$("duplicate-up").addEventListener("click", () => edit({ op: "duplicate_up", id: studio.state.active }));
$("type").addEventListener("change", () => edit({ op: "type", value: $("type").value }));
$("apply-style").addEventListener("click", () => edit({ op: "style", style: $("style").value.trim(), type: $("type").value }));

// ---- grammar mode ---------------------------------------------------------
function showGrammar(s) {
  $("diagnostics").replaceChildren(...s.diagnostics.map((d) => {
    const div = document.createElement("div");
    div.className = "diag " + d.severity;
    div.dataset.code = d.code;
    div.textContent = `${d.file}:${d.line}:${d.col} ${d.code}\n${d.rendered}`;
    return div;
  }));
  if (!s.diagnostics.length) $("diagnostics").textContent = "no diagnostics";
  const step = $("step");
  step.max = Math.max(s.length, s.step, 1);
  step.value = s.step;
  $("step-value").textContent = `${s.step} of ${s.length}`;
  const box = $("grammar-defines");
  if (box.dataset.file !== s.file || box.children.length !== s.defines.length) {
    box.dataset.file = s.file;
    box.replaceChildren(...s.defines.map((d) => {
      const l = document.createElement("label");
      const input = d.range
        ? `<input type="range" data-name="${d.name}" min="${d.range[0]}" max="${d.range[1]}" step="${d.integer ? 1 : (d.range[1] - d.range[0]) / 100}" value="${d.override ?? d.number}">`
        : `<input data-name="${d.name}" value="${d.override ?? d.value}">`;
      l.innerHTML = `${d.name}${input}<output>${d.override ?? d.value}</output>`;
      return l;
    }));
    box.querySelectorAll("input").forEach((i) => {
      i.addEventListener("input", () => (i.nextElementSibling.textContent = i.value));
      i.addEventListener("change", sendGrammar);
    });
  }
  // A saved file's new values move the sliders not set on the page.
  for (const d of s.defines) {
    const i = box.querySelector(`input[data-name="${CSS.escape(d.name)}"]`);
    if (i && d.override == null && document.activeElement !== i) { i.value = i.type === "range" ? d.number : d.value; i.nextElementSibling.textContent = d.value; }
  }
}
function sendGrammar() {
  $("status").textContent = "building…";
  const defines = {};
  $("grammar-defines").querySelectorAll("input").forEach((i) => {
    const d = studio.state.defines.find((x) => x.name === i.dataset.name);
    if (!d) return;
    // A slider differs from the file's value (7/61 is a number there).
    const changed = i.type === "range"
      ? Math.abs(Number(i.value) - d.number) > 1e-9 * Math.max(1, Math.abs(d.number))
      : String(i.value) !== String(d.value);
    if (changed) defines[i.dataset.name] = i.type === "range" ? Number(i.value) : i.value;
  });
  return api("/api/grammar", { defines, step: Number($("step").value) }).then((r) => show(r.data, true));
}
$("step").addEventListener("input", () => ($("step-value").textContent = $("step").value));
$("step").addEventListener("change", sendGrammar);

// ---- both -------------------------------------------------------------------
async function show(s, reload) {
  studio.state = s;
  studio.version = s.version;
  const pailou = s.mode === "pailou";
  $("mode").textContent = pailou ? "Pailou editor" : "grammar preview";
  $("file").textContent = s.file || "(default entrance, not saved)";
  for (const id of ["pailou-left", "pailou-right", "save", "export-toml"]) $(id).hidden = !pailou;
  $("grammar-left").hidden = pailou;
  document.querySelector("main").classList.toggle("grammar", !pailou);
  if (pailou) showPailou(s); else showGrammar(s);
  const problems = s.problems || [];
  $("problems").replaceChildren(...problems.map((p) => Object.assign(document.createElement("div"), { textContent: "⚠ " + p.message })));
  $("status").textContent = `${s.parts} component instances, ${s.triangles} triangles`;
  if (reload) await loadModel(problems.flatMap((p) => p.parts));
}

$("save").addEventListener("click", async () => {
  const name = prompt("Save the graph as (a .toml in the opened folder):", studio.state.file || "pailou.toml");
  if (!name) return;
  let r = await api("/api/save", { path: name });
  // Another graph of that name: replaced only when the user says so.
  if (r.status === 409 && r.data.exists && confirm(`${name} is another graph. Replace it?`)) {
    r = await api("/api/save", { path: name, replace: true });
  }
  $("status").textContent = r.status === 200 ? `saved ${name}` : `not saved: ${r.data.error || r.data}`;
  refreshFiles();
});
// Downloads without leaving the page: a refusal is shown in the status line.
document.querySelectorAll(".exports a").forEach((a) => a.addEventListener("click", async (e) => {
  e.preventDefault();
  const format = a.dataset.format;
  const r = await fetch(`/api/export?format=${format}`);
  if (!r.ok) {
    $("status").textContent = `not exported: ${(await r.text()).trim()}`;
    return;
  }
  const link = Object.assign(document.createElement("a"), {
    href: URL.createObjectURL(await r.blob()),
    download: `studio.${format}`,
  });
  link.click();
  setTimeout(() => URL.revokeObjectURL(link.href), 10000);
}));
async function refreshFiles() {
  const r = await api("/api/files");
  $("open").replaceChildren(new Option("open…", ""), ...r.data.files.map((f) => new Option(f, f)));
}
$("open").addEventListener("change", async () => {
  const f = $("open").value;
  if (!f) return;
  const r = await api("/api/open", { path: f });
  viewer.fitted = false;
  if (r.status === 200) collapsed.clear();
  if (r.status === 200) await show(r.data, true);
  else $("status").textContent = r.data.error || r.data;
});

// Updates pushed by the server (a saved grammar file, another tab's edit).
const events = new EventSource("/api/events");
events.addEventListener("update", async (e) => {
  if (Number(e.data) === studio.version || pending > 0) return;
  const r = await api("/api/state");
  // An edit's own answer may have drawn a newer state meanwhile.
  if (pending > 0 || r.data.version < studio.version) return;
  await show(r.data, true);
});

viewer.resize();
api("/api/state").then((r) => show(r.data, true));
refreshFiles();
