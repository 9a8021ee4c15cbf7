#!/usr/bin/env python3
"""Measures the paper's Table 2 (Toukungs) and Table 3 (Pailous) with the
release binary and prints the markdown tables of docs/reproduction.md, the
paper's values beside ours; renders the front view of each Table 3 Pailou
to docs/images/pailou/<example>.png and its iso view to <example>_iso.png.
Times are the median of 5 runs of the sum of --stats stages (parse, derive,
interpret, mesh, write)."""
import json, statistics, subprocess, sys, tempfile, os, glob

LSYS = "target/release/lsys"
PAPER_TOUKUNG = {("middle", 3): 4.33e3, ("middle", 5): 8.04e3, ("middle", 7): 1.22e4, ("middle", 18): 3.37e4,
                 ("side", 3): 6.71e3, ("side", 5): 1.75e4, ("side", 7): 3.13e4, ("side", 18): 1.87e5}

# Table 3: polygons, modelling time (s), file size (KB) per figure.
PAPER_PAILOU = {"fig17-1": (2.23e5, 45, 4.59e3), "fig17-2": (1.15e6, 140, 1.50e5),
                "fig17-3": (8.94e5, 92, 1.52e4), "fig17-4": (6.88e5, 87, 1.38e4),
                "fig18-1": (1.07e6, 70, 2.11e4), "fig18-2": (2.11e6, 150, 4.28e4),
                "fig18-3": (1.84e6, 200, 3.72e4), "fig18-4": (6.86e5, 39, 1.36e4),
                "fig18-5": (8.71e5, 80, 3.36e4), "fig18-6": (2.48e6, 123, 4.93e4),
                "fig19-1": (7.74e5, 110, 1.54e4), "fig19-2": (9.15e5, 106, 1.82e4),
                "fig19-3": (1.23e6, 113, 2.45e4), "fig19-4": (2.51e6, 297, 5.00e4),
                "fig19-5": (1.78e6, 182, 3.52e4)}

def stats(args, runs=5):
    out = tempfile.mktemp(suffix=".glb")
    n, runs = runs, []
    for _ in range(n):
        p = subprocess.run([LSYS] + args + ["-o", out, "--stats"], capture_output=True, text=True, check=True)
        runs.append(json.loads(p.stdout.strip().splitlines()[-1]))
    os.remove(out)
    ms = statistics.median(sum(r["timings_ms"].values()) for r in runs)
    return runs[0], ms

print("| Toukung | levels | components | triangles (ours) | triangles (ours, --detail 0) | polygons (paper) | ms (ours, median) | paper |")
print("|---|---|---|---|---|---|---|---|")
for kind in ["middle", "side"]:
    for n in [3, 5, 7, 18]:
        r, ms = stats(["build", f"std:toukung_{kind}", "-D", f"NTL={n}"])
        comps = sum(r["instances"].values())
        preview, _ = stats(["build", f"std:toukung_{kind}", "-D", f"NTL={n}", "--detail", "0"], runs=1)
        print(f"| {kind} | {n} | {comps} | {r['triangles']:,} | {preview['triangles']:,} | {PAPER_TOUKUNG[(kind, n)]:.3g} | {ms:.1f} | about 1 s |")
print()
print("| Pailou (example) | type | NP-NE-NR (ours) | polygons: paper | triangles: ours | ours / paper | file KB: paper | GLB KB: ours | time: paper (s, modelling by hand) | ms: ours (median) |")
print("|---|---|---|---|---|---|---|---|---|---|")
os.makedirs("docs/images/pailou", exist_ok=True)
for g in sorted(glob.glob("examples/pailou/*.toml")):
    r, ms = stats(["pailou", g])
    i = r["instances"]
    name = os.path.basename(g)[:-5]
    fig = name.split("_")[0]
    kind = "pillar" if 'type = "pillar"' in open(g).read() else "ridge"
    poly, secs, kb = PAPER_PAILOU[fig]
    roofs = i.get("RE", 0) + i.get("RC", 0)
    ne = i.get("MPB", 0) - 1
    print(f"| [{name}](images/pailou/{name}.png) | {kind} | {i.get('MPB', 0)}-{ne}-{roofs} | {poly:.3g} | {r['triangles']:,} | {r['triangles'] / poly:.2f} | {kb:,.0f} | {r['output']['bytes'] // 1024:,} | {secs} | {ms:.1f} |")
    for view, suffix in [("front", ""), ("iso", "_iso")]:
        subprocess.run([LSYS, "pailou", g, "-o", f"docs/images/pailou/{name}{suffix}.png", "--view", view,
                        "--size", "480x360"], check=True, capture_output=True)
