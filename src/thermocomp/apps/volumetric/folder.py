"""What tells a volumetric folder and what its parameter series depend on, without the adapter.

Every stage asks whether ``data.path`` is volumetric; only a volumetric one needs the adapter
(:mod:`.source`: the calibration, SciPy's linear algebra), imported where such a folder is opened.
"""

from __future__ import annotations

from pathlib import Path

from .artefact import SETUP_FILE

# the calibrate.* settings a parameter series depends on (calibrate.format: how it is written)
SETTINGS = ("outlier_z", "column_share", "require_seen", "prior")


def is_volumetric(root: str | Path) -> bool:
    """``root`` is a volumetric dataset (``volumetric.json`` in it)."""
    return (Path(root) / SETUP_FILE).is_file()
