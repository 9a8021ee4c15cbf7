"""Scene: arrays handed over without copying, placements, GLB bytes equal
to `lsys build -o`, files by extension, stats, and Pailous."""

import pathlib
import subprocess

import numpy as np
import pytest

import pailou

PLANT = """\
derivation length: 3
Axiom: A
A --> F [+A] [-A] F A
angle: 25
"""


@pytest.fixture(scope="module")
def toukung():
    return pailou.Grammar.from_path("std:toukung_middle").build()


def test_arrays_have_their_shapes_and_types():
    s = pailou.Grammar.from_str("plant.lsys", PLANT).build()
    n = s.positions.shape[0]
    assert s.positions.shape == (n, 3) and s.positions.dtype == np.float32
    assert s.normals.shape == (n, 3) and s.normals.dtype == np.float32
    assert s.colors.shape == (n, 3) and s.colors.dtype == np.float32
    assert s.indices.dtype == np.uint32 and s.indices.shape[1] == 3
    assert s.indices.shape[0] == s.stats["triangles"] == s.triangle_count
    assert int(s.indices.max()) < n
    assert np.allclose(np.linalg.norm(s.normals, axis=1), 1.0, atol=1e-4)
    lo, hi = s.bounds
    assert np.allclose(s.positions.min(axis=0), lo) and np.allclose(s.positions.max(axis=0), hi)


def test_arrays_are_the_rust_buffers_not_copies(toukung):
    for a in (toukung.positions, toukung.normals, toukung.indices, toukung.colors):
        # An array NumPy allocated has no base; one that took Rust's
        # buffer keeps the Rust owner as its base.
        assert a.base is not None and not isinstance(a.base, np.ndarray)
        assert type(a.base).__name__ == "PySliceContainer"
        assert not a.flags.writeable and a.flags.c_contiguous
    # The same buffer every time it is asked for.
    assert toukung.positions.ctypes.data == toukung.positions.ctypes.data


def test_instances_are_placements_with_names(toukung):
    counts = toukung.stats["instances"]
    assert len(toukung.instances) == sum(counts.values())
    names = [name for name, _ in toukung.instances]
    assert {n: names.count(n) for n in set(names)} == counts
    for _, m in toukung.instances:
        assert m.shape == (4, 4) and m.dtype == np.float32
        assert np.allclose(m[3], [0, 0, 0, 1])


def test_glb_bytes_are_lsys_build_o(tmp_path, lsys_bin):
    g = pailou.Grammar.from_str("plant.lsys", PLANT)
    path = tmp_path / "plant.lsys"
    path.write_text(PLANT)
    out = tmp_path / "cli.glb"
    subprocess.run([lsys_bin, "build", str(path), "-n", "2", "-o", str(out)], check=True, capture_output=True)
    assert g.build(2).to_glb() == out.read_bytes()
    t = pailou.Grammar.from_path("std:toukung_middle", defines={"NTL": 3})
    out2 = tmp_path / "tm.glb"
    subprocess.run([lsys_bin, "build", "std:toukung_middle", "-D", "NTL=3", "-o", str(out2)], check=True, capture_output=True)
    assert t.build().to_glb() == out2.read_bytes()


def test_write_picks_the_format_from_the_extension(tmp_path, toukung):
    assert toukung.write(tmp_path / "t.glb") == len(toukung.to_glb())
    assert (tmp_path / "t.glb").read_bytes() == toukung.to_glb()
    toukung.write(str(tmp_path / "t.obj"))
    assert (tmp_path / "t.obj").read_text().startswith("#") or (tmp_path / "t.obj").read_text().startswith("mtllib")
    assert (tmp_path / "t.mtl").exists()
    toukung.write(tmp_path / "t.png")
    assert (tmp_path / "t.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(pailou.LsysError) as e:
        toukung.write(tmp_path / "t.xyz")
    assert e.value.diagnostics[0]["code"] == "lsys::export::format"
    assert not (tmp_path / "t.xyz").exists()


def test_stats_are_the_stats_flag(tmp_path, lsys_bin):
    g = pailou.Grammar.from_str("plant.lsys", PLANT)
    path = tmp_path / "plant.lsys"
    path.write_text(PLANT)
    import json

    cli = subprocess.run(
        [lsys_bin, "build", str(path), "-o", str(tmp_path / "p.glb"), "--stats"],
        check=True, capture_output=True, text=True,
    )
    line = [l for l in cli.stdout.splitlines() + cli.stderr.splitlines() if l.startswith("{")][0]
    expected = json.loads(line)
    got = g.build().stats
    for key in ("modules", "vertices", "triangles", "bounds", "instances"):
        assert got[key] == expected[key], key


def test_pailou_from_a_style_and_a_graph(root, tmp_path, lsys_bin):
    ridge = pailou.pailou(style="4-3-7", type="ridge")
    pillar = pailou.pailou(style="4-3-7", type="pillar")
    assert ridge.triangle_count > 0 and pillar.triangle_count > 0
    assert ridge.triangle_count != pillar.triangle_count
    out = tmp_path / "p.glb"
    subprocess.run([lsys_bin, "pailou", "--style", "4-3-7", "--type", "ridge", "-o", str(out)], check=True, capture_output=True)
    assert ridge.to_glb() == out.read_bytes()
    graphs = sorted((root / "examples").rglob("*.toml"))
    graph = next(g for g in graphs if "[components]" in g.read_text())
    assert pailou.pailou(graph=graph).triangle_count > 0
    with pytest.raises(ValueError):
        pailou.pailou(style="4-3-7", type="roof")
    with pytest.raises(ValueError):
        pailou.pailou()
    with pytest.raises(pailou.LsysError):
        pailou.pailou(style="9-9-9")


def test_to_trimesh_and_to_pyvista_import_only_when_called(toukung):
    import sys

    assert "trimesh" not in sys.modules and "pyvista" not in sys.modules
    try:
        import trimesh  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError):
            toukung.to_trimesh()
    else:
        m = toukung.to_trimesh()
        assert len(m.faces) == toukung.triangle_count
        assert (m.vertices == toukung.positions).all()
    try:
        import pyvista  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError):
            toukung.to_pyvista()
    else:
        p = toukung.to_pyvista()
        assert (p.n_points, p.n_cells) == (len(toukung.positions), toukung.triangle_count)
        assert p.is_all_triangles


def test_repr_html_is_a_self_contained_viewer(toukung):
    html = toukung._repr_html_()
    assert "<canvas" in html and "pailouView" in html
    assert "http://" not in html and "https://" not in html
