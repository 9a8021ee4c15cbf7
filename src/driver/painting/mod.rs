//! A painting session (seed 004's interface, docs/studio.md "The painting
//! page"): a rectangle painted in one of five views and the component it
//! stands for -> a part, a box in the world, whose third dimension comes
//! from the rules' configure rules and whose edges the automatic
//! correction moves onto the parts near them; and the constraint report
//! of the holes the parts will cut.
//!
//! The rules (a `.rules` file of productions, included by the session's
//! `.lsys`; `file.rs` writes and reads that file) say which
//! components the palette offers and how deep each is: a component is a
//! module `X` with a `#define DEPTH_X d` (its depth, the configure rule of
//! the dimension a view does not show), and `#define THROUGH_X 1` makes it
//! go that deep into the part it is painted on, from the face the view
//! shows, instead of standing in front of it (RAAM: "a window or a door
//! component always has a same dimension value of p with the wall it
//! belongs to") — those are the components whose rule cuts a hole. A part
//! painted on nothing but standing on a part (its bottom edge on that
//! part's top, within the threshold) takes that part's depth: "the bottom
//! of a roof component always has the same size with the top of the
//! corresponding body component".

use serde::{Deserialize, Serialize};

mod correct;
mod file;
#[cfg(test)]
mod tests;

use correct::{correct, overlap, standing_on};
pub use file::{PaintDoc, PaintFileError, Photo};

/// One of the five views the page paints in (seed 004, Sec 4: "front,
/// back, up, left and right").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PaintView {
    Front,
    Back,
    Top,
    Left,
    Right,
}

/// A world axis seen from a view: which one and which way.
#[derive(Clone, Copy, Debug)]
struct Axis {
    index: usize,
    sign: f64,
}

impl PaintView {
    pub const ALL: [PaintView; 5] = [
        PaintView::Front,
        PaintView::Back,
        PaintView::Top,
        PaintView::Left,
        PaintView::Right,
    ];

    pub fn name(self) -> &'static str {
        match self {
            PaintView::Front => "front",
            PaintView::Back => "back",
            PaintView::Top => "top",
            PaintView::Left => "left",
            PaintView::Right => "right",
        }
    }

    pub fn from_name(s: &str) -> Option<PaintView> {
        PaintView::ALL.into_iter().find(|v| v.name() == s)
    }

    /// The turtle's turn from the start frame (heading y, up z) to the
    /// view's frame (`tests`: each view's box is where the turtle draws it).
    pub fn turn(self) -> &'static str {
        match self {
            PaintView::Front => "",
            PaintView::Back => "/(180) ",
            PaintView::Left => "/(-90) ",
            PaintView::Right => "/(90) ",
            PaintView::Top => "&(90) ",
        }
    }

    /// The view's right (u), up (v) and toward-the-viewer (w) axes. The
    /// world is y up, z toward the front viewer; each view looks at the
    /// model from outside, so its u × v is w.
    fn axes(self) -> [Axis; 3] {
        let a = |index, sign| Axis { index, sign };
        match self {
            PaintView::Front => [a(0, 1.0), a(1, 1.0), a(2, 1.0)],
            PaintView::Back => [a(0, -1.0), a(1, 1.0), a(2, -1.0)],
            // From above: x right, the back (−z) up the screen.
            PaintView::Top => [a(0, 1.0), a(2, -1.0), a(1, 1.0)],
            // From the left (−x): z right.
            PaintView::Left => [a(2, 1.0), a(1, 1.0), a(0, -1.0)],
            PaintView::Right => [a(2, -1.0), a(1, 1.0), a(0, 1.0)],
        }
    }
}

/// A component of the palette: a module of the rules.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Component {
    pub name: String,
    /// `DEPTH_<name>`: its depth when nothing else gives it.
    pub depth: f64,
    /// `THROUGH_<name>` non-zero: it takes the depth of the part it is
    /// painted on (windows and doors, whose rules cut holes).
    pub through: bool,
}

/// The palette of a compiled session: every `DEPTH_X` define is a
/// component `X`, in the order the defines come.
pub fn palette(defines: &[(String, f64)]) -> Vec<Component> {
    defines
        .iter()
        .filter_map(|(name, depth)| {
            let c = name.strip_prefix("DEPTH_")?;
            let through = defines
                .iter()
                .any(|(n, v)| *v != 0.0 && n.strip_prefix("THROUGH_") == Some(c));
            Some(Component {
                name: c.to_string(),
                depth: *depth,
                through,
            })
        })
        .collect()
}

/// A painted part: a component in a box (world coordinates, y up).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Part {
    pub component: String,
    /// The view it was painted in (written beside it in the file).
    pub view: PaintView,
    pub min: [f64; 3],
    pub max: [f64; 3],
}

