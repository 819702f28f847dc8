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

from ...apps.volumetric.design_study import (
    checked_study,
    design_report,
    design_setup,
    own_poses_line,
    summary_lines,
)
from ...base.files import staged_outputs, write_json
from ...base.log import say
from ...base.paths import resolve
from ..config.checks import check_config
from ..source import calibration_prior
from ..tracking import stage_run


def build_study(cfg: DictConfig) -> tuple:
    """The study of the config, the strategies it runs, and where the set-up came from."""
    d = OmegaConf.to_container(cfg.design, resolve=True)     # checked by check_config
    d["studies"] = {name: s for name, s in d["studies"].items() if s is not None}
    data = (cfg.get("data") or {}).get("path")
    setup, source = design_setup(data, resolve(str(data)) if data else None)
    study, todo = checked_study(d, setup, calibration_prior(cfg.calibrate), int(cfg.seed))
    if (line := own_poses_line(setup)) is not None:
        say(line)
    return study, d["studies"], todo, source


def design(cfg: DictConfig) -> dict:
    """Run the study; write ``design.json`` and the figures."""
    check_config(cfg)
    study, studies, todo, source = build_study(cfg)
    with stage_run(cfg, "design") as tr:
        say(f"design: {study.n_machines} machines × {len(todo)} strategies (C: {source})")
        result = study.run(studies)
        report = design_report(study, result, source, calibration_prior(cfg.calibrate))
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
