//! The 3D turtle: a derived module string -> a [`Drawing`]. Each symbol is
//! mapped once to an `Act` through the command table and the file's
//! dialect, then the string is walked left to right with a branch stack.

use glam::{DVec3, Vec3};

use super::drawing::{Drawing, Polygon};
use super::error::TurtleError;
use super::frame::{Frame, SinCosCache};
use super::solid::Projection;
use crate::derive::store::{head_arity, head_sym, rest_of_branch};
use crate::derive::ModuleStore;
use crate::lang::commands::{lookup, Action};
use crate::lang::{Dialect, Profile};
use crate::resolve::ir::{Program, SymId, SymbolKind, Symbols};
use crate::support::prefault::Prefault;

mod chains;

/// Defaults the turtle starts from.
#[derive(Clone, Debug)]
pub struct TurtleOptions {
    pub profile: Profile,
    /// Turning angle of `+`, `&`, ... without a parameter, in degrees.
    pub angle: f32,
    /// Length of `F`, `f`, ... without a parameter.
    pub step: f32,
    /// Initial line width (the tube diameter).
    pub width: f32,
    /// What `#` and `!` without a parameter add and take away.
    pub width_increment: f32,
    /// Widths are cpfg screen pixels (see `turtle::cpfg`).
    pub pixel_lines: bool,
    /// The mesh's triangle limit: shapes (at least a triangle each) past
    /// it end the interpretation before they are all collected.
    pub max_triangles: usize,
}

/// The default of `--max-triangles`, the mesh's limit (docs/limits.md).
pub const DEFAULT_MAX_TRIANGLES: usize = 100_000_000;

/// Pieces all splits and repeats of one interpretation may lay out:
/// each repeat is capped at [`super::scope::MAX_COPIES`], but nested ones
/// multiply (three levels of 1,000 asked for 10^9 and aborted). A piece
/// that draws a block keeps about 170 bytes until the end: 340 MB at most.
pub const MAX_PIECES: usize = 2_000_000;

/// The default angle when neither the file nor the command line gives one.
pub const DEFAULT_ANGLE: f64 = 90.0;
/// The default line width: a tenth of the default step.
pub const DEFAULT_WIDTH: f64 = 0.1;

impl TurtleOptions {
    /// The file's headers, each overridden by the command line when given.
    pub fn new(
        program: &Program,
        angle: Option<f64>,
        step: Option<f64>,
        width: Option<f64>,
    ) -> Self {
        let file = &program.turtle;
        let width = width.or(file.width).unwrap_or(DEFAULT_WIDTH);
        TurtleOptions {
            profile: program.profile,
            angle: angle.or(file.angle).unwrap_or(DEFAULT_ANGLE) as f32,
            step: step.or(file.step).unwrap_or(1.0) as f32,
            width: width as f32,
            width_increment: file.width_increment.unwrap_or(width * 0.1) as f32,
            pixel_lines: file.pixel_lines,
            max_triangles: DEFAULT_MAX_TRIANGLES,
        }
    }
}

/// What one symbol does: a turtle command's action from the command
/// table, a component placement, or nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Act {
    Command(Action),
    Place,
}

fn act_of(name: &str, kind: SymbolKind, dialect: Dialect) -> Act {
    if name == "?" && dialect == Dialect::Cpfg {
        return Act::Command(Action::SubStart);
    }
    match kind {
        SymbolKind::Component => Act::Place,
        _ => Act::Command(
            lookup(name)
                .filter(|_| kind == SymbolKind::Turtle || name == "[" || name == "]")
                .map_or(Action::Nothing, |c| c.action(dialect)),
        ),
    }
}

