"""Builds an `lsys batch` manifest with Ray Data and `pailou.generate`.

The manifest's items become a Ray dataset; each is built by
`pailou.generate` in a Ray worker, which writes `OUT/<id>.<format>` (the
bytes `lsys batch` writes) and returns the index entry. The entries are
written to `OUT/index.jsonl` in manifest order.

    python examples/python/ray_pipeline.py MANIFEST.jsonl --out DIR [--workers 2]
    RAY_ADDRESS=ray://head:10001 python examples/python/ray_pipeline.py MANIFEST.jsonl --out DIR
"""

import argparse
import json
import pathlib
import time

import pailou


def main():
    import ray

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("manifest")
    ap.add_argument("--out", required=True)
    ap.add_argument("--workers", type=int, default=2, help="CPUs of a local Ray (ignored with RAY_ADDRESS)")
    ap.add_argument("--batch-size", type=int, default=25, help="items per Ray task")
    args = ap.parse_args()
    with open(args.manifest) as f:
        specs = [json.loads(line) for line in f if line.strip()]
    base = str(pathlib.Path(args.manifest).resolve().parent)
    out = str(pathlib.Path(args.out).resolve())
    ray.init(num_cpus=args.workers, include_dashboard=False, ignore_reinit_error=True)
    # One item per row; the spec travels as JSON (its `defines` vary in keys).
    rows = [{"order": i, "spec": json.dumps(s)} for i, s in enumerate(specs)]

    def build(batch):
        # Items in batches: most items build in milliseconds, and a Ray task
        # per item would cost more than the item.
        entries = [
            json.dumps(pailou.generate(json.loads(s), out_dir=out, base_dir=base)) for s in batch["spec"]
        ]
        return {"order": batch["order"], "entry": entries}

    t0 = time.perf_counter()
    blocks = max(2 * args.workers, len(rows) // args.batch_size)
    ds = ray.data.from_items(rows, override_num_blocks=blocks).map_batches(
        build, batch_size=args.batch_size, batch_format="numpy", num_cpus=1
    )
    results = sorted(ds.take_all(), key=lambda r: int(r["order"]))
    took = time.perf_counter() - t0
    entries = [json.loads(str(r["entry"])) for r in results]
    with open(pathlib.Path(out) / "index.jsonl", "w") as f:
        for e in entries:
            f.write(json.dumps(e) + "\n")
    failed = sum(e["status"] != "ok" for e in entries)
    print(f"{len(entries)} items, {failed} failed, {took:.2f} s, {len(entries) / took:.1f} items/s")
    ray.shutdown()
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
