"""Grammars cross process boundaries (pickle: source, defines, seed) and
long derivations and builds release the GIL."""

import multiprocessing
import pickle
import threading
import time

import pailou

STOCHASTIC = "derivation length: 10\nAxiom: A\nA --> A B : 0.5\nA --> A C : 0.5\n"


def _derive(g):
    return str(g.derive())


def _glb(g):
    return g.build().to_glb()


def test_a_grammar_pickles_as_source_defines_and_seed(tmp_path):
    g = pailou.Grammar.from_str("s.lsys", STOCHASTIC, seed=7)
    back = pickle.loads(pickle.dumps(g))
    assert str(back.derive()) == str(g.derive())
    (tmp_path / "t.lsys").write_text("#define N 2\nAxiom: A(0)\nA(x) : x < N --> A(x+1) B\n")
    p = pailou.Grammar.from_path(tmp_path / "t.lsys", defines={"N": 4})
    assert str(pickle.loads(pickle.dumps(p)).derive(6)) == str(p.derive(6)) == "A(4) B B B B"
    std = pailou.Grammar.from_path("std:toukung_middle", defines={"NTL": 3})
    assert pickle.loads(pickle.dumps(std)).build().to_glb() == std.build().to_glb()


def test_a_pickled_grammar_is_rebuilt_in_another_process():
    grammars = [pailou.Grammar.from_str("s.lsys", STOCHASTIC, seed=s) for s in range(4)]
    ctx = multiprocessing.get_context("spawn")  # a fresh interpreter, no fork
    with ctx.Pool(2) as pool:
        strings = pool.map(_derive, grammars)
        glbs = pool.map(_glb, grammars[:2])
    assert strings == [str(g.derive()) for g in grammars]
    assert glbs == [g.build().to_glb() for g in grammars[:2]]


BUSHY = "derivation length: 10\nangle: 22.5\nAxiom: A\nA --> F [+A] [-A] [&A] F A\nF --> F F\n"


def test_builds_release_the_gil():
    g = pailou.Grammar.from_str("bushy.lsys", BUSHY)
    t0 = time.perf_counter()
    g.build()
    alone = time.perf_counter() - t0
    ticks = 0
    worker = threading.Thread(target=g.build)
    worker.start()
    while worker.is_alive():
        ticks += 1
    worker.join()
    # Held through the build, the GIL would let this loop run only at the
    # build's start and end: a few switch intervals (5 ms each).
    assert alone > 0.05, "the build is too short to tell"
    assert ticks > 10_000, f"{ticks} loop turns during a {alone:.2f} s build"


def test_deep_grammars_compile_on_a_small_python_thread():
    # 250 nested parentheses and a 1,999-operator chain are within the
    # parser's limits; the compiler recurses that deep on its own thread
    # (the binary's deep stack), not on the caller's 256 KiB one.
    deep = "Axiom: F(" + "(" * 250 + "1" + ")" * 250 + ") G(" + "+".join(["1"] * 2000) + ")\n"
    got = {}

    def work():
        try:
            g = pailou.Grammar.from_str("deep.lsys", deep)
            got["derived"] = str(g.derive(0))
            got["triangles"] = g.build(0).triangle_count
        except Exception as e:  # noqa: BLE001 - reported below
            got["error"] = e

    old = threading.stack_size(256 * 1024)
    try:
        t = threading.Thread(target=work)
        t.start()
        t.join()
    finally:
        threading.stack_size(old)
    assert "error" not in got, got.get("error")
    assert got["derived"] == "F(1) G(2000)"
    assert got["triangles"] > 0