/// Pushed and popped at every bracket: a W2 tree copies it 2 × 262,143
/// times, so what few models use (an open generalized cylinder, with a
/// frame of its own) is boxed.
#[derive(Clone, Debug)]
pub(super) struct State {
    pub(super) frame: Frame,
    /// The scope's size (docs/shapes.md); its origin and axes are the
    /// frame's. `None` until `@Scope`.
    pub(super) scope: Option<DVec3>,
    /// `@Snap(d)`: blocks drawn now snap to earlier ones within d.
    pub(super) snap: f64,
    /// `@Tex(...)`: the texture projected onto the blocks drawn now
    /// (boxed: few models have one, and the state is copied at every `[`).
    pub(super) texture: Option<Box<Projection>>,
    pub(super) width: f32,
    pub(super) colour: u32,
    pub(super) scale: f32,
    /// The chain the next drawn segment may extend.
    chain: Option<usize>,
    /// The drawn point the turtle stands on (chain, point), if any: a
    /// chain started here records it as its origin (a hint for meshing).
    at: Option<(u32, u32)>,
    /// The open generalized cylinder: its last control point, and the
    /// chain its last segment extended. A branch copies it and goes on
    /// from the branch point, as cpfg's spline stack does.
    pub(super) cylinder: Option<Box<super::cylinder::Open>>,
    /// cpfg's `@#(id)`: the cross-section of the cylinders drawn from
    /// here, an index into the program's contours; `None`: round.
    pub(super) contour: Option<usize>,
    tropism: Vec3,
    elasticity: f32,
}

impl Turtle<'_> {
    /// `Err` when a placement from `from` on has a non-finite transform;
    /// `module` (at index `index`) placed them.
    /// The module at `index` as errors show it.
    pub(super) fn text_of(&self, sym: SymId, args: &[f64]) -> String {
        module_text(&self.program.symbols, sym, args)
    }

    fn placements_finite(
        &self,
        from: usize,
        sym: SymId,
        args: &[f64],
        index: usize,
    ) -> Result<(), TurtleError> {
        let placed = &self.drawing.placements[from.min(self.drawing.placements.len())..];
        if placed.iter().all(|p| p.transform.is_finite()) {
            return Ok(());
        }
        Err(TurtleError::ComponentOverflow {
            index: index + 1,
            text: self.text_of(sym, args),
            symbol: self.program.symbols.name(sym).to_string(),
        })
    }
}

impl State {
    /// Whether the frame (as the f32 the model is stored in) and the width
    /// are finite. The frame computes in f64.
    fn is_finite(&self) -> bool {
        let f = &self.frame;
        f.pos.as_vec3().is_finite()
            && f.h.is_finite()
            && f.u.is_finite()
            && f.l.is_finite()
            && self.width.is_finite()
    }
}

pub(super) struct Turtle<'a> {
    pub(super) opts: &'a TurtleOptions,
    /// Pieces laid out by splits and repeats so far ([`MAX_PIECES`]).
    pub(super) pieces: usize,
    /// For errors that point at the grammar.
    pub(super) program: &'a Program,
    symbols: &'a Symbols,
    pub(super) drawing: Drawing,
    pub(super) state: State,
    stack: Vec<State>,
    /// Open polygons: global, not per branch, so that a polygon can collect
    /// vertices from several branches (ABOP's leaves).
    polygons: Vec<(usize, Vec<Vec3>)>,
    /// The scales in force before each open sub-L-system (`?(n, s)`).
    subs: Vec<f32>,
    /// Primitives and hole cutters, drawn at the end (turtle/solid.rs).
    pub(super) solids: Vec<super::solid::Solid>,
    pub(super) holes: Vec<super::solid::Solid>,
    trig: SinCosCache,
    /// A second core backing the pages of a big drawing's chains (and
    /// their origins) ahead of the walk.
    prefault: Option<Prefault<2>>,
}

/// The string being walked and each symbol's act.
pub(super) struct Walk<'s> {
    pub(super) heads: &'s [u32],
    pub(super) params: &'s [f64],
    acts: &'s [Act],
}

/// Interprets `store` (normally the string after the homomorphism).
pub fn interpret(
    program: &Program,
    store: &ModuleStore,
    opts: &TurtleOptions,
) -> Result<Drawing, TurtleError> {
    interpret_with(program, store, opts, &mut |_| {})
}

/// Where a query module stands in a string and the turtle's state there.
#[derive(Clone, Copy, Debug)]
pub struct QuerySite {
    pub sym: SymId,
    pub arity: usize,
    /// The module's position in the string.
    pub index: usize,
    /// Offset of its first parameter in the string's parameter arena.
    pub offset: usize,
    pub frame: Frame,
    /// The line width and the scale (`@Dd`) in force.
    pub width: f32,
    pub scale: f32,
    /// The scope's size (zero outside any scope): `?S(sx,sy,sz)`.
    pub scope: DVec3,
}