impl Part {
    /// Its rectangle in `view`: `[u0, v0, u1, v1]`, u0 ≤ u1, v0 ≤ v1.
    pub fn rect(&self, view: PaintView) -> [f64; 4] {
        let [u, v, _] = view.axes();
        let (u0, u1) = self.span(u);
        let (v0, v1) = self.span(v);
        [u0, v0, u1, v1]
    }

    /// How near the viewer of `view` its front is (to draw the parts in
    /// a view back to front).
    pub fn front(&self, view: PaintView) -> f64 {
        self.span(view.axes()[2]).1
    }

    /// Its extent along a view's axis, in that axis's direction.
    fn span(&self, a: Axis) -> (f64, f64) {
        let (lo, hi) = (self.min[a.index] * a.sign, self.max[a.index] * a.sign);
        (lo.min(hi), lo.max(hi))
    }

    /// Where its construction rule draws it: the scope's corner, the
    /// turtle's turn that makes the scope's x, y and z the view's right,
    /// up and toward the viewer (so that a component's front faces the
    /// view it was painted in), and the scope's size.
    pub fn scope(&self) -> ([f64; 3], &'static str, [f64; 3]) {
        let axes = self.view.axes();
        let mut corner = [0.0; 3];
        let mut size = [0.0; 3];
        for (k, a) in axes.iter().enumerate() {
            corner[a.index] = if a.sign > 0.0 {
                self.min[a.index]
            } else {
                self.max[a.index]
            };
            size[k] = self.max[a.index] - self.min[a.index];
        }
        (corner, self.view.turn(), size)
    }

    /// The part drawn by [`Part::scope`]'s corner and size.
    pub fn from_scope(
        component: String,
        view: PaintView,
        corner: [f64; 3],
        size: [f64; 3],
    ) -> Part {
        let mut p = Part {
            component,
            view,
            min: corner,
            max: corner,
        };
        for (k, a) in view.axes().iter().enumerate() {
            let far = corner[a.index] + a.sign * size[k];
            p.min[a.index] = corner[a.index].min(far);
            p.max[a.index] = corner[a.index].max(far);
        }
        p
    }

    /// Sets its extent along a view's axis (given in that direction).
    fn set_span(&mut self, a: Axis, (lo, hi): (f64, f64)) {
        let (x, y) = (lo * a.sign, hi * a.sign);
        self.min[a.index] = x.min(y);
        self.max[a.index] = x.max(y);
    }
}

/// What painting a rectangle did besides placing it: the correction's
/// moves and where the depth came from, as sentences for the page.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Painted {
    pub corrections: Vec<String>,
    pub depth: String,
}

/// Why a rectangle cannot be painted.
#[derive(Debug, thiserror::Error, miette::Diagnostic)]
pub enum PaintError {
    #[error("no component `{name}` in the rules")]
    #[diagnostic(
        code(lsys::driver::paint_component),
        help("the palette lists the rules' components: a module X with `#define DEPTH_X d`")
    )]
    Component { name: String },
    #[error("the rectangle is {w} x {h}: too small to paint")]
    #[diagnostic(
        code(lsys::driver::paint_small),
        help("drag a rectangle at least 0.01 wide and high")
    )]
    Small { w: f64, h: f64 },
    #[error("the rectangle {rect:?} is not a finite one within 10 000 of the origin")]
    #[diagnostic(code(lsys::driver::paint_far), help("paint within the view"))]
    Far { rect: [f64; 4] },
}

/// Sizes below this are no rectangle (a click, not a drag).
const MIN_SIZE: f64 = 0.01;
/// Coordinates are within this of the origin.
const FAR: f64 = 10_000.0;

fn checked(rect: [f64; 4]) -> Result<[f64; 4], PaintError> {
    if rect.iter().any(|c| !c.is_finite() || c.abs() > FAR) {
        return Err(PaintError::Far { rect });
    }
    let r = [
        rect[0].min(rect[2]),
        rect[1].min(rect[3]),
        rect[0].max(rect[2]),
        rect[1].max(rect[3]),
    ];
    let (w, h) = (r[2] - r[0], r[3] - r[1]);
    if w < MIN_SIZE || h < MIN_SIZE {
        return Err(PaintError::Small { w, h });
    }
    Ok(r)
}

