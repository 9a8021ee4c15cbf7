#!/usr/bin/env python3
"""Independent reference derivations for the ABOP examples (examples/abop).

An oracle, not a parser: the axiom and productions of each system are written
out below as Python data, independently of the Rust code.  From each
`examples/abop/<stem>.lsys` file only `derivation length:` and `seed:` are
read; in addition the script checks that every axiom and production written
here also appears, character for character up to white space, in that file,
so the data below and the example files cannot drift apart silently.

Writes `tests/abop_expected/<stem>.txt`: the string after `derivation length`
steps, formatted as lsys prints it (modules separated by single spaces,
parameters as `A(1,2.5)`, a newline at the end), and prints the number of
modules after each step.

Usage:
    python3 scripts/abop_oracle.py            # write the expected files
    python3 scripts/abop_oracle.py --check    # compare, write nothing, exit 1 on a difference
    python3 scripts/abop_oracle.py STEM...    # only these systems

Semantics (those of cpfg, as the lsys specification states them):
  * parallel rewriting; the first matching production in file order wins;
    a module no production matches is copied;
  * a pattern module matches only modules with the same name and the same
    number of parameters;
  * context: the left context scans leftwards from the predecessor, skipping
    ignored symbols; a `]` skips the whole branch (to its matching `[`, then
    on to the left of it); a `[` is climbed out of (skipped).  The right
    context scans rightwards, skipping ignored symbols; a `[` the pattern does
    not expect skips the whole branch; a `]` ends the current branch: fail;
  * stochastic productions: POSIX erand48 seeded like srand48(seed); each
    module that has stochastic productions takes exactly one draw u in [0,1),
    left to right, step after step; with weights w1..wk (sum S) the first i
    with u*S < w1+...+wi is chosen.
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Optional

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples" / "abop"
EXPECTED = ROOT / "tests" / "abop_expected"

# A module is (name, params); params is a tuple of floats, () for none.
Module = tuple[str, tuple[float, ...]]


# --------------------------------------------------------------------------
# erand48 / srand48 (POSIX): 48-bit linear congruential generator.

class Drand48:
    A = 0x5DEECE66D
    C = 0xB
    MASK = (1 << 48) - 1

    def __init__(self, seed: int) -> None:
        # srand48(seed): high 32 bits = low 32 bits of seed, low 16 = 0x330E.
        self.x = (((seed & 0xFFFFFFFF) << 16) | 0x330E) & self.MASK

    def next(self) -> float:
        self.x = (self.A * self.x + self.C) & self.MASK
        return self.x / float(1 << 48)  # exact: 48 bits fit a double


# --------------------------------------------------------------------------
# Number and string formatting, as lsys prints them.

def fmt_num(v: float) -> str:
    r = repr(float(v))
    if r.endswith(".0"):
        r = r[:-2]
    return r


def fmt_module(m: Module) -> str:
    name, params = m
    if not params:
        return name
    return name + "(" + ",".join(fmt_num(p) for p in params) + ")"


def fmt_string(s: list[Module]) -> str:
    return " ".join(fmt_module(m) for m in s) + "\n"


def syms(text: str) -> list[Module]:
    """Parameterless modules, one a character ("F[+F]" -> F [ + F ])."""
    return [(c, ()) for c in text if not c.isspace()]


# --------------------------------------------------------------------------
# Productions.

@dataclass
class Pattern:
    name: str
    vars: tuple[str, ...] = ()


@dataclass
class Production:
    pred: Pattern
    succ: Callable[[dict], list[Module]]
    text: str                                  # as written in the .lsys file
    left: list[Pattern] = field(default_factory=list)
    right: list[Pattern] = field(default_factory=list)
    cond: Optional[Callable[[dict], bool]] = None
    prob: Optional[float] = None


def plain(pred: str, succ: str, prob: Optional[float] = None,
          left: str = "", right: str = "") -> Production:
    """A production over parameterless single-character modules."""
    text = ""
    if left:
        text += f"{left} < "
    text += pred
    if right:
        text += f" > {right}"
    text += f" --> {succ}"
    if prob is not None:
        text += f" : {prob}"
    out = syms(succ)
    return Production(
        pred=Pattern(pred),
        succ=lambda env, out=out: list(out),
        text=text,
        left=[Pattern(c) for c in left],
        right=[Pattern(c) for c in right],
        prob=prob,
    )


@dataclass
class System:
    stem: str
    axiom: list[Module]
    axiom_text: str
    prods: list[Production]
    ignore: str = ""


BRACKETS = "[]"


def bind(pat: Pattern, m: Module, env: dict) -> bool:
    name, params = m
    if name != pat.name or len(params) != len(pat.vars):
        return False
    for v, x in zip(pat.vars, params):
        env[v] = x
    return True


def match_left(s: list[Module], pos: int, pats: list[Pattern],
               ignore: str, env: dict) -> bool:
    i = pos - 1
    for pat in reversed(pats):
        assert pat.name not in BRACKETS, "brackets in a left context: not needed here"
        while True:
            if i < 0:
                return False
            c = s[i][0]
            if c in ignore:
                i -= 1
            elif c == "]":
                depth = 1            # jump to the matching '[' ...
                i -= 1
                while depth:
                    if s[i][0] == "]":
                        depth += 1
                    elif s[i][0] == "[":
                        depth -= 1
                    i -= 1           # ... and continue left of it
            elif c == "[":
                i -= 1               # climb out of the branch
            else:
                break
        if not bind(pat, s[i], env):
            return False
        i -= 1
    return True


def match_right(s: list[Module], pos: int, pats: list[Pattern],
                ignore: str, env: dict) -> bool:
    j = pos + 1
    for pat in pats:
        assert pat.name not in BRACKETS, "brackets in a right context: not needed here"
        while True:
            if j >= len(s):
                return False
            c = s[j][0]
            if c in ignore:
                j += 1
            elif c == "[":
                depth = 1            # skip the whole branch
                j += 1
                while depth:
                    if s[j][0] == "[":
                        depth += 1
                    elif s[j][0] == "]":
                        depth -= 1
                    j += 1
            elif c == "]":
                return False         # end of the current branch
            else:
                break
        if not bind(pat, s[j], env):
            return False
        j += 1
    return True


def applicable(p: Production, s: list[Module], pos: int, ignore: str) -> Optional[dict]:
    env: dict = {}
    if not bind(p.pred, s[pos], env):
        return None
    if p.left and not match_left(s, pos, p.left, ignore, env):
        return None
    if p.right and not match_right(s, pos, p.right, ignore, env):
        return None
    if p.cond is not None and not p.cond(env):
        return None
    return env


def step(sys_: System, s: list[Module], rng: Optional[Drand48]) -> list[Module]:
    out: list[Module] = []
    for pos, m in enumerate(s):
        cands = [p for p in sys_.prods
                 if p.pred.name == m[0] and len(p.pred.vars) == len(m[1])]
        stoch = [p for p in cands if p.prob is not None]
        if stoch:
            # Only what the examples need: a predecessor is either wholly
            # stochastic (context-free, unconditional) or not at all.
            assert len(stoch) == len(cands)
            assert all(not p.left and not p.right and p.cond is None for p in stoch)
            assert rng is not None, "stochastic productions need a seed"
            u = rng.next()
            total = 0.0
            for p in stoch:
                total += p.prob
            acc = 0.0
            chosen = stoch[-1]
            for p in stoch:
                acc += p.prob
                if u * total < acc:
                    chosen = p
                    break
            out.extend(chosen.succ({}))
            continue
        for p in cands:
            env = applicable(p, s, pos, sys_.ignore)
            if env is not None:
                out.extend(p.succ(env))
                break
        else:
            out.append(m)
    return out


# --------------------------------------------------------------------------
# The systems (ABOP chapter 1), transcribed from the book.

def edge(stem: str, axiom: str, *rules: tuple) -> System:
    return System(stem, syms(axiom), axiom,
                  [plain(*r) for r in rules])


def parametric_1_10() -> System:
    A = lambda x, y: ("A", (float(x), float(y)))
    B = lambda x: ("B", (float(x),))
    C = ("C", ())
    prods = [
        Production(Pattern("A", ("x", "y")),
                   lambda e: [A(e["x"] * 2, e["x"] + e["y"])],
                   "A(x,y) : y <= 3 --> A(x*2,x+y)",
                   cond=lambda e: e["y"] <= 3),
        Production(Pattern("A", ("x", "y")),
                   lambda e: [B(e["x"]), A(e["x"] / e["y"], 0)],
                   "A(x,y) : y > 3 --> B(x)A(x/y,0)",
                   cond=lambda e: e["y"] > 3),
        Production(Pattern("B", ("x",)),
                   lambda e: [C],
                   "B(x) : x < 1 --> C",
                   cond=lambda e: e["x"] < 1),
        Production(Pattern("B", ("x",)),
                   lambda e: [B(e["x"] - 1)],
                   "B(x) : x >= 1 --> B(x-1)",
                   cond=lambda e: e["x"] >= 1),
    ]
    return System("parametric_1_10", [B(2), A(4, 4)], "B(2)A(4,4)", prods)


def fig1_31a() -> System:
    table = [  # left, strict predecessor, right, successor
        ("0", "0", "0", "0"),
        ("0", "0", "1", "1[+F1F1]"),
        ("0", "1", "0", "1"),
        ("0", "1", "1", "1"),
        ("1", "0", "0", "0"),
        ("1", "0", "1", "1F1"),
        ("1", "1", "0", "0"),
        ("1", "1", "1", "0"),
    ]
    prods = [plain(p, succ, left=l, right=r) for l, p, r, succ in table]
    prods += [plain("+", "-"), plain("-", "+")]
    return System("fig1_31a", syms("F1F1F1"), "F1F1F1", prods, ignore="+-F")


SYSTEMS: list[System] = [
    edge("koch_quadratic_island", "F-F-F-F",
         ("F", "F+FF-FF-F-F+F+FF-F-F+F+FF+FF-F")),
    edge("fig1_6_koch_island", "F-F-F-F",
         ("F", "F-F+F+FF-F-F+F")),
    edge("fig1_8_islands_lakes", "F+F+F+F",
         ("F", "F+f-FF+F+FF+Ff+FF-f+FF-F-FF-Ff-FFF"),
         ("f", "ffffff")),
    edge("koch_snowflake", "F--F--F",
         ("F", "F+F--F+F")),
    edge("fig1_24a", "F", ("F", "F[+F]F[-F]F")),
    edge("fig1_24b", "F", ("F", "F[+F]F[-F][F]")),
    edge("fig1_24c", "F", ("F", "FF-[-F+F+F]+[+F-F-F]")),
    edge("fig1_24d", "X", ("X", "F[+X]F[-X]+X"), ("F", "FF")),
    edge("fig1_24e", "X", ("X", "F[+X][-X]FX"), ("F", "FF")),
    edge("fig1_24f", "X", ("X", "F-[[X]+X]+F[+FX]-X"), ("F", "FF")),
    parametric_1_10(),
    fig1_31a(),
    edge("stochastic_1_27", "F",
         ("F", "F[+F]F[-F]F", 0.33),
         ("F", "F[+F]F", 0.33),
         ("F", "F[-F]F", 0.34)),
]


# --------------------------------------------------------------------------
# Reading the example files (derivation length, seed, consistency check).

def strip_comments(text: str) -> str:
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def squash(s: str) -> str:
    return re.sub(r"\s+", "", s)


def read_settings(sys_: System) -> tuple[int, Optional[int]]:
    path = EXAMPLES / f"{sys_.stem}.lsys"
    text = strip_comments(path.read_text())
    lines = {squash(l) for l in text.splitlines() if l.strip()}
    m = re.search(r"^\s*derivation\s+length\s*:\s*(\d+)\s*$", text, re.M)
    if not m:
        sys.exit(f"{path}: no 'derivation length:' line")
    n = int(m.group(1))
    m = re.search(r"^\s*seed\s*:\s*(-?\d+)\s*$", text, re.M)
    seed = int(m.group(1)) if m else None
    missing = []
    if squash("Axiom: " + sys_.axiom_text) not in lines:
        missing.append("Axiom: " + sys_.axiom_text)
    missing += [p.text for p in sys_.prods if squash(p.text) not in lines]
    if sys_.ignore and squash("ignore: " + sys_.ignore) not in lines:
        missing.append("ignore: " + sys_.ignore)
    if missing:
        sys.exit(f"{path}: the oracle's data is not in the file:\n  "
                 + "\n  ".join(missing))
    return n, seed


def derive(sys_: System, n: int, seed: Optional[int]) -> tuple[list[Module], list[int]]:
    rng = Drand48(seed) if seed is not None else None
    s = list(sys_.axiom)
    counts = [len(s)]
    for _ in range(n):
        s = step(sys_, s, rng)
        counts.append(len(s))
    return s, counts


# --------------------------------------------------------------------------
# Self-checks on small cases the book prints.

def self_test() -> None:
    par = parametric_1_10()
    book = ["B(2)A(4,4)", "B(1)B(4)A(1,0)", "B(0)B(3)A(2,1)",
            "CB(2)A(4,3)", "CB(1)A(8,7)"]
    s = list(par.axiom)
    for i, want in enumerate(book):
        got = "".join(fmt_module(m) for m in s)
        assert got == want, f"parametric step {i}: {got} != {want}"
        s = step(par, s, None)
    assert "".join(fmt_module(m) for m in s) == \
        "CB(0)B(8)A(1.1428571428571428,0)"

    a = edge("t", "F", ("F", "F[+F]F[-F]F"))
    s = step(a, list(a.axiom), None)
    assert fmt_string(s) == "F [ + F ] F [ - F ] F\n"

    # Context: F1F1F1 after one step.  First 1 has no left context: copied.
    # Middle 1: 1 < 1 > 1 -> 0.  Last 1 has no right context: copied.
    c = fig1_31a()
    s = step(c, list(c.axiom), None)
    assert "".join(m[0] for m in s) == "F1F0F1", s
    # Branch skipping: in 0[+F1]F1 the first 0 sees 1 to its right (the
    # branch is skipped); the 1 inside the branch sees 0 to its left
    # (climbing out of '[') and ']' to its right (fail: copied).
    s = step(c, syms("10[+F1]F1"), None)
    assert "".join(m[0] for m in s) == "11F1[-F1]F1", s

    # srand48(1); drand48() x 3, as printed by glibc with %.17g.
    r = Drand48(1)
    assert [r.next() for _ in range(3)] == \
        [0.041630344771878214, 0.45449244472862915, 0.8348172181669149]

    assert fmt_num(1.0) == "1" and fmt_num(-0.0) == "-0" and fmt_num(0.5) == "0.5"
    assert fmt_num(1 / 3) == "0.3333333333333333"


def main(argv: list[str]) -> int:
    check = "--check" in argv
    stems = [a for a in argv if not a.startswith("-")]
    known = {s.stem for s in SYSTEMS}
    for st in stems:
        if st not in known:
            sys.exit(f"unknown system {st!r}; known: {', '.join(sorted(known))}")
    self_test()
    EXPECTED.mkdir(parents=True, exist_ok=True)
    bad = 0
    for sys_ in SYSTEMS:
        if stems and sys_.stem not in stems:
            continue
        n, seed = read_settings(sys_)
        s, counts = derive(sys_, n, seed)
        text = fmt_string(s)
        out = EXPECTED / f"{sys_.stem}.txt"
        status = ""
        if check:
            if not out.exists() or out.read_text() != text:
                status = "  DIFFERS"
                bad += 1
        else:
            out.write_text(text)
        seed_note = f", seed {seed}" if seed is not None else ""
        print(f"{sys_.stem}: n={n}{seed_note}; modules per step: "
              + " ".join(map(str, counts)) + status)
    if check:
        print("all expected files agree" if not bad else f"{bad} file(s) differ")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