/// Every query module with parameters in `store` (`?P`, `?E`, ...), in
/// string order, with the turtle's state where it stands. A string that
/// ends inside a polygon is read up to its end.
pub fn query_sites(
    program: &Program,
    store: &ModuleStore,
    opts: &TurtleOptions,
) -> Result<Vec<QuerySite>, TurtleError> {
    let mut out = Vec::new();
    interpret_with(program, store, opts, &mut |site| out.push(site)).or_else(|e| match e {
        TurtleError::UnclosedPolygon { .. } => Ok(Drawing::default()),
        e => Err(e),
    })?;
    Ok(out)
}

/// Called with each query module's site.
pub(super) type QueryFn<'a> = dyn FnMut(QuerySite) + 'a;

/// [`interpret`], telling `on_query` the turtle's state at every query
/// module.
fn interpret_with(
    program: &Program,
    store: &ModuleStore,
    opts: &TurtleOptions,
    on_query: &mut QueryFn,
) -> Result<Drawing, TurtleError> {
    let acts: Vec<Act> = program
        .symbols
        .list
        .iter()
        .map(|s| act_of(&s.name, s.kind, opts.profile.dialect))
        .collect();
    let mut t = Turtle {
        opts,
        pieces: 0,
        program,
        symbols: &program.symbols,
        drawing: Drawing::default(),
        state: State {
            scope: None,
            snap: 0.0,
            texture: None,
            frame: if opts.profile.cpfg_turtle {
                Frame::cpfg()
            } else {
                Frame::default()
            },
            width: opts.width,
            colour: program.turtle.colour.unwrap_or(0),
            scale: 1.0,
            chain: None,
            at: None,
            cylinder: None,
            contour: None,
            tropism: Vec3::NEG_Y,
            elasticity: 0.0,
        },
        stack: Vec::new(),
        polygons: Vec::new(),
        subs: Vec::new(),
        solids: Vec::new(),
        holes: Vec::new(),
        trig: SinCosCache::default(),
        prefault: None,
    };
    let walk = Walk {
        heads: store.heads(),
        params: store.params(),
        acts: &acts,
    };
    t.reserve_chains(&walk);
    t.walk(&walk, on_query, 0, walk.heads.len(), 0)?;
    t.prefault = None;
    if let Some((first, _)) = t.polygons.first() {
        return Err(TurtleError::UnclosedPolygon {
            count: t.polygons.len(),
            first: *first + 1,
        });
    }
    t.draw_solids();
    if opts.pixel_lines {
        super::cpfg::pixels_to_units(&mut t.drawing);
    }
    Ok(t.drawing)
}

fn module_text(symbols: &Symbols, sym: SymId, args: &[f64]) -> String {
    let name = symbols.name(sym);
    if args.is_empty() {
        name.to_string()
    } else {
        let a: Vec<String> = args.iter().map(|x| x.to_string()).collect();
        format!("{name}({})", a.join(","))
    }
}

