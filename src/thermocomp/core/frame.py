"""Campaign frames -> model matrices and side inputs, in the contract's reference frame.

With ``reference="first_sample"`` every ``T_`` and ``E_`` column is taken
relative to the campaign's first valid sample (ΔT, ΔE); ``S_`` columns keep
their values.  Models, metrics and diagnosis all work in this frame.

:func:`stack` builds the matrices of a batch of campaigns and their per-row
``context`` (:mod:`thermocomp.core.context`); :func:`context_record` is the one rule
for a context row, used by :func:`stack` on whole campaigns and by the
streaming compensator on one sample.  Written on NumPy arrays: the evaluation
stacks the same campaigns hundreds of times (mutual prediction, ATI baselines).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..base.errors import ContractError, listed
from .choices import REFERENCES
from .context import AMBIENT_C0, CAMPAIGN, TIME
from .io.contract import is_ambient, manifest_ambient, match_columns
from .io.instants import start_instants
from .io.own_headers import header_pattern
from .io.roles import split_unit

REFERENCED_PREFIXES = ("T_", "E_")   # taken relative to the first sample; S_ keep their values
RAW_PREFIXES = ("S_", "T_")          # ride along raw in the context


def check_reference(reference: str) -> None:
    if reference not in REFERENCES:
        raise ContractError(f"data.reference must be one of {REFERENCES}, got {reference!r}")


def first_valid(A: np.ndarray) -> np.ndarray:
    """First non-NaN value of each column of ``A`` (NaN for an all-NaN column)."""
    A = np.asarray(A, dtype=float)
    if A.shape[0] == 0:
        return np.full(A.shape[1], np.nan)
    valid = ~np.isnan(A)
    first = A[valid.argmax(axis=0), np.arange(A.shape[1])]
    first[~valid.any(axis=0)] = np.nan
    return first


def referenced(df: pd.DataFrame, reference: str = "first_sample") -> pd.DataFrame:
    """Copy of ``df`` with ``T_``/``E_`` columns relative to their first valid sample."""
    check_reference(reference)
    if reference == "none":
        return df
    out = df.copy()
    cols = [c for c in df.columns if c.startswith(REFERENCED_PREFIXES)]
    out[cols] = df[cols].to_numpy(float) - first_valid(df[cols].to_numpy(float))
    return out


def ambient_c0(first_values) -> float:
    """Initial ambient (°C) from the first valid absolute values of the ambient sensors."""
    v = np.asarray(first_values, dtype=float)
    return float(v.mean()) if v.size else float("nan")


def initial_ambient(df: pd.DataFrame) -> float:
    """First valid absolute ambient temperature (°C) of a campaign: its ``T_amb*`` sensors, else
    the manifest's ``ambient_c``; NaN if neither."""
    amb = [c for c in df.columns if is_ambient(c)]
    return ambient_c0(first_valid(df[amb].to_numpy(float))) if amb else manifest_ambient(df)


def context_record(campaign, time, ambient: float, raw: Mapping) -> dict:
    """One context entry (a sample, or arrays for a whole campaign): the rule of :mod:`.context`."""
    return {CAMPAIGN: campaign, TIME: time, AMBIENT_C0: ambient, **raw}


@dataclass
class Matrices:
    """Stacked campaigns: inputs ``X``, targets ``Y``, campaign of each row, time, context.

    ``context`` has one row per sample (see :mod:`thermocomp.core.context`):
    ``campaign``, ``time`` (s), ``ambient_c0`` (the campaign's first valid
    absolute ambient, °C: its ``T_amb*`` columns, else the manifest's ``ambient_c``, else NaN)
    and every ``S_`` and
    ``T_`` column of the campaigns, raw values (NaN where a campaign lacks it).
    """

    X: pd.DataFrame
    Y: pd.DataFrame
    groups: np.ndarray
    time: np.ndarray
    context: pd.DataFrame | None = None

    def rows_of(self, cid: str) -> np.ndarray:
        return self.groups == cid

    def subset(self, rows) -> "Matrices":
        """The rows ``rows`` (boolean mask), index reset."""
        idx = np.flatnonzero(rows)
        return Matrices(self.X.iloc[idx].reset_index(drop=True), self.Y.iloc[idx].reset_index(drop=True),
                        self.groups[idx], self.time[idx],
                        None if self.context is None else self.context.iloc[idx].reset_index(drop=True))


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
    errors = [c for c in x_cols if c.startswith("E_")]
    if errors:      # data.inputs=[E_X, T_*] for E_Z fitted on another axis's measurement, silently
        raise ContractError(f"data.inputs {inputs} takes a measured error as an input: a machine "
                            "that is compensating does not measure it (inputs are T_ and S_ "
                            "columns)", column=",".join(errors))
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


