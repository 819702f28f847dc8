"""`thermocomp calibrate`: artefact distances of a volumetric dataset -> error parameter series.

Reads ``data.path`` (a volumetric dataset: ``volumetric.json`` + the distance columns
``E_<pose>_B<i>_B<j>``, one row per measurement cycle; a folder without the set-up is
refused) through :func:`~thermocomp.shell.source.open_source`, which identifies the kinematic
model's parameters of every cycle (:class:`~thermocomp.apps.volumetric.ArtefactCalibration`:
GLS, outliers flagged and left out of their cycle), and writes, staged and atomically:

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

from omegaconf import DictConfig

from ...apps.volumetric.outputs import check_replaceable, summary, with_roundtrip
from ...base.files import staged_outputs, write_json
from ...base.log import say
from ...base.paths import resolve
from ...core import io
from ..config.apart import check_apart
from ..config.checks import _check_writable, check_config
from ..source import open_source, simulated_truth
from ..tracking import stage_run


def calibrate(cfg: DictConfig) -> dict:
    """Identify the error parameters of every measurement cycle of ``data.path``."""
    check_config(cfg)
    c, out = cfg.calibrate, resolve(cfg.out)
    target = resolve(c.dataset) if c.get("dataset") else out / "parameters"
    if c.get("dataset"):
        check_apart(cfg, ("calibrate.dataset",), ())   # the default, <out>/parameters: as out
        _check_writable("calibrate.dataset", c.dataset, folder=True)
    check_replaceable(target, resolve(cfg.data.path),
                      f"calibrate.dataset={c.dataset}" if c.get("dataset") else f"out={cfg.out}")
    with stage_run(cfg, "calibrate") as tr:
        params = open_source(cfg, volumetric=True)
        cal = params.meta["calibrator"]
        report = with_roundtrip(params, cal, dict(params.meta["calibration"]),
                                *reversed(simulated_truth(cfg)))
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
    print(summary(cal, report))
    say(f"calibrate: {out / 'calibration.json'}, parameters: {target}")
    return report
