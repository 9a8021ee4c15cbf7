"""Builds an `lsys batch` manifest on a Dask cluster with `pailou.generate`.

Each item runs in a worker process, writes `OUT/<id>.<format>` (the bytes
`lsys batch` writes for it) and returns its index entry; the entries are
written to `OUT/index.jsonl` in manifest order. Without `--scheduler` a
LocalCluster of `--workers` processes (one thread each) is started.

    python examples/python/dask_pipeline.py MANIFEST.jsonl --out DIR [--workers 2]
    python examples/python/dask_pipeline.py MANIFEST.jsonl --out DIR --scheduler tcp://host:8786
"""

import argparse
import json
import pathlib
import time

import pailou


def load(manifest):
    with open(manifest) as f:
        return [json.loads(line) for line in f if line.strip()]


def main():
    from dask.distributed import Client, LocalCluster

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("manifest")
    ap.add_argument("--out", required=True)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--scheduler", help="an existing Dask scheduler's address")
    args = ap.parse_args()
    specs = load(args.manifest)
    base = str(pathlib.Path(args.manifest).resolve().parent)
    out = str(pathlib.Path(args.out).resolve())
    if args.scheduler:
        client = Client(args.scheduler)
    else:
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
    t0 = time.perf_counter()
    futures = client.map(pailou.generate, specs, out_dir=out, base_dir=base, pure=False)
    entries = client.gather(futures)
    took = time.perf_counter() - t0
    with open(pathlib.Path(out) / "index.jsonl", "w") as f:
        for e in entries:
            f.write(json.dumps(e) + "\n")
    failed = sum(e["status"] != "ok" for e in entries)
    print(f"{len(entries)} items, {failed} failed, {took:.2f} s, {len(entries) / took:.1f} items/s")
    client.close()
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
