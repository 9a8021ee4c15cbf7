"""pailou: parametric L-systems for procedural architecture and plants.

Compile a grammar, derive its strings, build its 3D model (NumPy arrays,
GLB, OBJ, PNG), build Pailou gateways, and run batch items on Ray, Dask
or Slurm. See docs/python.md in the repository.

    >>> import pailou
    >>> g = pailou.Grammar.from_str("koch.lsys", "Axiom: F\\nF --> F+F-F-F+F\\n")
    >>> str(g.derive(1))
    'F + F - F - F + F'
"""

from ._native import (
    Derived,
    Grammar,
    LsysError,
    Scene,
    __version__,
    generate,
    pailou,
)

__all__ = [
    "Derived",
    "Grammar",
    "LsysError",
    "Scene",
    "generate",
    "pailou",
    "__version__",
]