impl Turtle<'_> {
    /// Interprets modules `i..end`, whose parameters start at `offset`.
    pub(super) fn walk(
        &mut self,
        w: &Walk,
        on_query: &mut QueryFn,
        mut i: usize,
        end: usize,
        mut offset: usize,
    ) -> Result<(), TurtleError> {
        let (heads, params, program) = (w.heads, w.params, self.program);
        let t = self;
        while i < end {
            let (sym, arity) = (head_sym(heads[i]), head_arity(heads[i]));
            let args = &params[offset..offset + arity];
            if arity > 0 && program.symbols.list[sym as usize].kind == SymbolKind::Query {
                on_query(QuerySite {
                    sym,
                    arity,
                    index: i,
                    offset,
                    frame: t.state.frame,
                    width: t.state.width,
                    scale: t.state.scale,
                    scope: t.state.scope.unwrap_or_default(),
                });
            }
            offset += arity;
            let act = w.acts[sym as usize];
            // `matches!`, not `==`: comparing two `Act`s was a call.
            if !matches!(act, Act::Command(Action::Nothing)) {
                if let Some(&bad) = args.iter().find(|a| !a.is_finite()) {
                    return Err(TurtleError::NonFinite {
                        index: i + 1,
                        text: module_text(&program.symbols, sym, args),
                        symbol: program.symbols.name(sym).to_string(),
                        value: bad,
                    });
                }
                if matches!(act, Act::Command(Action::Cut)) {
                    // Skip to the `]` that ends this branch (or the end), and
                    // let that `]` pop the branch as usual.
                    let (end, skipped) = rest_of_branch(heads, i + 1);
                    i = end;
                    offset += skipped;
                    continue;
                }
                // Components placed by this module: a scale factor past f32
                // (`~X(1e308)`) or a huge scope would give a transform of
                // infinities, which the exporters cannot write and the
                // renderer would drop silently.
                let placed = t.drawing.placements.len();
                let module = i;
                if let Act::Command(Action::Scope(c)) = act {
                    // Shape commands (turtle/scope_walk.rs); splits consume
                    // the branches that follow them.
                    (i, offset) = t.scope_cmd(w, on_query, c, sym, args, i, offset)?;
                    t.placements_finite(placed, sym, args, module)?;
                    continue;
                }
                match act {
                    Act::Command(a) => t.apply(a, sym, args, i)?,
                    Act::Place => t.place(sym, args, i),
                }
                t.placements_finite(placed, sym, args, module)?;
                // The model is in 32-bit floats: steps that add up past their
                // range would reach the exporter as infinities. A bracket
                // changes nothing or brings back a state checked when it
                // was current (checks were a fifth of W2's interpretation).
                if !matches!(act, Act::Command(Action::Push | Action::Pop)) && !t.state.is_finite()
                {
                    return Err(TurtleError::Overflow {
                        index: i + 1,
                        text: module_text(&program.symbols, sym, args),
                        symbol: program.symbols.name(sym).to_string(),
                    });
                }
            }
            i += 1;
        }
        Ok(())
    }

    fn angle(&self, args: &[f64]) -> f32 {
        args.first().map_or(self.opts.angle, |&a| a as f32)
    }

    fn apply(
        &mut self,
        act: Action,
        sym: SymId,
        args: &[f64],
        index: usize,
    ) -> Result<(), TurtleError> {
        use Action::*;
        let s = &mut self.state;
        match act {
            // Shape commands are run by `scope_cmd` before `apply`.
            Nothing | Cut | Scope(_) => {}
            Move { draw, vertex } => {
                let d = args.first().map_or(self.opts.step, |&a| a as f32) * s.scale;
                self.forward(d, draw, vertex);
            }
            Turn(sign) => {
                let sc = self.trig.sin_cos(f64::from(sign * self.angle(args)));
                self.state.frame.turn_by(sc)
            }
            Pitch(sign) => {
                // cpfg's `&` moves H toward its U (interpret.c: `change_dir(
                // temp, heading, up, sin, cos)`, the form of `+` toward L),
                // the paper's away from U; with cpfg's U = -z both pitch
                // down toward -z, so the cpfg frame pitches the other way.
                let sign = if self.opts.profile.cpfg_turtle {
                    -sign
                } else {
                    sign
                };
                let sc = self.trig.sin_cos(f64::from(sign * self.angle(args)));
                self.state.frame.pitch_by(sc)
            }
            Roll(sign) => {
                let sc = self.trig.sin_cos(f64::from(sign * self.angle(args)));
                self.state.frame.roll_by(sc)
            }
            TurnAround => s.frame.turn(180.0),
            RollAround => s.frame.roll(180.0),
            PitchAround => s.frame.pitch(180.0),
            RollHorizontal => s.frame.roll_to_horizontal(),
            HeadingUp => s.frame.rotate_heading_to(DVec3::Y),
            Mirror => s.frame.mirror(),
            Push => {
                self.stack.push(self.state.clone());
                // A branch draws its own tubes; the parent's chain resumes
                // after the matching `]`. An open generalized cylinder
                // goes on in the branch.
                self.state.chain = None;
            }
            Pop => {
                self.state = self
                    .stack
                    .pop()
                    .ok_or_else(|| TurtleError::unbalanced(index + 1, self.program))?;
            }
            SetWidth | IncWidth if self.opts.profile.cpfg_turtle => {
                super::cpfg::set_width(s, act == IncWidth, args, self.opts.width_increment)
            }
            SetWidth => match args.first() {
                Some(&w) => s.width = (w as f32).max(0.0),
                None => s.width = (s.width - self.opts.width_increment).max(0.0),
            },
            IncWidth => match args.first() {
                Some(&w) => s.width = (s.width + w as f32).max(0.0),
                None => s.width += self.opts.width_increment,
            },
            SetColour => match args.first() {
                Some(&c) => s.colour = colour_index(c),
                None => s.colour = s.colour.saturating_add(1),
            },
            DecColour => match args.first() {
                Some(&c) => s.colour = colour_index(c),
                None => s.colour = s.colour.saturating_sub(1),
            },
            IncColour => match args.first() {
                Some(&c) => s.colour = colour_index(c),
                None => s.colour = s.colour.saturating_add(1),
            },
            PolyStart => {
                // cpfg's `{` records no vertex (only `.`, `F`, `f` do):
                // leaves written `{.` ... `}` across branches depend on it.
                let start = s.frame.pos.as_vec3();
                let first = (!self.opts.profile.cpfg_turtle).then_some(start);
                self.polygons.push((index, first.into_iter().collect()));
            }
            PolyVertex => {
                let p = s.frame.pos.as_vec3();
                if let Some((_, poly)) = self.polygons.last_mut() {
                    push_vertex(poly, p);
                }
            }
            PolyEnd => {
                let (_, mut points) = self
                    .polygons
                    .pop()
                    .ok_or(TurtleError::UnopenedPolygon { index: index + 1 })?;
                if points.len() > 1 && points[0].distance(points[points.len() - 1]) < 1e-6 {
                    points.pop();
                }
                if points.len() >= 3 {
                    self.drawing.polygons.push(Polygon {
                        colour: self.state.colour,
                        points,
                        uv: None,
                    });
                }
            }
            Shape(kind) => {
                let d = args.first().map_or(s.width, |&a| a as f32);
                if d > 0.0 {
                    self.drawing.shapes.push(super::drawing::Shape {
                        kind,
                        centre: s.frame.pos.as_vec3(),
                        normal: s.frame.h.as_vec3(),
                        radius: d * 0.5,
                        colour: s.colour,
                    });
                }
            }
            MoveTo => {
                s.frame.pos = DVec3::new(args[0], args[1], args[2]);
                s.chain = None;
                s.at = None;
            }
            SetHeading => {
                let v = |k: usize| DVec3::new(args[k], args[k + 1], args[k + 2]);
                let up = (args.len() >= 6).then(|| v(3));
                s.frame.set_heading(v(0), up);
                s.chain = None;
            }
            // cpfg writes `@Ts(movement, e)`: the first parameter picks one
            // of its tropisms, the second is the elasticity (none: 0).
            Elasticity if self.opts.profile.cpfg_turtle => {
                s.elasticity = args.get(1).map_or(0.0, |&e| e as f32)
            }
            Elasticity => s.elasticity = args.first().map_or(0.0, |&e| e as f32),
            Tropism => {
                if args.len() >= 3 {
                    s.tropism = Vec3::new(args[0] as f32, args[1] as f32, args[2] as f32);
                }
                match args.len() {
                    0 => s.elasticity = 0.0,
                    1 => s.elasticity = args[0] as f32,
                    4 => s.elasticity = args[3] as f32,
                    _ => {}
                }
            }
            CylStart | CylPoint | CylEnd => {
                let s = &mut self.state;
                let contours = &self.program.turtle.contours;
                super::cylinder::control_point(&mut self.drawing, s, act, args, contours);
            }
            CylContour => {
                s.contour = args.first().and_then(|&id| {
                    let contours = &self.program.turtle.contours;
                    contours.iter().position(|c| f64::from(c.id) == id)
                })
            }
            SubStart => super::cpfg::enter_sub(&mut self.subs, s, args),
            SubEnd => super::cpfg::leave_sub(&mut self.subs, s),
            ScaleSet => s.scale = args.first().map_or(1.0, |&a| a as f32),
            ScaleMul => s.scale *= args.first().map_or(1.0, |&a| a as f32),
            ScaleDiv => {
                let d = args.first().map_or(1.0, |&a| a as f32);
                if d == 0.0 {
                    return Err(TurtleError::ZeroScale {
                        index: index + 1,
                        text: module_text(self.symbols, sym, args),
                    });
                }
                s.scale /= d;
            }
        }
        Ok(())
    }
}

pub(super) fn push_vertex(poly: &mut Vec<Vec3>, p: Vec3) {
    if poly.last().map_or(true, |q| q.distance(p) > 1e-6) {
        poly.push(p);
    }
}

fn colour_index(c: f64) -> u32 {
    c.clamp(0.0, u32::MAX as f64) as u32
}
