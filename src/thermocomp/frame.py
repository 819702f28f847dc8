"""Campaign frames -> model matrices, in the contract's reference frame.

With ``reference="first_sample"`` every ``T_`` and ``E_`` column is taken
relative to the campaign's first valid sample (ΔT, ΔE); ``S_`` columns keep
their values.  Models, metrics and diagnosis all work in this frame.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .io.contract import TIME, ContractError, match_columns

REFERENCES = ("first_sample", "none")


def referenced(df: pd.DataFrame, reference: str = "first_sample") -> pd.DataFrame:
    """Copy of ``df`` with ``T_``/``E_`` columns relative to their first valid sample."""
    if reference not in REFERENCES:
        raise ContractError(f"data.reference must be one of {REFERENCES}, got {reference!r}")
    if reference == "none":
        return df
    out = df.copy()
    cols = [c for c in df.columns if c.startswith(("T_", "E_"))]
    first = df[cols].bfill().iloc[0]
    out[cols] = df[cols] - first
    return out


@dataclass
class Matrices:
    """Stacked campaigns: inputs ``X``, targets ``Y``, campaign of each row, time.

    ``context`` has one row per sample with what a model may know besides its
    inputs: ``campaign``, ``time`` (s) and ``ambient_c0`` (the campaign's first
    valid absolute ambient temperature, °C, NaN without a ``T_amb*`` column) --
    the key of ambient-interval (ATI) models -- and every ``S_`` and ``T_`` column
    of the campaigns, raw values (NaN where a campaign lacks it), for models that
    use a machine state or a sensor outside the declared inputs (the door signal
    of ARX+RF, the effects of :class:`thermocomp.diagnose.AugmentedRegressor`).
    """

    X: pd.DataFrame
    Y: pd.DataFrame
    groups: np.ndarray
    time: np.ndarray
    context: pd.DataFrame | None = None

    def rows_of(self, cid: str) -> np.ndarray:
        return self.groups == cid


def resolve_columns(columns, inputs, targets) -> tuple[list[str], list[str]]:
    """Declared input columns and target columns among ``columns``.

    Raises ContractError when a pattern matches nothing or a target is not an
    ``E_`` column, so a typo in ``data.inputs``/``data.targets`` is a clear
    exit-2 error rather than an empty model.
    """
    inputs = list(inputs) if not isinstance(inputs, str) else [inputs]
    x_cols = match_columns(columns, inputs)
    if not x_cols:
        raise ContractError(f"data.inputs {inputs} matches no column (have {list(columns)})",
                            column=",".join(inputs))
    all_targets = [c for c in columns if c.startswith("E_")]
    if targets is None:
        y_cols = all_targets
    else:
        targets = [targets] if isinstance(targets, str) else list(targets)
        missing = [t for t in targets if t not in all_targets]
        if missing:
            raise ContractError(f"data.targets names no E_ column of the dataset "
                                f"(have {all_targets})", column=",".join(missing))
        y_cols = targets
    overlap = set(x_cols) & set(y_cols)
    if overlap:
        raise ContractError("a column cannot be both input and target", column=",".join(sorted(overlap)))
    return x_cols, y_cols


def initial_ambient(df: pd.DataFrame) -> float:
    """First valid absolute ambient temperature (°C) of a campaign, NaN if none."""
    amb = [c for c in df.columns if c == "T_amb" or c.startswith("T_amb_")]
    if not amb:
        return float("nan")
    first = df[amb].bfill().iloc[0]
    return float(first.mean())


def stack(campaigns: Mapping[str, pd.DataFrame], x_cols, y_cols,
          reference: str = "first_sample") -> Matrices:
    """Stack campaigns (in the reference frame) into model matrices."""
    xs, ys, groups, times, amb0, states = [], [], [], [], [], []
    for cid, df in campaigns.items():
        missing = [c for c in list(x_cols) + list(y_cols) if c not in df.columns]
        if missing:
            raise ContractError("campaign lacks a column the model needs", file=cid,
                                column=",".join(missing))
        ref = referenced(df, reference)
        xs.append(ref[list(x_cols)])
        ys.append(ref[list(y_cols)])
        groups.append(np.full(len(df), cid, dtype=object))
        times.append(df[TIME].to_numpy(float))
        amb0.append(np.full(len(df), initial_ambient(df)))
        # machine states (S_*) and every sensor (T_*, declared or not), raw values, ride along
        # for models that use them (ARX+RF door, the diagnosis' AugmentedRegressor)
        states.append(df[[c for c in df.columns if c.startswith(("S_", "T_"))]].reset_index(drop=True))
    groups, times = np.concatenate(groups), np.concatenate(times)
    context = pd.DataFrame({"campaign": groups, "time": times, "ambient_c0": np.concatenate(amb0)})
    context = pd.concat([context, pd.concat(states, ignore_index=True)], axis=1)
    return Matrices(pd.concat(xs, ignore_index=True), pd.concat(ys, ignore_index=True),
                    groups, times, context)
