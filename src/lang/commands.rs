//! The one table of turtle commands: symbol, accepted parameter counts,
//! default argument, what the turtle does in each dialect, and meaning.
//! Resolve reads it to build the alphabet (so `FF` splits into two `F`s and
//! `@Gs` is one command) and to check parameter counts, the turtle reads
//! the action, and `lsys commands` prints it.

use super::profile::Dialect;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ShapeKind {
    /// `@O`: a sphere.
    Sphere,
    /// `@o`: a filled disc facing the heading.
    Disc,
    /// `@c`: a circle (a thin ring) facing the heading.
    Circle,
}

/// What the turtle does for a command.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Action {
    Nothing,
    /// Move; `draw` a tube; `vertex`: add a polygon vertex inside `{ }`.
    Move {
        draw: bool,
        vertex: bool,
    },
    /// Rotate about U (+1: toward L), L (+1: pitch down) or H (+1: roll left).
    Turn(f32),
    Pitch(f32),
    Roll(f32),
    TurnAround,
    RollAround,
    PitchAround,
    RollHorizontal,
    HeadingUp,
    /// Mirror the frame: negate L, so that what follows is drawn as the
    /// mirror image (turns toward L go the other way, components placed
    /// after it are mirrored in their width).
    Mirror,
    Cut,
    Push,
    Pop,
    SetWidth,
    IncWidth,
    SetColour,
    DecColour,
    IncColour,
    PolyStart,
    PolyVertex,
    PolyEnd,
    Shape(ShapeKind),
    MoveTo,
    SetHeading,
    Elasticity,
    Tropism,
    CylStart,
    CylPoint,
    CylEnd,
    /// cpfg's `@#(id)`: generalized cylinders take the view file's
    /// contour `id` as their cross-section (`@#` alone: round).
    CylContour,
    ScaleSet,
    ScaleMul,
    ScaleDiv,
    /// cpfg's `?(n, s)`: a sub-L-system starts; steps and widths are
    /// scaled by s until its `$`.
    SubStart,
    /// cpfg's `$`: the sub-L-system ends and the scale before it returns.
    SubEnd,
    /// Scopes, splits and primitives (docs/shapes.md).
    Scope(super::scope_commands::ScopeCmd),
}

/// One turtle command.
#[derive(Clone, Copy, Debug)]
pub struct Command {
    pub symbol: &'static str,
    /// Fewest and most parameters accepted. cpfg files pass extra
    /// parameters to some commands (`F(3,1)`, `!(w,n,f)`); the turtle reads
    /// the ones described in `doc` and ignores the rest, as cpfg does.
    pub min_args: u8,
    pub max_args: u8,
    /// What a missing parameter means, for the help text.
    pub default: &'static str,
    /// The action in the paper's dialect and in cpfg's.
    pub paper: Action,
    pub cpfg: Action,
    /// What the command does, with its parameters named.
    pub doc: &'static str,
}

impl Command {
    pub fn action(&self, dialect: Dialect) -> Action {
        match dialect {
            Dialect::Paper => self.paper,
            Dialect::Cpfg => self.cpfg,
        }
    }
}

pub(super) const fn cmd(
    symbol: &'static str,
    args: (u8, u8),
    default: &'static str,
    action: Action,
    doc: &'static str,
) -> Command {
    Command {
        symbol,
        min_args: args.0,
        max_args: args.1,
        default,
        paper: action,
        cpfg: action,
        doc,
    }
}

/// A command whose meaning depends on the dialect.
const fn clash(symbol: &'static str, paper: Action, cpfg: Action, doc: &'static str) -> Command {
    Command {
        symbol,
        min_args: 0,
        max_args: 0,
        default: "",
        paper,
        cpfg,
        doc,
    }
}

use Action::*;

const STEP: &str = "the step";
const ANGLE: &str = "the angle";
const MOVE_DRAW: Action = Move {
    draw: true,
    vertex: true,
};