def check_common_columns(campaigns: Mapping[str, pd.DataFrame], columns,
                         files: Mapping[str, object] | None = None,
                         headers: Mapping[str, str] | None = None,
                         starts: Mapping[str, object] | None = None) -> None:
    """Every campaign holds every column the model reads (``columns``).

    Otherwise a ContractError naming the odd one out: the campaign that lacks a column the
    others have, or, when only a few have it, the first of those (a sensor fitted to once
    would be missing wherever the model runs); where another column of its role is in exactly
    the other campaigns, the first campaign of the later name (a sensor renamed from some run
    on).  ``files`` maps campaign ids to the files named in the error (default: the ids, in the
    message); ``headers`` contract names to the files' own headers where they differ (a lab's
    ``T03``, read as ``T_T03``), named in the fix; ``starts`` each campaign's start (the
    manifest's ``start``, a file's first timestamp): where every campaign has one, a renamed
    sensor's earlier name and its first campaign under the later one are read in time order,
    not in the campaigns' (a folder's file names).
    """
    n, headers = len(campaigns), headers or {}
    for column in columns:
        have = [cid for cid, df in campaigns.items() if column in df.columns]
        if len(have) == n:
            continue
        lack = [cid for cid in campaigns if cid not in have]
        twin = _other_name(campaigns, column, lack)
        if twin is not None:
            raise _renamed(campaigns, column, twin, files, headers, starts)
        if have and len(have) < len(lack):
            odd, what = have[0], f"only {len(have)} of {n} campaigns have it ({listed(have)})"
        else:
            odd, what = lack[0], f"{len(lack)} of {n} campaigns lack it ({listed(lack)})"
        where = {"file": files[odd]} if files and odd in files else {}
        # a lab's header read by role is left out by a pattern over it (data.inputs are globs
        # over contract names: none leaves one sensor out)
        out = (f"(data.roles.ignore=[{header_pattern(headers[column])!r}])" if column in headers
               else "of data.inputs")
        raise ContractError(f"{what}: the model reads every declared column (data.inputs, "
                            "data.targets) in every campaign; give it to all of them or leave "
                            f"it out {out}", column=column, **where)


def _other_name(campaigns: Mapping[str, pd.DataFrame], column: str, lack: list) -> str | None:
    """The one column of ``column``'s role that is in exactly the campaigns ``lack`` (those
    without ``column``), else None: one sensor under two names (``T3``, then ``T03``)."""
    prefix, lack = column.split("_", 1)[0] + "_", set(lack)
    names = {c for cid in lack for c in campaigns[cid].columns
             if c.startswith(prefix) and c != column}
    twins = [c for c in sorted(names)
             if {cid for cid, df in campaigns.items() if c in df.columns} == lack]
    return twins[0] if len(twins) == 1 else None


_PLAIN_KEY = re.compile(r"[A-Za-z0-9_.\- ]+")


def renamed_sensors(campaigns: Mapping[str, pd.DataFrame], columns, headers=None,
                    starts=None) -> dict[str, tuple[str, str]]:
    """``{data.columns key: (earlier contract name, later one)}`` of each of ``columns`` read
    under one name in some campaigns and another in exactly the others (:func:`_other_name`):
    the entry that reads the later header as the earlier name (initone65: ``init`` proposes it
    where ``run`` refused it, naming the entry)."""
    out: dict = {}
    n = len(campaigns)
    for column in columns:
        have = [cid for cid, df in campaigns.items() if column in df.columns]
        if not have or len(have) == n:
            continue
        twin = _other_name(campaigns, column, [cid for cid in campaigns if cid not in have])
        if twin is None:
            continue
        old, new, _, _, key = _rename(campaigns, column, twin, headers or {}, starts)
        if new not in {v[1] for v in out.values()}:
            out[key] = (old, new)
    return out


