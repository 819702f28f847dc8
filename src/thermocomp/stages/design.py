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

from ..errors import ConfigError
from ..files import staged_outputs, write_json
from ..log import logger
from ..paths import resolve
from ..tracking import stage_run
from ..volumetric import KinematicModel, load_setup
from ..volumetric.artefact import check_reach
from ..volumetric.calibration import prior_sd
from ..volumetric.design import CalibrationDesignStudy, MachineFamily, strategies
from .common import calibration_prior, check_config, say

WHAT_IF = "what-if"      # the mark of a strategy beyond the travel (table, findings, figures)


def build_study(cfg: DictConfig) -> tuple[CalibrationDesignStudy, dict, str]:
    """The study of the config, its studies, and where the set-up came from."""
    d = OmegaConf.to_container(cfg.design, resolve=True)     # checked by check_config
    d["studies"] = {name: s for name, s in d["studies"].items() if s is not None}
    prior = calibration_prior(cfg.calibrate)
    data = (cfg.get("data") or {}).get("path")
    setup = load_setup(resolve(str(data))) if data else None
    if setup is not None:
        base, source = setup.model, f"{Path(str(data)) / 'volumetric.json'}"
        length, probing, ball = setup.array.length_mm, setup.probing_um, setup.ball_um
    else:
        if data:
            why = ("does not exist" if not resolve(str(data)).exists() else
                   "holds no volumetric.json (not a volumetric dataset)")
            logger.warning(f"design: data.path {data} {why}: the kinematic model's "
                           "default machine and artefact are studied")
        base, source = KinematicModel(), "kinematic model defaults"
        length, probing, ball = 1500.0, 0.5, 0.5
    geometry = {"ranges": base.ranges, "chain": base.chain, "tool": base.tool}
    c_order = d["compensation_order"] or base.order
    compensation = KinematicModel(**geometry, order=c_order, cross_terms=base.cross_terms)
    m_order = d["machine"]["order"] or c_order + 2
    if m_order < c_order:
        raise ConfigError(f"design.machine.order={m_order} is below the compensation model's {c_order}")
    machine = KinematicModel(**geometry, order=m_order,
                             cross_terms=bool(d["machine"]["cross_terms"] or base.cross_terms))
    ranges = dict(d["ranges"])
    family = MachineFamily(machine, {k: v for k, v in ranges.items() if k != "decay"},
                           float(ranges.get("decay", 0.3)))
    sd = prior_sd(compensation, prior)
    try:
        study = CalibrationDesignStudy(
            compensation, family, length_mm=d["length_mm"] or length, x_centres=d["x_centres"],
            probing_um=probing if d["probing_um"] is None else d["probing_um"],
            ball_um=ball if d["ball_um"] is None else d["ball_um"], grid=d["grid"],
            n_machines=d["n_machines"], n_jobs=d["n_jobs"], seed=int(cfg.seed),
            prior_sd=sd)
        todo = strategies(d["studies"])[0]
        unreachable: dict[str, list[str]] = {}     # is every ball where a probe can go?
        for strategy in todo:
            setup = study.setup(strategy)
            try:
                check_reach(setup.model, setup.array, setup.poses)
            except ValueError as err:     # studied all the same: a what-if, not a measurement
                unreachable.setdefault(str(err), []).append(
                    f"{strategy.n_balls} balls at {strategy.misalignment_deg:g}° ({strategy.position_set})")
        if unreachable:
            n = sum(len(v) for v in unreachable.values())
            logger.warning(f"design: {n} of {len(todo)} strategies put a ball outside the travel "
                           f"({study.length_mm:g} mm bar), studied all the same (reachable: false in "
                           "design.json): " + "; ".join(f"{', '.join(who)}: {why}"
                                                        for why, who in unreachable.items()))
    except ValueError as err:
        raise ConfigError(f"design: {err}") from None
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
                from ..volumetric.design_figures import draw
                draw(stage / "design", report)
            write_json(stage / "design.json", report)
        f = result["findings"]
        tr.log_metrics({"design": {"ve_median": result["ve"]["median"],
                                   "balls_for_95pct": f.get("balls_for_95pct"),
                                   "time_s": result["time_s"]}})
        tr.log_artifact(out / "design.json")
    _print(report)
    say(f"design: {out / 'design.json'} ({result['time_s']:.1f} s)")
    return report


def _pct(value) -> str:
    return "n/a" if value is None else f"{value:.0f} %"


def _print(report: dict) -> None:
    print(f"VE (median, p95): {report['ve']['median']:.2f}, {report['ve']['p95']:.2f} µm "
          f"over {report['n_machines']} machines")
    print(f"{'set':<10} {'balls':>5} {'θ (°)':>6} {'VCE med':>8} {'p95':>7} {'impr.':>6} {'ident.':>6} "
          f"{'no noise':>8} {'noise':>6}")
    for r in report["strategies"]:
        print(f"{r['position_set']:<10} {r['n_balls']:>5} {r['misalignment_deg']:>6g} "
              f"{r['median']:>8.2f} {r['p95']:>7.2f} {_pct(r['improvement_pct']):>6} {r['n_identified']:>6} "
              f"{r['noise_free_median']:>8.2f} {r['noise_only_median']:>6.2f}"
              + ("  " + WHAT_IF if not r["reachable"] else ""))
    if any(not r["reachable"] for r in report["strategies"]):
        print(f"{WHAT_IF}: a ball outside the travel; studied, but no bar can be measured so "
              "(reachable: false in design.json)")
    f = report["findings"]
    what_ifs = {study: sum(not r["reachable"] for r in report["strategies"] if study in r["studies"])
                for study in ("balls", "misalignment", "position_sets")}

    def caveat(study):
        n = what_ifs[study]
        return f" ({n} of its strategies put a ball outside the travel: what-ifs)" if n else ""

    if f.get("balls_for_95pct") is not None:
        print(f"95 % of the best improvement with {f['balls_for_95pct']} balls{caveat('balls')}")
    elif "balls_for_95pct" in f:
        print("no number of balls improves on the uncompensated machine (VCE above VE)")
    for s, m in f.get("misalignment", {}).items():
        print(f"misalignment, {s}: VCE {m['vce_aligned']:.2f} at {m['aligned_deg']:g}° -> "
              f"{m['vce_best']:.2f} at {m['best_deg']:g}° ({_pct(m['reduction_pct'])} less); "
              f"noise-free {m['noise_free'][0]:.2f} -> {m['noise_free'][1]:.2f}, noise alone "
              f"{m['noise_only'][0]:.2f} -> {m['noise_only'][1]:.2f}{caveat('misalignment')}")
    if "best_position_set" in f:
        b = f["best_position_set"]
        print(f"best position set: {b['position_set']} (VCE {b['median']:.2f} µm, "
              f"{b['n_probings']} probed points)"
              + (f" {WHAT_IF}: a ball outside the travel" if not b.get("reachable", True)
                 else caveat("position_sets")))
