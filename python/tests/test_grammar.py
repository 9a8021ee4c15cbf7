"""Grammar: compiling from text and paths, defines, seeds, derive and
steps as `lsys derive` prints them, and errors as LsysError."""

import subprocess

import pytest

import pailou

TREE = """\
#define N 3
derivation length: 3
Axiom: A(1)
A(s) : s < N --> F(1) [+A(s+1)] [-A(s+1)]
A(s) : else --> L
F(x) --> F(x*1.5)
"""

STOCHASTIC = "Axiom: A\nA --> A B : 0.5\nA --> A C : 0.5\n"


def test_from_str_derives_like_the_command_line(tmp_path, lsys_bin):
    g = pailou.Grammar.from_str("tree.lsys", TREE)
    path = tmp_path / "tree.lsys"
    path.write_text(TREE)
    for n in (0, 1, 3):
        cli = subprocess.run(
            [lsys_bin, "derive", str(path), "-n", str(n)],
            check=True, capture_output=True, text=True,
        ).stdout
        assert str(g.derive(n)) + "\n" == cli
    assert str(g.derive()) == str(g.derive(3))
    assert g.derive(2).step == 2
    assert len(g.derive(1)) == 9  # F(1) [ + A(2) ] [ - A(2) ]


def test_steps_are_derive_every(tmp_path, lsys_bin):
    g = pailou.Grammar.from_str("tree.lsys", TREE)
    path = tmp_path / "tree.lsys"
    path.write_text(TREE)
    cli = subprocess.run(
        [lsys_bin, "derive", str(path), "--every"],
        check=True, capture_output=True, text=True,
    ).stdout
    steps = list(g.steps())
    assert [s.step for s in steps] == [0, 1, 2, 3]
    assert "".join(str(s) + "\n" for s in steps) == cli
    assert [str(s) for s in g.steps(1)] == ["A(1)", "F(1) [ + A(2) ] [ - A(2) ]"]


def test_defines_override_like_dash_d():
    g = pailou.Grammar.from_str("tree.lsys", TREE, defines={"N": 1})
    assert str(g.derive(1)) == "L"
    # A misspelt define is refused, not ignored.
    with pytest.raises(pailou.LsysError) as e:
        pailou.Grammar.from_str("tree.lsys", TREE, defines={"M": 1})
    assert "M" in str(e.value)


def test_namespaced_defines_reach_a_grammar_component():
    # TM.NTL sets NTL in the middle Toukungs the Pailou places.
    plain = pailou.Grammar.from_path("std:pailou").build()
    three = pailou.Grammar.from_path("std:pailou", defines={"TM.NTL": 3}).build()
    assert three.stats["triangles"] < plain.stats["triangles"]


def test_seed_fixes_a_stochastic_derivation():
    a = pailou.Grammar.from_str("s.lsys", STOCHASTIC, seed=1)
    b = pailou.Grammar.from_str("s.lsys", STOCHASTIC, seed=1)
    assert str(a.derive(12)) == str(b.derive(12))
    others = {str(pailou.Grammar.from_str("s.lsys", STOCHASTIC, seed=s).derive(12)) for s in range(2, 8)}
    assert len(others) > 1


def test_from_path_takes_files_std_and_pathlib(tmp_path):
    (tmp_path / "params.lsys").write_text("#define N 2\n")
    (tmp_path / "t.lsys").write_text('#include "params.lsys"\n' + TREE.replace("#define N 3\n", ""))
    g = pailou.Grammar.from_path(tmp_path / "t.lsys")
    assert str(g.derive(2)) == "F(1.5) [ + L ] [ - L ]"  # N 2 from the include
    assert pailou.Grammar.from_path(str(tmp_path / "t.lsys")).name.endswith("t.lsys")
    assert pailou.Grammar.from_path("std:toukung_middle").derivation_length > 0


def test_a_syntax_error_raises_with_typed_diagnostics(tmp_path, lsys_bin):
    text = "Axiom: A\nA --> B(\n"
    with pytest.raises(pailou.LsysError) as e:
        pailou.Grammar.from_str("broken.lsys", text)
    d = e.value.diagnostics
    assert len(d) == 1
    assert d[0]["code"] == "lsys::parse::syntax"
    assert (d[0]["severity"], d[0]["file"], d[0]["line"], d[0]["column"]) == ("error", "broken.lsys", 2, 8)
    assert d[0]["message"] and d[0]["help"]
    # str() is what `lsys check` prints.
    path = tmp_path / "broken.lsys"
    path.write_text(text)
    check = subprocess.run(
        [lsys_bin, "check", "broken.lsys", "--color", "never"],
        capture_output=True, text=True, cwd=tmp_path,
    )
    assert check.returncode == 65
    assert str(e.value) + "\n" == check.stderr


def test_a_missing_file_raises():
    with pytest.raises(pailou.LsysError) as e:
        pailou.Grammar.from_path("/no/such/grammar.lsys")
    assert e.value.diagnostics[0]["severity"] == "error"
    with pytest.raises(pailou.LsysError):
        pailou.Grammar.from_path("std:no_such_grammar")
