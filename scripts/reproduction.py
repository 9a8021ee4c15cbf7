#!/usr/bin/env python3
"""Measures the paper's Table 2 (Toukungs) and Table 3 (Pailous) with the
release binary and prints the markdown tables of docs/reproduction.md.
Times are the median of 5 runs of the sum of --stats stages (parse, derive,
interpret, mesh, write)."""
import json, statistics, subprocess, sys, tempfile, os, glob

LSYS = "target/release/lsys"
PAPER_TOUKUNG = {("middle", 3): 4.33e3, ("middle", 5): 8.04e3, ("middle", 7): 1.22e4, ("middle", 18): 3.37e4,
                 ("side", 3): 6.71e3, ("side", 5): 1.75e4, ("side", 7): 3.13e4, ("side", 18): 1.87e5}

def stats(args):
    out = tempfile.mktemp(suffix=".glb")
    runs = []
    for _ in range(5):
        p = subprocess.run([LSYS] + args + ["-o", out, "--stats"], capture_output=True, text=True, check=True)
        runs.append(json.loads(p.stdout.strip().splitlines()[-1]))
    os.remove(out)
    ms = statistics.median(sum(r["timings_ms"].values()) for r in runs)
    return runs[0], ms

print("| Toukung | levels | components | triangles (ours) | polygons (paper) | ms (ours, median) | paper |")
print("|---|---|---|---|---|---|---|")
for kind in ["middle", "side"]:
    for n in [3, 5, 7, 18]:
        r, ms = stats(["build", f"std:toukung_{kind}", "-D", f"NTL={n}"])
        comps = sum(r["instances"].values())
        print(f"| {kind} | {n} | {comps} | {r['triangles']:,} | {PAPER_TOUKUNG[(kind, n)]:.3g} | {ms:.1f} | about 1 s |")
print()
print("| Pailou (example) | style | pillars | roofs | components | triangles | GLB KB | ms (median) |")
print("|---|---|---|---|---|---|---|---|")
for g in sorted(glob.glob("examples/pailou/*.toml")):
    r, ms = stats(["pailou", g])
    i = r["instances"]
    name = os.path.basename(g)[:-5]
    style = name.split("_")[1]
    print(f"| {name} | {style} | {i.get('MPB', 0)} | {i.get('RE', 0) + i.get('RC', 0)} | {sum(i.values())} | {r['triangles']:,} | {r['output']['bytes'] // 1024:,} | {ms:.1f} |")