/// Every turtle command, paper (Table 1) and cpfg. Where the two notations
/// give a symbol different meanings (`%`, `$`), the dialect picks.
pub const COMMANDS: &[Command] = &[
    cmd(
        "F",
        (0, 2),
        STEP,
        MOVE_DRAW,
        "move forward by d and draw: F, F(d)",
    ),
    cmd(
        "f",
        (0, 1),
        STEP,
        Move {
            draw: false,
            vertex: true,
        },
        "move forward by d without drawing (a polygon vertex inside { })",
    ),
    cmd(
        "G",
        (0, 1),
        STEP,
        Move {
            draw: true,
            vertex: false,
        },
        "move forward by d and draw, without adding a polygon vertex",
    ),
    cmd(
        "g",
        (0, 1),
        STEP,
        Move {
            draw: false,
            vertex: false,
        },
        "move forward by d without drawing or adding a vertex",
    ),
    cmd("+", (0, 1), ANGLE, Turn(1.0), "turn left by θ: +, +(θ)"),
    cmd("-", (0, 1), ANGLE, Turn(-1.0), "turn right by θ: -, -(θ)"),
    cmd("&", (0, 1), ANGLE, Pitch(1.0), "pitch down by θ: &, &(θ)"),
    cmd("^", (0, 1), ANGLE, Pitch(-1.0), "pitch up by θ: ^, ^(θ)"),
    cmd(
        "\\",
        (0, 1),
        ANGLE,
        Roll(1.0),
        "roll left by θ (cpfg): \\, \\(θ)",
    ),
    cmd(
        "/",
        (0, 1),
        ANGLE,
        Roll(-1.0),
        "roll right by θ (cpfg): /, /(θ)",
    ),
    cmd(
        "<",
        (0, 1),
        ANGLE,
        Roll(1.0),
        "roll left by θ (paper notation)",
    ),
    cmd(
        ">",
        (0, 1),
        ANGLE,
        Roll(-1.0),
        "roll right by θ (paper notation)",
    ),
    cmd(
        "|",
        (0, 0),
        "",
        TurnAround,
        "turn around: 180° about the up axis",
    ),
    clash(
        "%",
        RollAround,
        Cut,
        "paper: roll 180°; cpfg: cut the rest of the branch",
    ),
    clash(
        "$",
        PitchAround,
        SubEnd,
        "paper: pitch 180°; cpfg: end a sub-L-system `?(n,s) ... $` (its scale s ends; `@v` rolls horizontal)",
    ),
    cmd(
        "[",
        (0, 0),
        "",
        Push,
        "push the turtle state (start a branch)",
    ),
    cmd("]", (0, 0), "", Pop, "pop the turtle state (end a branch)"),
    cmd(
        "!",
        (0, 4),
        "a tenth of the initial width less",
        SetWidth,
        "set the line width: !(w); without a parameter, decrement it",
    ),
    cmd(
        "#",
        (0, 1),
        "a tenth of the initial width",
        IncWidth,
        "increase the line width: #(w) adds w (cpfg: sets it to w, as `!(w)`)",
    ),
    cmd(
        ";",
        (0, 2),
        "the next index",
        SetColour,
        "set the colour index: ;(i); without a parameter, increment it",
    ),
    cmd(
        ",",
        (0, 2),
        "the previous index",
        DecColour,
        "set the colour index: ,(i); without a parameter, decrement it",
    ),
    cmd(
        "'",
        (0, 1),
        "the next index",
        IncColour,
        "set the colour index: '(i); without a parameter, increment it (ABOP)",
    ),
    cmd("{", (0, 0), "", PolyStart, "start a polygon at the turtle"),
    cmd(
        ".",
        (0, 0),
        "",
        PolyVertex,
        "add the turtle's position to the polygon",
    ),
    cmd("}", (0, 0), "", PolyEnd, "end the polygon and draw it"),
    cmd(
        "@O",
        (0, 1),
        "the line width",
        Shape(ShapeKind::Sphere),
        "draw a sphere of diameter d: @O, @O(d)",
    ),
    cmd(
        "@o",
        (0, 1),
        "the line width",
        Shape(ShapeKind::Disc),
        "draw a disc of diameter d facing the heading",
    ),
    cmd(
        "@c",
        (0, 1),
        "the line width",
        Shape(ShapeKind::Circle),
        "draw a circle of diameter d facing the heading",
    ),
    cmd(
        "@v",
        (0, 0),
        "",
        RollHorizontal,
        "roll so that the left axis is horizontal",
    ),
    cmd(
        "@M",
        (3, 3),
        "",
        MoveTo,
        "move the turtle to the point (x,y,z) without drawing",
    ),
    cmd(
        "@m",
        (3, 3),
        "",
        MoveTo,
        "move to the point (x,y,z) without drawing (as @M)",
    ),
    cmd(
        "@R",
        (3, 6),
        "",
        SetHeading,
        "set the heading (and up) vectors: @R(hx,hy,hz[,ux,uy,uz])",
    ),
    cmd(
        "@Ts",
        (0, 1),
        "0 (off)",
        Elasticity,
        "set the tropism elasticity e (cpfg: @Ts(i, e), tropism i)",
    ),
    cmd(
        "@T",
        (0, 4),
        "off",
        Tropism,
        "set tropism: @T(x,y,z,e), @T(x,y,z), @T(e); @T alone turns it off",
    ),
    cmd(
        "@Gs",
        (0, 0),
        "",
        CylStart,
        "start a generalized cylinder at the turtle",
    ),
    cmd(
        "@Gc",
        (0, 1),
        "8 segments",
        CylPoint,
        "add a control point to the generalized cylinder: @Gc(n)",
    ),
    cmd(
        "@Ge",
        (0, 1),
        "8 segments",
        CylEnd,
        "add the last control point and draw the generalized cylinder: @Ge(n)",
    ),
    cmd(
        "@#",
        (0, 1),
        "round",
        CylContour,
        "cpfg: the cross-section of generalized cylinders: @#(id) the view file's `contour: id FILE`",
    ),
    cmd(
        "@Gr",
        (0, 4),
        "",
        Nothing,
        "generalized cylinder radius profile (accepted, draws nothing)",
    ),
    cmd(
        "@Gt",
        (0, 2),
        "",
        Nothing,
        "generalized cylinder tangent parameters (accepted, draws nothing)",
    ),
    cmd("@D", (0, 1), "1", ScaleSet, "set the step scale s: @D(s)"),
    cmd("@Di", (0, 1), "1", ScaleMul, "multiply the step scale by s"),
    cmd("@Dd", (0, 1), "1", ScaleDiv, "divide the step scale by s"),
    cmd("@L", (0, 1), "", Nothing, "label (accepted, draws nothing)"),
    cmd(
        "@!",
        (0, 1),
        "",
        Nothing,
        "cpfg: the number of sides of cylinders and spheres (accepted; lsys chooses its own)",
    ),
    cmd("@H", (0, 0), "", HeadingUp, "turn the heading straight up"),
    cmd(
        "@X",
        (0, 0),
        "",
        Mirror,
        "mirror the frame (negate the left axis): what follows is drawn mirrored, as the paper's `|` between two halves means",
    ),
];

/// The command named `symbol`, if any.
pub fn lookup(symbol: &str) -> Option<&'static Command> {
    all().find(|c| c.symbol == symbol)
}

/// Every command: the classic table, then the shape commands
/// (lang/scope_commands.rs).
pub fn all() -> impl Iterator<Item = &'static Command> {
    COMMANDS.iter().chain(super::scope_commands::SCOPE_COMMANDS)
}

/// The table as text, for `lsys commands`.
pub fn help_text() -> String {
    let mut out = String::from("symbol  parameters  default                             meaning\n");
    for c in all() {
        let args = if c.min_args == c.max_args {
            format!("{}", c.min_args)
        } else {
            format!("{}-{}", c.min_args, c.max_args)
        };
        out.push_str(&format!(
            "{:<7} {:<11} {:<35} {}\n",
            c.symbol,
            args,
            if c.default.is_empty() { "-" } else { c.default },
            c.doc
        ));
    }
    out.push_str(
        "~X      0, 1 or 3   scale 1                             place component X: ~X(s), ~X(sx,sy,sz); in a scope ~X fills it\n",
    );
    out
}
