//! The shape-grammar commands of the turtle (docs/shapes.md): scopes,
//! splits, primitives and hole cutters. Input: nothing (a table); output:
//! [`Command`] rows that [`lookup`](super::commands::lookup) finds after
//! the classic commands, so resolve checks their parameter counts and
//! `lsys commands` lists them like any other command.

use super::commands::{cmd, Action, Command};

/// A scope axis: x = H × U, y = H, z = U (the start frame's x, y, z).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    X,
    Y,
    Z,
}

impl Axis {
    pub fn index(self) -> usize {
        match self {
            Axis::X => 0,
            Axis::Y => 1,
            Axis::Z => 2,
        }
    }

    pub fn name(self) -> &'static str {
        ["x", "y", "z"][self.index()]
    }
}

/// A solid fitted to the scope.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Primitive {
    /// The scope's box.
    Block,
    /// An upright (along y) cylinder inscribed in the box.
    Cylinder,
    /// A gable prism: ridge along x at the top, triangle in y–z.
    Prism,
    /// A Chinese roof, hip or gable, its slope from the purlins' steps.
    Roof,
}

/// What a shape command does to the turtle's scope.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ScopeCmd {
    /// `@Scope(sx,sy,sz)`: a scope at the turtle with this size.
    Set,
    /// `@Tr(x,y,z)`: move the scope's origin along its own axes.
    Translate,
    /// `@Ext(d)`: give the scope depth d (extrude a face).
    Extrude,
    /// `@Grow(dx,dy,dz)`: add to the scope's size (origin unmoved).
    Grow,
    /// `@Sc(fx,fy,fz)`: multiply the scope's size (origin unmoved).
    Scale,
    /// `@Rot(ax,ay,az)`: rotate the scope about its centre, degrees about
    /// its x, then its (new) y, then its z axis.
    Rotate,
    /// `@SX(s1,...)`: subdivide along an axis into the branches that follow.
    Split(Axis),
    /// `@RX(s)`: repeat the next branch as many times as size s fits.
    Repeat(Axis),
    /// `@RSX(e,s,c)`: ends e, bays ≈ s, a centre c, symmetric.
    Symmetric(Axis),
    /// `@Comp`: the box's faces, one branch each.
    Faces,
    /// `@Block`, `@Cyl`, `@Prism`, `@Roof`.
    Solid(Primitive),
    /// `@Hole`: a box that cuts an opening through the blocks it meets.
    Hole,
    /// `@Snap(d)`: blocks drawn after this snap to earlier blocks' faces
    /// within d (0 switches it off).
    Snap,
    /// `@Tex(n, u0, v0, u1, v1)`: texture n's crop projected along the
    /// scope's z onto the faces of the blocks drawn after it that face
    /// that way (`@Tex(0)` switches it off).
    Texture,
}

/// A scope command's row: the same action in both dialects.
const fn row(
    symbol: &'static str,
    args: (u8, u8),
    default: &'static str,
    c: ScopeCmd,
    doc: &'static str,
) -> Command {
    cmd(symbol, args, default, Action::Scope(c), doc)
}

use Axis::{X, Y, Z};
use ScopeCmd::*;

/// The shape commands (docs/shapes.md).
pub const SCOPE_COMMANDS: &[Command] = &[
    row(
        "@Scope",
        (3, 3),
        "",
        Set,
        "start a scope (box) of size sx,sy,sz at the turtle",
    ),
    row(
        "@Tr",
        (3, 3),
        "",
        Translate,
        "move the scope by x,y,z along its axes",
    ),
    row(
        "@Ext",
        (1, 1),
        "",
        Extrude,
        "set the scope's depth (z size) to d",
    ),
    row(
        "@Grow",
        (3, 3),
        "",
        Grow,
        "add dx,dy,dz to the scope's size (its origin stays)",
    ),
    row(
        "@Sc",
        (3, 3),
        "",
        Scale,
        "multiply the scope's size by fx,fy,fz (its origin stays)",
    ),
    row(
        "@Rot",
        (3, 3),
        "",
        Rotate,
        "rotate the scope about its centre: ax, ay, az degrees about its x, y, z",
    ),
    row(
        "@SX",
        (1, 64),
        "",
        Split(X),
        "split the scope along x into the branches after it; sizes s, flo(w), rel(f)",
    ),
    row(
        "@SY",
        (1, 64),
        "",
        Split(Y),
        "split the scope along y into the branches after it; sizes s, flo(w), rel(f)",
    ),
    row(
        "@SZ",
        (1, 64),
        "",
        Split(Z),
        "split the scope along z into the branches after it; sizes s, flo(w), rel(f)",
    ),
    row(
        "@RX",
        (1, 1),
        "",
        Repeat(X),
        "repeat the next branch as often as size s fits along x",
    ),
    row(
        "@RY",
        (1, 1),
        "",
        Repeat(Y),
        "repeat the next branch as often as size s fits along y",
    ),
    row(
        "@RZ",
        (1, 1),
        "",
        Repeat(Z),
        "repeat the next branch as often as size s fits along z",
    ),
    row(
        "@RSX",
        (3, 3),
        "",
        Symmetric(X),
        "symmetric repeat: ends e, bays about s, centre c: [end][bay][centre]",
    ),
    row("@RSY", (3, 3), "", Symmetric(Y), "symmetric repeat along y"),
    row("@RSZ", (3, 3), "", Symmetric(Z), "symmetric repeat along z"),
    row(
        "@Comp",
        (0, 0),
        "",
        Faces,
        "component split: [front][back][left][right][top][bottom]",
    ),
    row(
        "@Block",
        (0, 0),
        "",
        Solid(Primitive::Block),
        "a box filling the scope",
    ),
    row(
        "@Cyl",
        (0, 1),
        "16 sides",
        Solid(Primitive::Cylinder),
        "a cylinder standing in the scope",
    ),
    row(
        "@Prism",
        (0, 0),
        "",
        Solid(Primitive::Prism),
        "a gable prism filling the scope (ridge along x)",
    ),
    row(
        "@Roof",
        (4, 10),
        "",
        Solid(Primitive::Roof),
        "a Chinese roof filling the scope (ridge along x): hip (1) or gable (0), tile spacing, eaves run and one jujia per purlin step",
    ),
    row(
        "@Hole",
        (0, 0),
        "",
        Hole,
        "cut an opening of the scope's size through the blocks it meets",
    ),
    row(
        "@Snap",
        (1, 1),
        "",
        Snap,
        "later blocks snap to earlier blocks' faces within d (0: off)",
    ),
    row(
        "@Tex",
        (1, 5),
        "the whole image",
        Texture,
        "project texture n's crop u0,v0,u1,v1 (0..1, v up) along the scope's z onto later blocks' faces that face it (0: off)",
    ),
];
