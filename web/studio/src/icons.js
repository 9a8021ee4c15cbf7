// One small SVG glyph per component kind (drawn in a 48×48 box centred on
// 0,0), after the paper's iconized graph (Fig. 5): the shape says the kind.
const P = (d) => `<path class="icon" d="${d}"/>`;
const ICONS = {
  pillar: P("M-5 -18h10v36h-10z"),
  suspended_pillar: P("M-4 -16h8v26h-8z M-8 10h16v3h-16z"),
  lintel: P("M-20 -4h40v8h-40z"),
  pillar_base: P("M-8 -6h16l5 12h-26z"),
  flower_board: P("M-18 -8h36v16h-36z") + `<circle class="icon" cx="0" cy="0" r="5" fill="#f3d36b"/>`,
  queti: P("M-16 -6h32l-26 12z"),
  yundan: `<circle class="icon" cx="-7" cy="0" r="6"/><circle class="icon" cx="5" cy="-2" r="7"/><circle class="icon" cx="12" cy="4" r="4"/>`,
  inscribed_board: P("M-12 -16h24v32h-24z") + `<path d="M-6 -8h12M-6 0h12M-6 8h12" stroke="#f5e9d8" stroke-width="2"/>`,
  middle_toukung: P("M-4 8h8v6h-8z M-10 2h20v5h-20z M-15 -4h30v5h-30z M-20 -10h40v5h-40z"),
  side_toukung: P("M0 14l-18 -22h6l12 15 12 -15h6z M-3 10h6v6h-6z"),
  clipped_roof: P("M-20 8h40l-8 -16h-24z"),
  eaves_roof: P("M-22 6q4 -2 8 -12h28q4 10 8 12q-6 0 -8 -2h-28q-2 2 -8 2z"),
};
export function icon(kind) {
  return ICONS[kind] || `<circle class="icon" r="10"/>`;
}
