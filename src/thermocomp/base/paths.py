"""The project root, from which every relative path in the config is resolved.

Hydra runs with ``version_base="1.3"`` and no working-directory change, but a
user may still call ``thermocomp`` from anywhere: paths are built from the
project root (``THERMOCOMP_ROOT``, else the checkout this package lives in,
else the current directory), never from the current directory by accident.
No Hydra here (``io`` resolves with it too); the CLI registers the config's
``${root:...}`` resolver on :func:`resolve`.
"""

from __future__ import annotations

import os
from pathlib import Path

import thermocomp


def project_root() -> Path:
    env = os.environ.get("THERMOCOMP_ROOT")
    if env:
        return Path(env).resolve()
    checkout = Path(thermocomp.__file__).resolve().parents[2]   # src/thermocomp/__init__.py
    if (checkout / "conf" / "config.yaml").is_file():
        return checkout
    return Path.cwd()


def resolve(path: str | os.PathLike) -> Path:
    """``path`` if absolute, else relative to the project root."""
    p = Path(os.path.expanduser(str(path)))
    return p if p.is_absolute() else project_root() / p


def elsewhere_hint(path: str | os.PathLike | None) -> str:
    """What to say of a missing ``path`` under the project root that exists relative to the
    current directory: a user who typed ``data.path=data/lathe`` in another folder meant
    that one (relative paths are the root's), and the bare "not found" would not tell why."""
    if path is None:
        return ""
    root, here, p = project_root(), Path.cwd().resolve(), Path(path)
    if here == root or p.exists() or root not in p.parents:
        return ""
    rel = p.relative_to(root)
    meant = next((part for part in (rel, *list(rel.parents)[:-1])
                  if (here / part).exists() and not (root / part).exists()), None)
    if meant is None:
        return ""
    return (f" (a relative path is read from the project root {root}, not the current folder; "
            f"{here / meant} exists: give it as an absolute path)")


def conf_dir() -> Path:
    return project_root() / "conf"


def overlap(output: Path, source: Path) -> str | None:
    """How ``output`` overlaps ``source``: ``is``, ``lies inside`` or ``holds``; None if apart."""
    if output == source:
        return "is"
    if source in output.parents:
        return "lies inside"
    if output in source.parents:
        return "holds"
    return None