/// A new part: `component` painted as `rect` (`[u0, v0, u1, v1]` in
/// `view`), among `parts`, on part `on` when the user chose one (a door
/// behind a porch goes into the wall, not the porch), else on the part
/// nearest the viewer whose rectangle overlaps it. Its third dimension is
/// the configure rule's, the first that applies:
/// a `THROUGH_` component on a part goes `DEPTH_` into it from the face
/// the viewer sees (at most through it: a window through a wall); a part
/// standing on another (its bottom edge on that one's top, within the
/// threshold; unless the user chose a part) is as deep as it; another on
/// a part stands in front of it (toward the viewer), `DEPTH_` deep; on
/// nothing it stands on the view's back plane through the origin. Then
/// its painted edges within `threshold` of another part's edges move
/// onto them (seed 004, Fig 3), never leaving it thinner than the
/// threshold.
pub fn paint(
    parts: &[Part],
    palette: &[Component],
    view: PaintView,
    rect: [f64; 4],
    component: &str,
    threshold: f64,
    on: Option<usize>,
) -> Result<(Part, Painted), PaintError> {
    let c = palette
        .iter()
        .find(|c| c.name == component)
        .ok_or_else(|| PaintError::Component {
            name: component.to_string(),
        })?;
    let rect = checked(rect)?;
    let [u, v, w] = view.axes();
    let mut part = Part {
        component: c.name.clone(),
        view,
        min: [0.0; 3],
        max: [0.0; 3],
    };
    part.set_span(u, (rect[0], rect[2]));
    part.set_span(v, (rect[1], rect[3]));
    let mut painted = Painted::default();
    // The part it is painted on: the one nearest the viewer whose
    // rectangle in this view overlaps the new one.
    let r = part.rect(view);
    let chosen = on.filter(|&i| i < parts.len() && overlap(&parts[i].rect(view), &r));
    let under = match chosen {
        Some(i) => Some((i, &parts[i])),
        None => parts
            .iter()
            .enumerate()
            .filter(|(_, p)| overlap(&p.rect(view), &r))
            .max_by(|(_, a), (_, b)| a.span(w).1.total_cmp(&b.span(w).1)),
    };
    let standing = standing_on(parts, view, &r, threshold).filter(|_| chosen.is_none());
    let depth = match (under, standing) {
        (Some((i, p)), _) if c.through => {
            let (back, front) = p.span(w);
            let depth = c.depth.min(front - back);
            painted.depth = format!(
                "{} into {} {} from its face (DEPTH_{}, THROUGH_{})",
                number(depth),
                p.component,
                i + 1,
                c.name,
                c.name
            );
            (front - depth, front)
        }
        (_, Some(i)) => {
            painted.depth = format!(
                "as deep as {} {}, which it stands on",
                parts[i].component,
                i + 1
            );
            parts[i].span(w)
        }
        (Some((i, p)), None) => {
            let front = p.span(w).1;
            painted.depth = format!(
                "{} deep (DEPTH_{}), in front of {} {}",
                number(c.depth),
                c.name,
                p.component,
                i + 1
            );
            (front, front + c.depth)
        }
        (None, None) => {
            painted.depth = format!("{} deep (DEPTH_{})", number(c.depth), c.name);
            (0.0, c.depth)
        }
    };
    part.set_span(w, depth);
    correct(&mut part, parts, view, threshold, &mut painted);
    Ok((part, painted))
}

/// The part `parts[i]` given the rectangle `rect` in `view`: the two
/// dimensions the view shows are set (and corrected), the third kept.
/// This is how a part painted in one view gets its depth from another.
pub fn reshape(
    parts: &[Part],
    i: usize,
    view: PaintView,
    rect: [f64; 4],
    threshold: f64,
) -> Result<(Part, Painted), PaintError> {
    let rect = checked(rect)?;
    let [u, v, _] = view.axes();
    let mut part = parts[i].clone();
    part.set_span(u, (rect[0], rect[2]));
    part.set_span(v, (rect[1], rect[3]));
    let others: Vec<Part> = parts
        .iter()
        .enumerate()
        .filter(|(k, _)| *k != i)
        .map(|(_, p)| p.clone())
        .collect();
    let mut painted = Painted::default();
    correct(&mut part, &others, view, threshold, &mut painted);
    Ok((part, painted))
}

/// The holes the constraint rule will cut: each `THROUGH_` part in every
/// other part it intersects, as a sentence for the page.
pub fn holes(parts: &[Part], palette: &[Component]) -> Vec<String> {
    let through = |p: &Part| palette.iter().any(|c| c.name == p.component && c.through);
    let mut out = Vec::new();
    for (i, h) in parts.iter().enumerate().filter(|(_, p)| through(p)) {
        for (j, b) in parts.iter().enumerate() {
            if j == i || through(b) {
                continue;
            }
            let lo: Vec<f64> = (0..3).map(|k| h.min[k].max(b.min[k])).collect();
            let hi: Vec<f64> = (0..3).map(|k| h.max[k].min(b.max[k])).collect();
            if (0..3).all(|k| hi[k] - lo[k] > 1e-9) {
                // Its size as the view it was painted in shows it.
                let [u, v, _] = h.view.axes();
                out.push(format!(
                    "{} {} intersects {} {}: a hole {} x {} is cut through it",
                    h.component,
                    i + 1,
                    b.component,
                    j + 1,
                    number(hi[u.index] - lo[u.index]),
                    number(hi[v.index] - lo[v.index])
                ));
            }
        }
    }
    out
}

/// A length as the page and the file show it: at most 3 decimals.
pub fn number(x: f64) -> String {
    let r = (x * 1000.0).round() / 1000.0;
    let r = if r == 0.0 { 0.0 } else { r };
    format!("{r}")
}
