"""`thermocomp calibrate`: artefact distances of a volumetric dataset -> error parameter series.

Reads ``data.path`` (a volumetric dataset: ``volumetric.json`` + the distance columns
``E_<pose>_B<i>_B<j>``, one row per measurement cycle; a folder without the set-up is
refused), identifies the kinematic model's parameters of every cycle
(:class:`~thermocomp.volumetric.ArtefactCalibration`: GLS, outliers flagged and left out of
their cycle) and writes, staged and atomically:

* the parameter series dataset (``calibrate.dataset``, default ``<out>/parameters``): the same
  campaigns with ``time``, ``T_``/``S_`` columns and one ``E_`` column per identified parameter;
* ``<out>/calibration.json``: per parameter its unit and standard uncertainty, the parameters
  the poses cannot see (with what they are confounded with), the outliers, and the round trip
  against ``<data.path>.truth.json`` when the data were simulated.

Bad artefact data: a pose of the set-up without distances -> exit 2 naming it; a pose set that
cannot see a parameter of a kind in ``calibrate.require_seen`` -> exit 2 naming the parameters
and the poses; a single distance off -> an outlier of its cycle; a distance column flagged in
more than ``calibrate.column_share`` of the cycles (a ball off its certificate, a swapped
label) -> left out of every cycle and named in ``excluded``.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
from omegaconf import DictConfig

from .. import io
from ..errors import ConfigError, ContractError
from ..files import staged_outputs, write_json
from ..log import logger
from ..paths import resolve
from ..sim.scenario import single_threaded_blas
from ..tracking import stage_run
from ..volumetric import SETUP_FILE, ArtefactCalibration, check_columns, equivalent_truth, load_setup
from ..volumetric.artefact import COLUMN
from .common import _check_writable, check_config, data_options, say

KINDS = ("positioning", "straightness", "angular", "cross")
FORMATS = ("parquet", "csv")


def check_calibrate(c: DictConfig) -> None:
    """Refuse a ``calibrate.*`` value the stage cannot use, before any data is read."""
    def number(key, low, high=None):
        v = c.get(key)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) \
                or v <= low or (high is not None and v > high):
            raise ConfigError(f"calibrate.{key} must be a number > {low:g}"
                              f"{f' and <= {high:g}' if high is not None else ''}, got {v!r}")

    number("outlier_z", 0)
    number("column_share", 0, 1)
    if c.get("format") not in FORMATS:
        raise ConfigError(f"calibrate.format={c.get('format')!r} is not one of {list(FORMATS)}")
    bad = [k for k in (c.get("require_seen") or []) if k not in KINDS]
    if bad:
        raise ConfigError(f"calibrate.require_seen: unknown kind(s) {bad}; use {list(KINDS)}")


def _kinds(setup) -> dict:
    return {p.name: p for p in setup.model.parameters}


def _require_seen(cal: ArtefactCalibration, setup, kinds) -> None:
    """A pose set that cannot see a parameter of a required kind is bad input: name both."""
    params = _kinds(setup)
    unseen = [n for n in cal.unidentifiable_ if params[n].kind in kinds]
    if unseen:
        poses = [p.name for p in setup.poses]
        what = ", ".join(f"{n} ({params[n].kind})" for n in unseen)
        raise ContractError(f"the poses {', '.join(poses)} cannot see {what}: add poses (position "
                            "sets S1 axes, S2 volume diagonals, S3 face diagonals) or "
                            "calibrate.require_seen=[]", file=setup_path(cal))


def setup_path(cal) -> str:
    return getattr(cal, "source_", SETUP_FILE)


def _identify(cal, ds, excluded=()):
    """Per campaign ``(P, flagged)``, the columns in ``excluded`` left out of every cycle."""
    cols = cal.design_.columns
    out = {}
    for cid, df in ds.campaigns.items():
        D = df[cols].to_numpy(float)
        if excluded:
            D[:, [cols.index(c) for c in excluded]] = np.nan
        try:
            out[cid] = cal.identify(D)
        except ValueError as exc:
            raise ContractError(f"campaign {cid}: {exc} (too many distances missing or excluded)",
                                file=ds.manifest.loc[cid, "file"]) from None
    return out


def _described(column: str) -> dict:
    m = COLUMN.match(column)
    return {"column": column, "pose": m["pose"], "balls": [int(m["i"]), int(m["j"])]}


def calibrate_folder(root: Path, c: DictConfig, data_cfg: dict):
    """``(parameter dataset, calibration, report)`` of the volumetric dataset in ``root``."""
    setup = load_setup(root)
    if setup is None:
        raise ContractError(f"not a volumetric dataset: no {SETUP_FILE} (write one with "
                            "thermocomp simulate sim=large_mill_volumetric, or see docs/data-format.md)",
                            file=root)
    ds, _ = io.read_dataset(root, data_cfg, missing="keep")     # NaN = a distance not measured
    check_columns(ds, setup)
    cal = ArtefactCalibration(setup, outlier_z=float(c.outlier_z)).fit()
    cal.source_ = str(root / SETUP_FILE)
    _require_seen(cal, setup, list(c.get("require_seen") or []))
    n_cycles = sum(len(df) for df in ds.campaigns.values())
    result = _identify(cal, ds)
    counts: dict[str, int] = {}
    for _, flagged in result.values():
        for f in flagged:
            counts[f["column"]] = counts.get(f["column"], 0) + 1
    excluded = sorted(col for col, k in counts.items() if k > float(c.column_share) * n_cycles)
    if excluded:     # a column off in most cycles is the artefact or its label, not a cycle
        logger.warning("calibrate: %d distance column(s) flagged in more than %.0f %% of the cycles, "
                       "left out of every cycle: %s", len(excluded), 100 * float(c.column_share),
                       ", ".join(excluded[:5]))
        result = _identify(cal, ds, excluded)
    report = _report(cal, setup, ds, result, excluded, counts, n_cycles)
    campaigns = {}
    for cid, df in ds.campaigns.items():
        keep = df[[col for col in df.columns if not col.startswith("E_")]]
        P = pd.DataFrame(result[cid][0], index=df.index, columns=cal.names_)
        campaigns[cid] = pd.concat([keep, P], axis=1)
    params = io.Dataset(ds.manifest.copy(), campaigns, name=ds.name, meta=dict(ds.meta))
    return params, cal, report, ds


def _report(cal, setup, ds, result, excluded, counts, n_cycles) -> dict:
    params = _kinds(setup)
    cols = cal.design_.columns
    outliers, sq, n = [], 0.0, 0
    for cid, (P, flagged) in result.items():
        df = ds.campaigns[cid]
        D = df[cols].to_numpy(float)
        R = D - cal.predict(P)
        skip = np.zeros_like(R, dtype=bool)
        for col in excluded:
            skip[:, cols.index(col)] = True
        for f in flagged:
            skip[f["cycle"], cols.index(f["column"])] = True
            outliers.append({"campaign": cid, "time": float(df["time"].iloc[f["cycle"]]),
                             "row": int(f["cycle"]) + 1, **_described(f["column"]),
                             "residual_um": f["residual_um"], "z": f["z"]})
        ok = np.isfinite(R) & ~skip
        sq += float(np.sum(R[ok] ** 2))
        n += int(ok.sum())
    return {
        "parameters": {name: {"unit": params[name].unit, "uncertainty": float(u),
                              "kind": params[name].kind}
                       for name, u in zip(cal.names_, cal.uncertainty_)},
        "unidentifiable": dict(cal.unidentifiable_),
        "outliers": outliers,
        "excluded": [{**_described(col), "cycles_flagged": counts[col],
                      "share": counts[col] / n_cycles} for col in excluded],
        "n_cycles": n_cycles,
        "n_distances": len(cols),
        "poses": [p.name for p in setup.poses],
        "residual_rms_um": math.sqrt(sq / n) if n else None,
        "campaigns": {cid: len(df) for cid, df in ds.campaigns.items()},
    }


def roundtrip(cal: ArtefactCalibration, result: dict, truth: dict) -> dict | None:
    """z = (identified - equivalent truth) / uncertainty over every parameter and cycle, or None
    when the truth does not hold this dataset's parameter series."""
    names = cal.setup.model.names
    z = []
    for cid, (P, _) in result.items():
        series = (truth.get("campaigns", {}).get(cid) or {}).get("parameters")
        if not series or set(series) != set(names) or len(series[names[0]]) != len(P):
            return None
        full = np.column_stack([series[n] for n in names])
        z.append((P - equivalent_truth(cal, full)) / cal.uncertainty_)
    z = np.vstack(z)
    return {"n_parameters": int(z.shape[1]), "max_abs_z": float(np.max(np.abs(z))),
            "share_within_2u": float(np.mean(np.abs(z) <= 2.0)), "n_values": int(z.size),
            "z_sd": float(np.std(z))}


