"""Batch items: `pailou.generate` writes what `lsys batch` writes, and the
Dask (and Ray, when installed) examples build a manifest into the same
files, with every item in the index once and the broken one reported."""

import json
import subprocess
import sys

import pytest

import pailou

TREE = "#define N 3\nderivation length: N\nAxiom: A(1)\nA(s) : s < N --> F(1) [+A(s+1)] [-A(s+1)]\n"
BUSH = "derivation length: 4\nangle: 22.5\nAxiom: F\nF --> F[+F]F[-F]F : 0.5\nF --> F[&F]F : 0.5\n"


@pytest.fixture()
def manifest(tmp_path, root):
    (tmp_path / "tree.lsys").write_text(TREE)
    (tmp_path / "bush.lsys").write_text(BUSH)
    (tmp_path / "broken.lsys").write_text("Axiom: A\nA --> B(\n")
    items = [{"id": f"tree-{n}", "grammar": "tree.lsys", "defines": {"N": n}} for n in range(1, 5)]
    items += [{"id": f"bush-{s}", "grammar": "bush.lsys", "seed": s} for s in range(1, 5)]
    items += [
        {"id": "toukung-3", "grammar": "std:toukung_middle", "defines": {"NTL": 3}},
        {"id": "gate", "grammar": str(root / "examples" / "pailou" / "fig18-4_2-1-1.toml")},
        {"id": "tree-obj", "grammar": "tree.lsys", "steps": 2, "format": "obj"},
        {"id": "broken", "grammar": "broken.lsys"},
    ]
    path = tmp_path / "manifest.jsonl"
    path.write_text("".join(json.dumps(i) + "\n" for i in items))
    return path, items


def batch(lsys_bin, manifest, out):
    return subprocess.run(
        [lsys_bin, "batch", str(manifest), "--out", str(out)], capture_output=True, text=True
    )


def index(out):
    return {e["id"]: e for e in map(json.loads, (out / "index.jsonl").read_text().splitlines())}


def same_entries(a, b):
    drop = lambda e: {k: v for k, v in e.items() if k != "ms"}  # noqa: E731
    assert a.keys() == b.keys()
    for k in a:
        assert drop(a[k]) == drop(b[k]), k


def test_generate_writes_what_lsys_batch_writes(tmp_path, manifest, lsys_bin):
    path, items = manifest
    ran = batch(lsys_bin, path, tmp_path / "cli")
    assert ran.returncode == 65, ran.stderr
    cli = index(tmp_path / "cli")
    py = {}
    for item in items:
        e = pailou.generate(item, out_dir=tmp_path / "py", base_dir=path.parent)
        py[e["id"]] = e
    same_entries(cli, py)
    for item_id, e in cli.items():
        if e["status"] == "ok":
            assert (tmp_path / "cli" / e["output"]).read_bytes() == (tmp_path / "py" / e["output"]).read_bytes()
    broken = py["broken"]
    assert broken["status"] == "error"
    d = broken["diagnostics"][0]
    assert (d["code"], d["line"], d["column"]) == ("lsys::parse::syntax", 2, 8)
    with pytest.raises(ValueError, match="grammar"):
        pailou.generate({"id": "x", "gramar": "std:toukung_middle"}, out_dir=tmp_path / "py")


def run_example(root, name, path, out, *extra):
    return subprocess.run(
        [sys.executable, str(root / "examples" / "python" / name), str(path), "--out", str(out), *extra],
        capture_output=True, text=True, timeout=600,
    )


def check_against_batch(tmp_path, path, items, out, lsys_bin):
    batch(lsys_bin, path, tmp_path / "cli")
    cli = index(tmp_path / "cli")
    got = index(out)
    assert len((out / "index.jsonl").read_text().splitlines()) == len(items)
    same_entries(cli, got)
    for e in cli.values():
        if e["status"] == "ok":
            assert (out / e["output"]).read_bytes() == (tmp_path / "cli" / e["output"]).read_bytes()


def test_the_dask_example_builds_the_files_lsys_batch_builds(tmp_path, manifest, root, lsys_bin):
    pytest.importorskip("dask.distributed")
    path, items = manifest
    ran = run_example(root, "dask_pipeline.py", path, tmp_path / "dask", "--workers", "2")
    assert ran.returncode == 1, ran.stderr  # the broken item
    assert f"{len(items)} items, 1 failed" in ran.stdout
    check_against_batch(tmp_path, path, items, tmp_path / "dask", lsys_bin)


def test_the_ray_example_builds_the_files_lsys_batch_builds(tmp_path, manifest, root, lsys_bin):
    pytest.importorskip("ray")
    path, items = manifest
    ran = run_example(root, "ray_pipeline.py", path, tmp_path / "ray", "--workers", "2", "--batch-size", "4")
    assert ran.returncode == 1, ran.stderr
    assert f"{len(items)} items, 1 failed" in ran.stdout
    check_against_batch(tmp_path, path, items, tmp_path / "ray", lsys_bin)


def test_the_recipe_writes_a_thousand_valid_items(tmp_path, root, lsys_bin):
    out = tmp_path / "m.jsonl"
    subprocess.run([sys.executable, str(root / "examples" / "python" / "dataset_recipe.py"), "--out", str(out)], check=True)
    lines = out.read_text().splitlines()
    assert len(lines) == 1000 and len({json.loads(l)["id"] for l in lines}) == 1000
    # Every item reads as a batch item (a manifest mistake would stop the
    # run before building anything); build a shard of 1 in 100.
    ran = subprocess.run(
        [lsys_bin, "batch", str(out), "--out", str(tmp_path / "o"), "--shard", "7/100"],
        capture_output=True, text=True,
    )
    assert ran.returncode == 0, ran.stderr
    assert len(index(tmp_path / "o")) == 10
