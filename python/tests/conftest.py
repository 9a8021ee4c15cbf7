"""Shared fixtures: the repository's root and the lsys binary (for
comparisons with the command line; set LSYS_BIN, or the tests look in
target/)."""

import os
import pathlib
import shutil

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def lsys_bin():
    for candidate in (
        os.environ.get("LSYS_BIN"),
        ROOT / "target" / "release" / "lsys",
        ROOT / "target" / "debug" / "lsys",
        shutil.which("lsys"),
    ):
        if candidate and pathlib.Path(candidate).is_file():
            return str(candidate)
    pytest.skip("no lsys binary: build it with `cargo build --release` or set LSYS_BIN")