def calibrate(cfg: DictConfig) -> dict:
    """Identify the error parameters of every measurement cycle of ``data.path``."""
    check_config(cfg)
    c = cfg.calibrate
    check_calibrate(c)
    out = resolve(cfg.out)
    target = resolve(c.dataset) if c.get("dataset") else out / "parameters"
    if c.get("dataset"):
        _check_writable("calibrate.dataset", c.dataset, folder=True)
    root = resolve(cfg.data.path)
    say(f"reading {root}")
    with stage_run(cfg, "calibrate") as tr:
        with single_threaded_blas():      # 1430-wide matrices: threads on 2 busy cores only thrash
            params, cal, report, _ = calibrate_folder(root, c, data_options(cfg))
        truth_path = Path(f"{root}.truth.json")
        if truth_path.is_file():
            result = {cid: (params.campaigns[cid][cal.names_].to_numpy(), None) for cid in params.campaigns}
            rt = roundtrip(cal, result, json.loads(truth_path.read_text()))
            if rt is None:
                logger.warning("calibrate: %s does not hold this dataset's parameter series; no "
                               "round trip", truth_path)
            else:
                report = {"parameters": report.pop("parameters"), "roundtrip": rt, **report}
        report["dataset"] = str(target)
        inside = target.parent == out
        with staged_outputs(out, last=("calibration.json",)) as stage:
            io.write_dataset(params, stage / target.name if inside else target, str(c.format))
            write_json(stage / "calibration.json", report, ensure_ascii=False)
        tr.log_metrics({"n_parameters": len(cal.names_), "n_outliers": len(report["outliers"]),
                        "n_excluded": len(report["excluded"]),
                        "residual_rms_um": report["residual_rms_um"],
                        **({"roundtrip": report["roundtrip"]} if "roundtrip" in report else {})})
        tr.log_artifact(out / "calibration.json")
    print(_summary(cal, report))
    say(f"calibrate: {out / 'calibration.json'}, parameters: {target}")
    return report


def _summary(cal, report) -> str:
    line = (f"calibrate: {len(cal.names_)} of {len(cal.setup.model.names)} parameters identified "
            f"({len(report['unidentifiable'])} not seen by the {len(report['poses'])} poses), "
            f"{report['n_cycles']} cycles, {len(report['outliers'])} outlier(s), "
            f"{len(report['excluded'])} column(s) excluded, residual RMS "
            f"{report['residual_rms_um'] or float('nan'):.3f} µm")
    rt = report.get("roundtrip")
    if rt:
        line += (f"; round trip: {100 * rt['share_within_2u']:.1f} % within 2u "
                 f"(max |z| {rt['max_abs_z']:.2f})")
    return line
