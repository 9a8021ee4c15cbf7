// Pailou mode's two views from the paper's editor: the layout chart drawn
// as coloured Π-shaped entrances (Sec. 4.2, Fig. 9a: a lintel and its two
// pillars per entrance, stacked upward and aligned laterally, each with
// the roof it carries) and the relation matrix (Sec. 4.1, Figs. 5C and 8:
// the active component's row in red, the kinds attached to it coloured).
import { icon } from "./icons.js";

const NS = "http://www.w3.org/2000/svg";
// One colour per entrance from the centre, G1.. (Fig. 9a colours them
// apart); upper levels of the same entrance keep its colour.
export const ENTRANCE_COLOURS = ["#c0392b", "#2e86c1", "#27ae60", "#8e44ad", "#e67e22", "#16a085"];
// Fig. 8's colours for the kinds attached to the active lintel: Toukungs
// blue, flower boards green, pillars purple, Quetis yellow.
const KIND_COLOURS = {
  middle_toukung: "#5dade2", side_toukung: "#5dade2", flower_board: "#58d68d",
  pillar: "#af7ac5", suspended_pillar: "#af7ac5", queti: "#f4d03f",
};
const SHORT = {
  clipped_roof: "RC", eaves_roof: "RE", middle_toukung: "TM", side_toukung: "TS", lintel: "L",
  pillar: "P", queti: "Q", flower_board: "FB", yundan: "Y", inscribed_board: "IB",
  suspended_pillar: "SP", pillar_base: "PB",
};

function el(name, attrs, text) {
  const e = document.createElementNS(NS, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}

// The chart in `svg`: columns are lateral places (left end to right end),
// rows the levels from the ground up.
export function drawChart(svg, entrances) {
  svg.replaceChildren();
  if (!entrances || !entrances.length) return;
  const half = Math.max(...entrances.map((e) => e.i));
  const levels = Math.max(...entrances.map((e) => e.j));
  const cell = 64, storey = 58, top = 30;
  const width = (2 * half - 1) * cell, height = top + levels * storey + 22;
  svg.setAttribute("viewBox", `0 0 ${width} ${height}`);
  const column = (e) => (e.side < 0 ? half - e.i : half - 2 + e.i);
  for (const e of entrances) {
    const colour = ENTRANCE_COLOURS[(e.i - 1) % ENTRANCE_COLOURS.length];
    const cx = column(e) * cell + cell / 2;
    const w = e.j === 1 ? cell * (e.i === 1 ? 0.8 : 0.7) : cell * 0.5;
    const base = top + levels * storey - (e.j - 1) * storey;
    const h = storey - 24;
    const g = el("g", { class: "entrance", "data-name": e.name });
    g.appendChild(el("title", {}, `${e.name}: entrance ${e.i} from the centre, level ${e.j}; roof: ${e.roof}` +
      (e.toukungs ? ", Toukungs" : "") + (e.flower_board ? ", flower board" : "") + (e.inscribed_board ? ", inscribed board" : "")));
    const line = (x1, y1, x2, y2, wdt = 4) => g.appendChild(el("line", { x1, y1, x2, y2, stroke: colour, "stroke-width": wdt, "stroke-linecap": "round" }));
    line(cx - w / 2, base, cx - w / 2, base - h);        // pillars
    line(cx + w / 2, base, cx + w / 2, base - h);
    line(cx - w / 2 - 4, base - h, cx + w / 2 + 4, base - h, 5);  // lintel
    const r = base - h - 4;
    if (e.roof === "eaves")
      g.appendChild(el("path", { class: "roof eaves", d: `M${cx - w / 2 - 10} ${r - 2} q6 0 10 -10 h${w - 0} q4 10 10 10 z` }));
    else if (e.roof === "clipped")
      g.appendChild(el("rect", { class: "roof clipped", x: cx - w / 2 - 4, y: r - 8, width: w + 8, height: 8 }));
    if (e.side_clipped)
      for (const s of [-1, 1]) g.appendChild(el("rect", { class: "roof clipped", x: cx + s * (w / 2 + 8) - 6, y: r - 22, width: 12, height: 6 }));
    // Over the outer pillar: both of the central entrance's.
    if (e.pillar_roof)
      for (const s of e.side === 0 ? [-1, 1] : [e.side]) {
        const x = cx + s * (w / 2);
        g.appendChild(el("rect", { class: "roof clipped", x: x - 6, y: base - h - 14, width: 12, height: 6 }));
      }
    g.appendChild(el("text", { x: cx, y: base - 4, fill: colour }, e.name));
    svg.appendChild(g);
  }
}

// The matrix in `table`: rows are hosts, columns what may attach (1 at
// (lintel, middle Toukung): a middle Toukung may link to a lintel). The
// active component's row is marked, the kinds attached to it coloured, and
// the cells of `pairs` ([row, column] kinds) outlined.
export function drawMatrix(table, matrix, activeKind, attachedKinds, pairs) {
  const paired = new Set(pairs.map(([r, c]) => `${r} ${c}`));
  if (!matrix) return;
  const head = `<tr><th></th>${matrix.kinds.map((k) => `<th title="${k.replace(/_/g, " ")}"><svg viewBox="-24 -24 48 48" width="16" height="16">${icon(k)}</svg><br>${SHORT[k] || k}</th>`).join("")}</tr>`;
  const rows = matrix.kinds.map((row) => {
    const accepts = new Set(matrix.accepts[row] || []);
    const active = row === activeKind;
    const cells = matrix.kinds.map((col) => {
      const cls = [];
      let style = "";
      if (active && attachedKinds.has(col) && accepts.has(col)) { cls.push("attached"); style = ` style="background:${KIND_COLOURS[col] || "#d5d8dc"}"`; }
      if (paired.has(`${row} ${col}`)) cls.push("pair");
      return `<td class="${cls.join(" ")}" data-row="${row}" data-col="${col}"${style}>${accepts.has(col) ? 1 : 0}</td>`;
    }).join("");
    return `<tr class="${active ? "active-row" : ""}"><th title="${row.replace(/_/g, " ")}">${SHORT[row] || row}</th>${cells}</tr>`;
  }).join("");
  table.innerHTML = head + rows;
}
