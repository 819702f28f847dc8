"""`thermocomp design`: Monte Carlo study of artefact calibration strategies (paper 001).

The compensation model C and the artefact are the set-up of ``data.path/volumetric.json``
when there is one (a volumetric dataset), else the kinematic model's defaults; the machine
family M, the strategies and the Monte Carlo are ``design.*``.  Writes
``<out>/design.json`` (one row per strategy with the VCE ``median`` and ``p95``; CLI.md)
and figures in ``<out>/design/``; prints the table and the findings.
"""

from __future__ import annotations

from pathlib import Path

from omegaconf import DictConfig, OmegaConf

from ...apps.volumetric import load_setup
from ...apps.volumetric.design import CalibrationDesignStudy, strategies
from ...apps.volumetric.design_study import study_from_settings, summary_lines, unreachable
from ...base.errors import ConfigError
from ...base.files import staged_outputs, write_json
from ...base.log import logger, say
from ...base.paths import resolve
from ..source import calibration_prior
from ..tracking import stage_run
from .common import check_config


def build_study(cfg: DictConfig) -> tuple[CalibrationDesignStudy, dict, str]:
    """The study of the config, its studies, and where the set-up came from."""
    d = OmegaConf.to_container(cfg.design, resolve=True)     # checked by check_config
    d["studies"] = {name: s for name, s in d["studies"].items() if s is not None}
    data = (cfg.get("data") or {}).get("path")
    setup = load_setup(resolve(str(data))) if data else None
    source = (f"{Path(str(data)) / 'volumetric.json'}" if setup is not None
              else "kinematic model defaults")
    if setup is None and data:
        why = ("does not exist" if not resolve(str(data)).exists() else
               "holds no volumetric.json (not a volumetric dataset)")
        logger.warning(f"design: data.path {data} {why}: the kinematic model's "
                       "default machine and artefact are studied")
    try:
        study = study_from_settings(d, setup, calibration_prior(cfg.calibrate), int(cfg.seed))
        todo = strategies(d["studies"])[0]
        missed = unreachable(study, todo)
    except ConfigError:
        raise
    except ValueError as err:
        raise ConfigError(f"design: {err}") from None
    if missed:
        n = sum(len(v) for v in missed.values())
        logger.warning(f"design: {n} of {len(todo)} strategies put a ball outside the travel "
                       f"({study.length_mm:g} mm bar), studied all the same (reachable: false in "
                       "design.json): " + "; ".join(f"{', '.join(who)}: {why}"
                                                    for why, who in missed.items()))
    return study, d["studies"], source


def design(cfg: DictConfig) -> dict:
    """Run the study; write ``design.json`` and the figures."""
    check_config(cfg)
    study, studies, source = build_study(cfg)
    n = len(strategies(studies)[0])
    with stage_run(cfg, "design") as tr:
        say(f"design: {study.n_machines} machines × {n} strategies (C: {source})")
        result = study.run(studies)
        report = {"n_machines": study.n_machines, "seed": study.seed, "setup": source,
                  "prior": calibration_prior(cfg.calibrate),
                  "compensation": study.compensation.to_dict(),
                  "machine": {**study.family.model.to_dict(), "ranges_a": study.family.amplitudes,
                              "decay": study.family.decay},
                  "artefact": {"length_mm": study.length_mm, "x_centres": list(study.x_centres),
                               "probing_um": study.probing_um, "ball_um": study.ball_um},
                  "grid": list(study.grid), **result}
        out = Path(resolve(cfg.out))
        with staged_outputs(out, last=("design.json",)) as stage:
            if cfg.plots != "none":
                from ...apps.volumetric.design_figures import draw
                draw(stage / "design", report)
            write_json(stage / "design.json", report)
        f = result["findings"]
        tr.log_metrics({"design": {"ve_median": result["ve"]["median"],
                                   "balls_for_95pct": f.get("balls_for_95pct"),
                                   "time_s": result["time_s"]}})
        tr.log_artifact(out / "design.json")
    print("\n".join(summary_lines(report)))
    say(f"design: {out / 'design.json'} ({result['time_s']:.1f} s)")
    return report
