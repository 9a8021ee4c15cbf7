"""The Python call's overhead over the same build in Rust.

For each model, `Grammar.build()` is timed from Python (wall clock, the
median of several runs) and divided by the time the Rust build itself
spent on the same work (`stats["timings_ms"]`: parse, derive, interpret,
mesh). The difference is what the Python layer adds: running the driver
job, expanding the scene into arrays, and wrapping them for NumPy.

    python python/bench/overhead.py [--runs 15]
"""

import argparse
import statistics
import time

import pailou

PLANT = """\
derivation length: 7
angle: 22.5
Axiom: A
A --> F [+A] [-A] [&A] F A
F --> F F
"""

MODELS = [
    ("plant (7 steps)", lambda: pailou.Grammar.from_str("plant.lsys", PLANT)),
    ("std:toukung_middle", lambda: pailou.Grammar.from_path("std:toukung_middle")),
    ("std:toukung_side NTL=18", lambda: pailou.Grammar.from_path("std:toukung_side", defines={"NTL": 18})),
    ("std:pailou", lambda: pailou.Grammar.from_path("std:pailou")),
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=15)
    args = ap.parse_args()
    print(f"| model | triangles | Python build (ms) | Rust build (ms) | ratio |")
    print(f"|---|---:|---:|---:|---:|")
    for name, make in MODELS:
        g = make()
        g.build()  # warm: components built once per process are cached alike
        py, rust = [], []
        for _ in range(args.runs):
            t0 = time.perf_counter()
            s = g.build()
            py.append((time.perf_counter() - t0) * 1e3)
            t = s.stats["timings_ms"]
            rust.append(t["parse"] + t["derive"] + t["interpret"] + t["mesh"])
        p, r = statistics.median(py), statistics.median(rust)
        print(f"| {name} | {s.triangle_count} | {p:.2f} | {r:.2f} | {p / r:.2f} |")


if __name__ == "__main__":
    main()
