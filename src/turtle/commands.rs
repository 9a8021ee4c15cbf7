//! The one table of turtle commands: symbol, accepted parameter counts and
//! meaning. Resolve reads it to build the alphabet (so `FF` splits into two
//! `F`s and `@Gs` is one command) and to check parameter counts; help text
//! is generated from it.

/// One turtle command.
#[derive(Clone, Copy, Debug)]
pub struct Command {
    pub symbol: &'static str,
    /// Fewest and most parameters accepted.
    pub min_args: u8,
    pub max_args: u8,
    /// What the command does, with its parameters named.
    pub doc: &'static str,
}

const fn cmd(symbol: &'static str, min_args: u8, max_args: u8, doc: &'static str) -> Command {
    Command {
        symbol,
        min_args,
        max_args,
        doc,
    }
}

/// Every turtle command, paper (Table 1) and cpfg. Where the two notations
/// give a symbol different meanings (`%`, `$`, `<`, `>`), `doc` names both.
pub const COMMANDS: &[Command] = &[
    cmd(
        "F",
        0,
        2,
        "move forward by d (default step) and draw: F, F(d)",
    ),
    cmd("f", 0, 1, "move forward by d without drawing: f, f(d)"),
    cmd(
        "G",
        0,
        1,
        "move forward by d and draw, without creating a polygon vertex",
    ),
    cmd(
        "g",
        0,
        1,
        "move forward by d without drawing or creating a vertex",
    ),
    cmd("+", 0, 1, "turn left by θ (default angle): +, +(θ)"),
    cmd("-", 0, 1, "turn right by θ: -, -(θ)"),
    cmd("&", 0, 1, "pitch down by θ: &, &(θ)"),
    cmd("^", 0, 1, "pitch up by θ: ^, ^(θ)"),
    cmd("\\", 0, 1, "roll left by θ (cpfg): \\, \\(θ)"),
    cmd("/", 0, 1, "roll right by θ (cpfg): /, /(θ)"),
    cmd("<", 0, 1, "roll left by θ (paper notation)"),
    cmd(">", 0, 1, "roll right by θ (paper notation)"),
    cmd("|", 0, 0, "turn around: 180° about the up axis"),
    cmd(
        "%",
        0,
        0,
        "paper: roll 180°; cpfg: cut the rest of the branch",
    ),
    cmd(
        "$",
        0,
        0,
        "paper: pitch 180°; cpfg: roll until the left axis is horizontal",
    ),
    cmd("[", 0, 0, "push the turtle state (start a branch)"),
    cmd("]", 0, 0, "pop the turtle state (end a branch)"),
    cmd(
        "!",
        0,
        4,
        "set the line width: !(w); without a parameter, decrement it",
    ),
    cmd("#", 0, 1, "increment the line width (cpfg)"),
    cmd(
        ";",
        0,
        2,
        "set the colour index: ;(i); without a parameter, increment it",
    ),
    cmd(",", 0, 2, "decrement the colour index, or set it: ,(i)"),
    cmd("'", 0, 1, "increment the colour index (ABOP)"),
    cmd("{", 0, 0, "start a polygon"),
    cmd(".", 0, 0, "record a polygon vertex"),
    cmd("}", 0, 0, "end a polygon"),
    cmd("@O", 0, 1, "draw a sphere of diameter d: @O, @O(d)"),
    cmd("@o", 0, 1, "draw a disc of diameter d: @o, @o(d)"),
    cmd("@c", 0, 1, "draw a circle of diameter d"),
    cmd("@v", 0, 0, "roll so that the left axis is horizontal"),
    cmd(
        "@M",
        3,
        3,
        "move the turtle to the point (x,y,z): @M(x,y,z)",
    ),
    cmd("@m", 3, 3, "move to the point (x,y,z) without drawing"),
    cmd(
        "@R",
        3,
        6,
        "set the heading (and up) vectors: @R(hx,hy,hz[,ux,uy,uz])",
    ),
    cmd("@Ts", 0, 1, "set the tropism elasticity"),
    cmd("@T", 0, 4, "set the tropism vector and elasticity"),
    cmd("@Gs", 0, 0, "start a generalized cylinder"),
    cmd(
        "@Gc",
        0,
        1,
        "add a control point to the generalized cylinder",
    ),
    cmd("@Ge", 0, 1, "end the generalized cylinder"),
    cmd("@Gr", 0, 4, "set the generalized cylinder's radius profile"),
    cmd(
        "@Gt",
        0,
        2,
        "set the generalized cylinder's tangent parameters",
    ),
    cmd("@D", 0, 1, "set the step size scale"),
    cmd("@Di", 0, 1, "multiply the step size scale"),
    cmd("@Dd", 0, 1, "divide the step size scale"),
    cmd("@L", 0, 1, "print a label"),
    cmd("@H", 0, 0, "set the turtle's heading up"),
];

/// The command named `symbol`, if any.
pub fn lookup(symbol: &str) -> Option<&'static Command> {
    COMMANDS.iter().find(|c| c.symbol == symbol)
}
