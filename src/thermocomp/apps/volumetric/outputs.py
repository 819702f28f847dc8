"""What ``calibrate`` writes beside the parameter series: the round trip against a simulated
truth, the one-line summary, and the check that the folder it replaces holds its own series."""

from __future__ import annotations

from pathlib import Path

from ...base.errors import ConfigError
from ...base.log import logger
from .calibration import roundtrip


def with_roundtrip(params, cal, report: dict, truth: dict | None, truth_path) -> dict:
    """``report`` with ``roundtrip`` (after ``parameters``) when ``truth`` holds this dataset's
    parameter series (said when it does not)."""
    if truth is None:
        return report
    result = {cid: (params.campaigns[cid][cal.names_].to_numpy(), None) for cid in params.campaigns}
    rt = roundtrip(cal, result, truth)
    if rt is None:
        logger.warning("calibrate: %s does not hold this dataset's parameter series; no "
                       "round trip", truth_path)
        return report
    return {"parameters": report.pop("parameters"), "roundtrip": rt, **report}


def check_replaceable(target: Path, root: Path, key: str) -> None:
    """The parameter series replace ``target`` whole: refuse a non-empty folder that is not this
    dataset's parameter series from an earlier calibrate (same campaigns): it once deleted a
    dataset given there by mistake (one inside ``data.path``: ``shell/stages/apart.py``)."""
    import pandas as pd

    t, r = target.resolve(), root.resolve()
    if not t.is_dir() or not any(t.iterdir()):
        return
    manifest = t / "campaigns.csv"
    try:
        ids = set(pd.read_csv(manifest)["campaign"].astype(str))
        mine = set(pd.read_csv(r / "campaigns.csv")["campaign"].astype(str))
    except Exception:
        ids, mine = None, set()
    if ids != mine:
        raise ConfigError(f"{key}: {t} is not empty and does not hold this dataset's parameter "
                          "series (written by an earlier calibrate); it would be replaced whole: "
                          "give an empty or new folder")


def summary(cal, report) -> str:
    """The line ``calibrate`` prints: parameters identified, cycles, outliers, the round trip."""
    seen = f"{len(report['unidentifiable'])} not seen by the {len(report['poses'])} poses"
    if report.get("prior") is None:
        n = len(cal.setup.model.names)
        line = f"calibrate: {len(cal.names_)} of {n} parameters identified ({seen}), "
    else:
        line = f"calibrate: all {len(cal.names_)} parameters estimated with calibrate.prior ({seen}), "
    line += (f"{report['n_cycles']} cycles, {len(report['outliers'])} outlier(s), "
             f"{len(report['excluded'])} column(s) excluded, residual RMS "
             f"{report['residual_rms_um'] or float('nan'):.3f} µm")
    rt = report.get("roundtrip")
    if rt:
        line += (f"; round trip: {100 * rt['share_within_2u']:.1f} % within 2u "
                 f"(max |z| {rt['max_abs_z']:.2f})")
    return line
