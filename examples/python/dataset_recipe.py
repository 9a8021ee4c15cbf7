"""A 1,000-variant data set recipe: writes an `lsys batch` manifest.

The variants are the paper's 15 Pailous (examples/pailou/*.toml) at three
Toukung sizes (NTL 3, 4, 5), both standard Toukungs at every level the
library builds (middle 1-5, side 1-18), and stochastic plants (ABOP Fig.
1.27) with different seeds and step counts, up to `--count` items. Grammar
paths are written relative to the manifest, so the manifest and the
repository can move together (to shared storage for a cluster).

    python examples/python/dataset_recipe.py --out target/dataset/manifest.jsonl
    lsys batch target/dataset/manifest.jsonl --out target/dataset/out --jobs 2
"""

import argparse
import json
import os
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2]


def variants(count):
    items = []
    for graph in sorted((ROOT / "examples" / "pailou").glob("*.toml")):
        for ntl in (3, 4, 5):
            items.append({"id": f"pailou-{graph.stem}-ntl{ntl}", "grammar": graph, "defines": {"NTL": ntl}})
    for ntl in range(1, 6):
        items.append({"id": f"toukung-middle-{ntl}", "grammar": "std:toukung_middle", "defines": {"NTL": ntl}})
    for ntl in range(1, 19):
        items.append({"id": f"toukung-side-{ntl}", "grammar": "std:toukung_side", "defines": {"NTL": ntl}})
    plant = ROOT / "examples" / "abop" / "stochastic_1_27.lsys"
    seed = 1
    while len(items) < count:
        steps = 4 + seed % 3
        items.append({"id": f"plant-{seed:04d}-n{steps}", "grammar": plant, "seed": seed, "steps": steps})
        seed += 1
    return items[:count]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="manifest.jsonl", help="the manifest to write")
    ap.add_argument("--count", type=int, default=1000)
    ap.add_argument("--format", default="glb", choices=["glb", "obj", "png"])
    args = ap.parse_args()
    out = pathlib.Path(args.out).resolve()
    out.parent.mkdir(parents=True, exist_ok=True)
    with open(out, "w") as f:
        for item in variants(args.count):
            g = item["grammar"]
            if isinstance(g, pathlib.Path):
                item["grammar"] = os.path.relpath(g, out.parent)
            item["format"] = args.format
            f.write(json.dumps(item) + "\n")
    print(f"{out}: {args.count} items")


if __name__ == "__main__":
    main()
