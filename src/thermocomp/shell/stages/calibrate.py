"""`thermocomp calibrate`: artefact distances of a volumetric dataset -> error parameter series.

Reads ``data.path`` (a volumetric dataset: ``volumetric.json`` + the distance columns
``E_<pose>_B<i>_B<j>``, one row per measurement cycle; a folder without the set-up is
refused), identifies the kinematic model's parameters of every cycle
(:class:`~thermocomp.apps.volumetric.ArtefactCalibration`: GLS, outliers flagged and left out of
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

from pathlib import Path

from omegaconf import DictConfig

from ...apps.volumetric.calibration import roundtrip
from ...base.errors import ConfigError
from ...base.files import staged_outputs, write_json
from ...base.log import logger, say
from ...base.paths import resolve
from ...core import io
from ..config.apart import check_apart
from ..tracking import stage_run
from .common import _check_writable, calibrated_dataset, check_config, simulated_truth


def calibrate(cfg: DictConfig) -> dict:
    """Identify the error parameters of every measurement cycle of ``data.path``."""
    check_config(cfg)
    c = cfg.calibrate
    out = resolve(cfg.out)
    target = resolve(c.dataset) if c.get("dataset") else out / "parameters"
    root = resolve(cfg.data.path)
    if c.get("dataset"):
        check_apart(cfg, ("calibrate.dataset",), ())   # the default, <out>/parameters: as out
        _check_writable("calibrate.dataset", c.dataset, folder=True)
    _check_replaceable(target, root, f"calibrate.dataset={c.dataset}" if c.get("dataset") else
                       f"out={cfg.out}")
    say(f"reading {root}")
    with stage_run(cfg, "calibrate") as tr:
        params, cal, report, _ = calibrated_dataset(cfg)
        truth_path, truth = simulated_truth(cfg)
        if truth is not None:
            result = {cid: (params.campaigns[cid][cal.names_].to_numpy(), None) for cid in params.campaigns}
            rt = roundtrip(cal, result, truth)
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


def _check_replaceable(target: Path, root: Path, key: str) -> None:
    """The parameter series replace ``target`` whole: refuse a non-empty folder that is not this
    dataset's parameter series from an earlier calibrate (same campaigns): it once deleted a
    dataset given there by mistake (one inside ``data.path``: :mod:`.apart`)."""
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


def _summary(cal, report) -> str:
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
