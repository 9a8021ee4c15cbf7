//! The turtle's shape commands (docs/shapes.md): setting and moving the
//! scope, splits that draw the branches after them in sub-scopes, the
//! primitives and `~X` fitted to the scope. Input: a shape command and
//! the string after it; output: the turtle's state changed, branches
//! walked, solids recorded (drawn at the end by turtle/solid.rs).

use glam::DVec3;

use super::chinese_roof::RoofShape;
use super::error::{source_of_symbol, ShapeError, TurtleError};
use super::frame::Frame;
use super::interp::{QueryFn, Turtle, Walk};
use super::scope::{self, axes, num, Misfit, Role, Size};
use super::solid::{Projection, Solid};
use crate::derive::store::{head_sym, rest_of_branch};
use crate::lang::scope_commands::{Primitive, ScopeCmd};
use crate::resolve::ir::{SymId, OPEN_BRACKET};

/// A branch `[ ... ]` in the string: its contents and where it ends.
#[derive(Clone, Copy, Debug)]
struct Branch {
    /// First module inside and its parameter offset.
    start: usize,
    offset: usize,
    /// Index of the closing `]`.
    end: usize,
    /// Parameters inside.
    params: usize,
}

impl Turtle<'_> {
    /// Runs shape command `c` (module `index`, parameters `args`, the next
    /// module's parameters at `next_offset`); returns where the walk goes
    /// on: after the module, or after the branches a split consumed.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn scope_cmd(
        &mut self,
        w: &Walk,
        q: &mut QueryFn,
        c: ScopeCmd,
        sym: SymId,
        args: &[f64],
        index: usize,
        next_offset: usize,
    ) -> Result<(usize, usize), TurtleError> {
        let next = (index + 1, next_offset);
        let arg = |k: usize| args.get(k).copied().unwrap_or(0.0);
        if let ScopeCmd::Set = c {
            self.state.scope = Some(DVec3::new(arg(0), arg(1), arg(2)).abs());
            return Ok(next);
        }
        let Some(size) = self.state.scope else {
            let (src, span) = source_of_symbol(self.program, sym);
            return Err(ShapeError::NoScope {
                index: index + 1,
                text: self.text(sym, args),
                src,
                written_by: span,
                help:
                    "start a scope first with @Scope(sx,sy,sz) (in this branch or one enclosing it)"
                        .into(),
            }
            .into());
        };
        let frame = self.state.frame;
        match c {
            ScopeCmd::Set => unreachable!("handled above"),
            ScopeCmd::Translate => {
                let [x, y, z] = axes(&frame);
                self.state.frame.pos += x * arg(0) + y * arg(1) + z * arg(2);
                Ok(next)
            }
            ScopeCmd::Extrude => {
                self.state.scope = Some(DVec3::new(size.x, size.y, arg(0).abs()));
                Ok(next)
            }
            ScopeCmd::Grow => {
                let grown = size + DVec3::new(arg(0), arg(1), arg(2));
                self.state.scope = Some(grown.max(DVec3::ZERO));
                Ok(next)
            }
            ScopeCmd::Scale => {
                let scaled = size * DVec3::new(arg(0), arg(1), arg(2));
                self.state.scope = Some(scaled.abs());
                Ok(next)
            }
            ScopeCmd::Rotate => {
                self.state.frame = scope::rotate(&frame, size, [arg(0), arg(1), arg(2)]);
                Ok(next)
            }
            ScopeCmd::Solid(kind) => {
                if self.solids.len() >= self.opts.max_triangles {
                    return Err(TurtleError::TooManyShapes {
                        limit: self.opts.max_triangles,
                        count: self.solids.len() + 1,
                        index: index + 1,
                        text: self.text_of(sym, args),
                    });
                }
                let mut solid = self.solid(kind, args, index);
                if kind == Primitive::Roof {
                    let shape = RoofShape::from_args(args)
                        .map_err(|problem| self.bad_roof(problem, sym, args, index))?;
                    solid.roof = Some(shape);
                }
                self.solids.push(solid);
                Ok(next)
            }
            ScopeCmd::Snap => {
                self.state.snap = arg(0).abs();
                Ok(next)
            }
            ScopeCmd::Texture => {
                let n = arg(0);
                if n < 0.5 {
                    self.state.texture = None;
                    return Ok(next);
                }
                let n = n.round() as usize;
                if !self.program.turtle.textures.iter().any(|t| t.index == n) {
                    let (src, span) = source_of_symbol(self.program, sym);
                    return Err(ShapeError::NoTexture {
                        index: index + 1,
                        text: self.text(sym, args),
                        texture: n,
                        src,
                        written_by: span,
                        help: format!("add a header `texture {n}: \"image.png\"` naming an image beside the grammar"),
                    }
                    .into());
                }
                let crop = if args.len() >= 5 {
                    [arg(1), arg(2), arg(3), arg(4)]
                } else {
                    [0.0, 0.0, 1.0, 1.0]
                };
                let [x, y, z] = axes(&frame);
                self.state.texture = Some(Box::new(Projection {
                    texture: n as u32,
                    origin: frame.pos,
                    x,
                    y,
                    z,
                    size: [size.x, size.y],
                    crop,
                }));
                Ok(next)
            }
            ScopeCmd::Hole => {
                let h = self.solid(Primitive::Block, &[], index);
                self.holes.push(h);
                Ok(next)
            }
            ScopeCmd::Split(axis) => {
                let total = size[axis.index()];
                let pieces = scope::subdivide(total, args, axis)
                    .map_err(|m| self.misfit(m, sym, args, index))?;
                let branches =
                    self.branches(w, sym, args, index, next, pieces.len(), pieces.len())?;
                let laid = branches.iter().copied().map(Some).zip(pieces);
                self.lay_out(w, q, (&frame, size), axis, laid, (sym, args, index))?;
                Ok(after(&branches, next))
            }
            ScopeCmd::Repeat(axis) => {
                let total = size[axis.index()];
                let pieces = scope::repeat(total, arg(0), axis)
                    .map_err(|m| self.misfit(m, sym, args, index))?;
                let branches = self.branches(w, sym, args, index, next, 1, 1)?;
                let laid = pieces.into_iter().map(|len| (Some(branches[0]), len));
                self.lay_out(w, q, (&frame, size), axis, laid, (sym, args, index))?;
                Ok(after(&branches, next))
            }
            ScopeCmd::Symmetric(axis) => {
                let total = size[axis.index()];
                let pieces = scope::symmetric(total, arg(0), arg(1), arg(2), axis)
                    .map_err(|m| self.misfit(m, sym, args, index))?;
                let branches = self.branches(w, sym, args, index, next, 3, 3)?;
                // A missing centre (length 0) draws nothing.
                let laid = pieces.into_iter().map(|(role, len)| {
                    let b = match role {
                        Role::End => branches[0],
                        Role::Bay => branches[1],
                        Role::Centre => branches[2],
                    };
                    ((len > 0.0).then_some(b), len)
                });
                self.lay_out(w, q, (&frame, size), axis, laid, (sym, args, index))?;
                Ok(after(&branches, next))
            }
            ScopeCmd::Faces => {
                let faces = scope::faces(&frame, size);
                let branches = self.branches(w, sym, args, index, next, 1, faces.len())?;
                for (b, face) in branches.iter().zip(faces) {
                    self.sub(w, q, *b, face)?;
                }
                Ok(after(&branches, next))
            }
        }
    }

    /// At the end of the string: the primitives as polygons, after the
    /// constraint rules (snap, holes), with their counts and reports.
    pub(super) fn draw_solids(&mut self) {
        let (polys, report) = super::solid::build(&self.solids, &self.holes);
        self.drawing.polygons.extend(polys);
        self.drawing.constraints.extend(report);
        for s in &self.solids {
            let kind = super::solid::kind_name(s.kind).to_string();
            *self.drawing.primitives.entry(kind).or_default() += 1;
        }
    }

    /// Draws branch `b` as `[ ... ]` would, in the sub-scope `(frame, size)`.
    /// Draws each branch in its piece of the scope `(frame, size)`, the
    /// pieces laid end to end along `axis`; a piece without a branch keeps
    /// its place and draws nothing.
    fn lay_out(
        &mut self,
        w: &Walk,
        q: &mut QueryFn,
        (frame, size): (&Frame, DVec3),
        axis: crate::lang::scope_commands::Axis,
        pieces: impl IntoIterator<Item = (Option<Branch>, f64)>,
        (sym, args, index): (SymId, &[f64], usize),
    ) -> Result<(), TurtleError> {
        let mut at = 0.0;
        for (b, len) in pieces {
            self.pieces += 1;
            if self.pieces > super::interp::MAX_PIECES {
                return Err(TurtleError::PieceLimit {
                    limit: super::interp::MAX_PIECES,
                    index: index + 1,
                    text: self.text_of(sym, args),
                });
            }
            if let Some(b) = b {
                self.sub(w, q, b, scope::piece(frame, size, axis, at, len))?;
            }
            at += len;
        }
        Ok(())
    }

    fn sub(
        &mut self,
        w: &Walk,
        q: &mut QueryFn,
        b: Branch,
        (frame, size): (Frame, DVec3),
    ) -> Result<(), TurtleError> {
        // Walk the branch with its own `[` and `]` (parameterless), so the
        // branch starts its own tubes as any branch does; the `[` saves
        // the sub-scope set here and the `]` brings it back.
        let saved = self.state.clone();
        self.state.frame = frame;
        self.state.scope = Some(size);
        let r = self.walk(w, q, b.start - 1, b.end + 1, b.offset);
        self.state = saved;
        r
    }

    /// The `min..=max` branches right after a split (fewer than `max` only
    /// when the string has no more `[` there).
    #[allow(clippy::too_many_arguments)]
    fn branches(
        &self,
        w: &Walk,
        sym: SymId,
        args: &[f64],
        index: usize,
        (mut i, mut offset): (usize, usize),
        min: usize,
        max: usize,
    ) -> Result<Vec<Branch>, TurtleError> {
        let mut out = Vec::new();
        while out.len() < max && i < w.heads.len() && head_sym(w.heads[i]) == OPEN_BRACKET {
            let (end, skipped) = rest_of_branch(w.heads, i + 1);
            if end >= w.heads.len() {
                break;
            }
            out.push(Branch {
                start: i + 1,
                offset,
                end,
                params: skipped,
            });
            offset += skipped;
            i = end + 1;
        }
        if out.len() < min {
            let (src, span) = source_of_symbol(self.program, sym);
            let what = |n: usize| {
                if n == 1 {
                    "one branch `[...]`".to_string()
                } else {
                    format!("{n} branches `[...]`")
                }
            };
            return Err(ShapeError::SplitBranches {
                index: index + 1,
                text: self.text(sym, args),
                wanted: what(min),
                found: if out.is_empty() {
                    "no branch follows it".into()
                } else {
                    format!("only {} follow{} it", out.len(), if out.len() == 1 { "s" } else { "" })
                },
                src,
                written_by: span,
                help: "write one branch per piece right after the split, e.g. @SX(1,flo(1),1) [A][B][C]".into(),
            }
            .into());
        }
        Ok(out)
    }

    fn misfit(&self, m: Misfit, sym: SymId, args: &[f64], index: usize) -> TurtleError {
        let (src, span) = source_of_symbol(self.program, sym);
        ShapeError::SplitMisfit {
            index: index + 1,
            text: self.text(sym, args),
            problem: m.problem,
            src,
            written_by: span,
            asked: m.asked,
            scope: num(m.scope),
            help: m.help,
        }
        .into()
    }

    fn solid(&self, kind: Primitive, args: &[f64], index: usize) -> Solid {
        Solid {
            kind,
            frame: self.state.frame,
            size: self.state.scope.unwrap_or(DVec3::ZERO),
            colour: self.state.colour,
            sides: args.first().map_or(16, |&n| (n.max(3.0) as usize).min(256)),
            module: index,
            seq: self.solids.len() + self.holes.len(),
            snap: self.state.snap,
            roof: None,
            texture: self.state.texture.as_deref().copied(),
        }
    }

    fn bad_roof(&self, problem: String, sym: SymId, args: &[f64], index: usize) -> TurtleError {
        let (src, span) = source_of_symbol(self.program, sym);
        ShapeError::BadRoof {
            index: index + 1,
            text: self.text(sym, args),
            problem,
            src,
            written_by: span,
            help: "write @Roof(hip, tile, eave, j1, ..., jn): hip 1 or 0, the spacing of the \
                   tile rows (0 for none), the eaves' run in bujias, then one jujia (rise per \
                   unit of run, more than 0) per step from the eaves purlin to the ridge, \
                   e.g. @Roof(1, 0.45, 0.8, 0.5, 0.7, 0.9)"
                .into(),
        }
        .into()
    }

    /// The module as the user wrote it: a split's `flo(w)` and `rel(f)`
    /// shown as such, not as the numbers they are encoded in.
    fn text(&self, sym: SymId, args: &[f64]) -> String {
        let name = self.program.symbols.name(sym);
        let split = matches!(
            crate::lang::lookup(name).map(|c| c.paper),
            Some(crate::lang::commands::Action::Scope(ScopeCmd::Split(_)))
        );
        let a: Vec<String> = args
            .iter()
            .map(|&x| {
                if split {
                    Size::decode(x).text()
                } else {
                    num(x)
                }
            })
            .collect();
        if a.is_empty() {
            name.to_string()
        } else {
            format!("{name}({})", a.join(","))
        }
    }
}

/// Where the walk resumes after a split: after its last branch's `]`
/// (which has no parameters).
fn after(branches: &[Branch], next: (usize, usize)) -> (usize, usize) {
    match branches.last() {
        Some(b) => (b.end + 1, b.offset + b.params),
        None => next,
    }
}