def _rename(campaigns, column: str, twin: str, headers, starts=None):
    """``(earlier name, later name, the later's campaigns in order, its header, its
    data.columns key)`` of one sensor under two names: later in time where every campaign has a
    start (``starts``), else in the campaigns' order."""
    order = list(campaigns)
    began = start_instants(pd.Series({c: (starts or {}).get(c) for c in order}, dtype=object))
    if began.notna().all():     # (a lab's files named otherwise than in time: T03 came first)
        order = list(began.sort_values(kind="stable").index)

    def where(name):
        return [cid for cid in order if name in campaigns[cid].columns]

    old, new = sorted((column, twin), key=lambda name: order.index(where(name)[0]))
    raw = headers.get(new, new)
    # the header without its unit is a key data.columns reads (io.roles.by_header), and the
    # unit is converted as a role's is (stranger65: 'dX1 [mm]' was told to be renamed in the
    # files, data.columns read it unconverted; 'T Wasser [°C]' was a key no command line reads)
    base = split_unit(raw)[0]
    key = base if base and _PLAIN_KEY.fullmatch(base) else raw
    return old, new, (order, where), raw, key


def _renamed(campaigns, column: str, twin: str, files, headers, starts=None) -> ContractError:
    """The refusal of ``column`` and ``twin``, each in the campaigns the other is not in, with
    the ``data.columns`` entry that reads the later name as the earlier one (:func:`_rename`)."""
    old, new, (order, where), raw, key = _rename(campaigns, column, twin, headers, starts)
    first = where(new)[0]
    said = "" if raw == new else f" (its header in the file: {raw!r})"
    if _PLAIN_KEY.fullmatch(key):
        fix = f"data.columns={{{key}: {old}}}"
    else:   # (a header beyond ASCII is no dict key on the command line: Hydra)
        fix = f"columns: {{{key!r}: {old}}} in the data config"
    return ContractError(
        f"{old!r} is in {len(where(old))} of {len(order)} campaigns ({listed(where(old))}), "
        f"{new!r}{said} in the other {len(where(new))}, from {first} on: one sensor renamed? "
        f"{fix} reads it under one name (thermocomp init writes it)", column=new,
        **({"file": files[first]} if files and first in files else {}))


def _framed(A: np.ndarray, cols, reference: str) -> np.ndarray:
    """Columns of one campaign in the reference frame."""
    if reference == "none" or A.shape[1] == 0:
        return A
    shift = np.where([c.startswith(REFERENCED_PREFIXES) for c in cols], first_valid(A), 0.0)
    return A - shift


def stack(campaigns: Mapping[str, pd.DataFrame], x_cols, y_cols,
          reference: str = "first_sample") -> Matrices:
    """Stack campaigns (in the reference frame) into model matrices and their context."""
    check_reference(reference)
    x_cols, y_cols = list(x_cols), list(y_cols)
    raw_cols = list(dict.fromkeys(c for df in campaigns.values() for c in df.columns
                                  if c.startswith(RAW_PREFIXES)))
    xs, ys, groups, times, amb0, raws = [], [], [], [], [], []
    for cid, df in campaigns.items():
        pos = {c: j for j, c in enumerate(df.columns)}
        if any(c not in pos for c in x_cols + y_cols):
            check_common_columns(campaigns, x_cols + y_cols)
        A = df.to_numpy(dtype=float)      # one conversion; columns picked by position below
        n = len(df)
        xs.append(_framed(A[:, [pos[c] for c in x_cols]], x_cols, reference))
        ys.append(_framed(A[:, [pos[c] for c in y_cols]], y_cols, reference))
        groups.append(np.full(n, cid, dtype=object))
        times.append(A[:, pos[TIME]])
        amb = [pos[c] for c in df.columns if is_ambient(c)]
        amb0.append(np.full(n, ambient_c0(first_valid(A[:, amb])) if amb else manifest_ambient(df)))
        raw = np.full((n, len(raw_cols)), np.nan)
        have = [j for j, c in enumerate(raw_cols) if c in pos]
        raw[:, have] = A[:, [pos[raw_cols[j]] for j in have]]
        raws.append(raw)
    groups, times = np.concatenate(groups), np.concatenate(times)
    raw = np.concatenate(raws) if raws else np.empty((0, len(raw_cols)))
    context = pd.DataFrame(context_record(groups, times, np.concatenate(amb0),
                                          {c: raw[:, j] for j, c in enumerate(raw_cols)}))
    X = pd.DataFrame(np.concatenate(xs) if xs else np.empty((0, len(x_cols))), columns=x_cols)
    Y = pd.DataFrame(np.concatenate(ys) if ys else np.empty((0, len(y_cols))), columns=y_cols)
    return Matrices(X, Y, groups, times, context)
