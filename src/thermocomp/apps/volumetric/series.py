"""Reading a volumetric dataset: its set-up (``volumetric.json``) and its distance columns.

A raw volumetric dataset is a dataset of the contract whose targets are the artefact's
distance deviations ``E_<pose>_B<i>_B<j>`` (µm), one row per measurement cycle, with the
temperatures of that cycle; ``volumetric.json`` in the folder says what was measured
(:class:`~thermocomp.apps.volumetric.artefact.Setup`).  Calibrating it gives a dataset of the
same campaigns whose targets are the identified error parameters (``E_XX1`` ...), the
input of the thermal model per parameter (:func:`thermocomp.shell.stages.calibrate.calibrate_folder`).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd

from ...core.io.contract import ContractError, Dataset
from .artefact import COLUMN, SETUP_FILE, Setup, column
from .identify import ArtefactCalibration


def load_setup(folder) -> Setup | None:
    """The set-up of a volumetric dataset folder, or None when it is not one."""
    path = Path(folder) / SETUP_FILE
    if not path.is_file():
        return None
    try:
        return Setup.from_dict(json.loads(path.read_text()))
    except (ValueError, KeyError, TypeError) as err:
        raise ContractError(f"not a valid set-up: {err}", file=path) from err


def check_columns(ds: Dataset, setup: Setup) -> None:
    """Every distance the set-up declares is a column of every campaign; no stray distance columns.

    Raises ContractError naming the campaign file, the pose and the balls.
    """
    declared = setup.columns()
    known = set(declared)
    poses = {p.name for p in setup.poses}
    for cid, df in ds.campaigns.items():
        file = ds.file_path(cid)
        have = set(df.columns)
        for c in df.columns:        # a stray column first: it often explains a "missing" one
            m = COLUMN.match(c)
            if m and c not in known:
                raise ContractError(f"distance column of an unknown measurement: "
                                    f"{_stray(m, poses, setup.array.n_balls)}", file=file, column=c)
            if not m and c.startswith("E_"):   # was dropped unsaid (a typo, an offset column)
                raise ContractError("an E_ column of a volumetric dataset is a distance "
                                    "deviation named E_<pose>_B<i>_B<j>", file=file, column=c)
        for pose in setup.poses:
            cols = [c for c in declared if c.startswith(f"E_{pose.name}_B")]
            missing = [c for c in cols if c not in have]
            if len(missing) == len(cols):
                raise ContractError(f"pose {pose.name} (declared in {SETUP_FILE}) has no distance "
                                    f"column (E_{pose.name}_B<i>_B<j>): a pose not measured in "
                                    f"this campaign keeps its columns with empty cells; one never "
                                    f"measured is left out of {SETUP_FILE}'s poses", file=file)
            if missing:
                m = COLUMN.match(missing[0])
                raise ContractError(f"pose {pose.name}: the distance of balls {int(m['i'])} and "
                                    f"{int(m['j'])} is missing ({len(missing)} of {len(cols)} "
                                    f"distances of this pose)", file=file, column=missing[0])


def _stray(m, poses: set, n_balls: int) -> str:
    """Why a distance column names no declared measurement."""
    i, j = int(m["i"]), int(m["j"])
    if m["pose"] not in poses:
        return f"pose {m['pose']} not declared in {SETUP_FILE}"
    bad = [k for k in (i, j) if not 1 <= k <= n_balls]
    if bad:
        return f"ball {bad[0]}: the balls are numbered 1 to {n_balls}"
    if i == j:
        return f"ball {i} twice: a distance needs two balls"
    if i > j:
        return f"balls {i} and {j}: write the lower ball first ({column(m['pose'], min(i, j), max(i, j))})"
    return f"balls {i} and {j}: ball numbers have 2 digits ({column(m['pose'], i, j)})"


def distance_matrix(df: pd.DataFrame, cal: ArtefactCalibration) -> np.ndarray:
    """A campaign's distance deviations in the calibration's column order."""
    where = df.columns.get_indexer(cal.design_.columns)
    if (where < 0).any():
        return df[cal.design_.columns].to_numpy(float)     # the KeyError that names them
    try:   # the reader keeps a block per column: one array of all, not a take over 1400 blocks
        return df.to_numpy(float)[:, where]
    except (TypeError, ValueError):                        # a column that is no number
        return df[cal.design_.columns].to_numpy(float)
