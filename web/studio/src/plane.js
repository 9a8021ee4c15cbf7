// The studio's 2D plane (the guides and painting pages): an SVG whose
// world group is y up, a box of the world it shows, and the conversions
// between the pointer and world coordinates.
const NS = "http://www.w3.org/2000/svg";

// An SVG element with `attrs`, appended to `parent`.
export function el(name, attrs, parent) {
  const e = document.createElementNS(NS, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (parent) parent.appendChild(e);
  return e;
}

export class Plane {
  constructor(svg, world) {
    this.svg = svg;
    this.world = world;
    this.box = [-5, -5, 5, 5]; // x0, y0, x1, y1 shown
  }

  // Shows the points' extent with a margin (a 10-unit square around the
  // origin when there are none).
  fit(pts) {
    if (pts.length === 0) { this.box = [-5, -5, 5, 5]; return; }
    let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
    for (const [x, y] of pts) { x0 = Math.min(x0, x); y0 = Math.min(y0, y); x1 = Math.max(x1, x); y1 = Math.max(y1, y); }
    const m = Math.max(x1 - x0, y1 - y0, 1) * 0.08;
    this.box = [x0 - m, y0 - m, x1 + m, y1 + m];
  }

  // World units per screen pixel.
  pixel() {
    const b = this.box;
    return Math.max((b[2] - b[0]) / (this.svg.clientWidth || 1), (b[3] - b[1]) / (this.svg.clientHeight || 1));
  }

  // The pointer event's point in the world.
  at(e) {
    const m = this.world.getScreenCTM().inverse();
    const p = new DOMPoint(e.clientX, e.clientY).matrixTransform(m);
    return [p.x, p.y];
  }

  // Clears the world group and sets the view box (y up).
  clear() {
    const b = this.box;
    this.svg.setAttribute("viewBox", `${b[0]} ${-b[3]} ${b[2] - b[0]} ${b[3] - b[1]}`);
    this.world.setAttribute("transform", "scale(1,-1)");
    this.world.replaceChildren();
  }
}
