"""The design study of ``thermocomp design`` from its settings (pure core: plain dicts in).

:func:`study_from_settings` builds the :class:`~.design.CalibrationDesignStudy`
from the ``design`` settings and the set-up (a volumetric dataset's, or the
kinematic model's defaults); :func:`unreachable` says which strategies put a
ball outside the travel; :func:`summary_lines` is the printed table and findings.
"""

from __future__ import annotations

from pathlib import Path

from ...base.errors import ConfigError
from ...base.log import logger
from .artefact import check_reach
from .calibration import prior_sd
from .design import CalibrationDesignStudy, MachineFamily
from .kinematics import KinematicModel

WHAT_IF = "what-if"      # the mark of a strategy beyond the travel (table, findings, figures)
# the artefact when no volumetric dataset gives one: bar length (mm), probing and ball noise (µm)
DEFAULT_ARTEFACT = (1500.0, 0.5, 0.5)


def study_from_settings(d: dict, setup=None, prior: dict | None = None, seed: int = 0
                        ) -> CalibrationDesignStudy:
    """The study of the ``design`` settings ``d`` (its unset entries taken from ``setup``,
    a :class:`~.series.VolumetricSetup`, or the defaults).  A ``machine.order`` below the
    compensation model's is a ConfigError; an artefact that cannot be built a ValueError."""
    if setup is not None:
        base = setup.model
        length, probing, ball = setup.array.length_mm, setup.probing_um, setup.ball_um
    else:
        base, (length, probing, ball) = KinematicModel(), DEFAULT_ARTEFACT
    geometry = {"ranges": base.ranges, "chain": base.chain, "tool": base.tool}
    c_order = d["compensation_order"] or base.order
    compensation = KinematicModel(**geometry, order=c_order, cross_terms=base.cross_terms)
    m_order = d["machine"]["order"] or c_order + 2
    if m_order < c_order:
        raise ConfigError(f"design.machine.order={m_order} is below the compensation model's "
                         f"{c_order}")
    machine = KinematicModel(**geometry, order=m_order,
                             cross_terms=bool(d["machine"]["cross_terms"] or base.cross_terms))
    ranges = dict(d["ranges"])
    family = MachineFamily(machine, {k: v for k, v in ranges.items() if k != "decay"},
                           float(ranges.get("decay", 0.3)))
    return CalibrationDesignStudy(
        compensation, family, length_mm=d["length_mm"] or length, x_centres=d["x_centres"],
        probing_um=probing if d["probing_um"] is None else d["probing_um"],
        ball_um=ball if d["ball_um"] is None else d["ball_um"], grid=d["grid"],
        n_machines=d["n_machines"], n_jobs=d["n_jobs"], seed=seed,
        prior_sd=prior_sd(compensation, prior))


def unreachable(study: CalibrationDesignStudy, todo) -> dict[str, list[str]]:
    """Why each strategy of ``todo`` puts a ball where no probe can go (studied all the same:
    a what-if, not a measurement): {reason: [strategies]}."""
    out: dict[str, list[str]] = {}
    for strategy in todo:
        setup = study.setup(strategy)
        try:
            check_reach(setup.model, setup.array, setup.poses)
        except ValueError as err:
            out.setdefault(str(err), []).append(
                f"{strategy.n_balls} balls at {strategy.misalignment_deg:g}° ({strategy.position_set})")
    return out


def design_setup(data, folder) -> tuple[object, str]:
    """(the set-up studied, where it came from): that of the volumetric dataset ``folder``
    (``data.path`` as given: ``data``, resolved: ``folder``), else the kinematic model's
    defaults (None; a warning says why when a ``data.path`` was given)."""
    from .artefact import SETUP_FILE
    from .series import load_setup

    setup = load_setup(folder) if data else None
    if setup is not None:
        return setup, f"{Path(str(data)) / SETUP_FILE}"
    if data:
        why = ("does not exist" if not Path(folder).exists() else
               "holds no volumetric.json (not a volumetric dataset)")
        logger.warning(f"design: data.path {data} {why}: the kinematic model's "
                       "default machine and artefact are studied")
    return None, "kinematic model defaults"


def own_poses_line(setup) -> str | None:
    """What of a dataset's set-up the study does not take: its poses (the strategies are the
    position sets S1, S2, S3 at ``design.x_centres``) and its ball count and angle (those of
    ``design.studies``).  A lab that brought its own pose set read its set-up's name in the
    log and took the table for a study of its poses; ``None`` without a set-up."""
    if setup is None:
        return None
    names = [p.name for p in setup.poses]
    shown = ", ".join(names[:4]) + (", ..." if len(names) > 4 else "")
    return (f"design: volumetric.json's own {len(names)} poses ({shown}), {setup.array.n_balls} "
            f"balls and {setup.array.misalignment_deg:g}° are not studied: the strategies are "
            "design.studies' (position sets S1, S2, S3 at design.x_centres); its machine, bar "
            "length and uncertainties are")


def checked_study(d: dict, setup, prior: dict | None, seed: int
                  ) -> tuple[CalibrationDesignStudy, list]:
    """(the study of the settings ``d``, the strategies it runs); a bad setting is a
    ConfigError (``design: ...``).  Strategies that put a ball outside the travel are studied
    all the same (``reachable: false`` in ``design.json``), with a warning naming them."""
    from .design import strategies

    try:
        study = study_from_settings(d, setup, prior, seed)
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
    return study, todo


def design_report(study: CalibrationDesignStudy, result: dict, source: str,
                  prior: dict | None) -> dict:
    """``design.json`` (CLI.md): the set-up studied and :meth:`CalibrationDesignStudy.run`'s
    ``result``."""
    return {"n_machines": study.n_machines, "seed": study.seed, "setup": source, "prior": prior,
            "compensation": study.compensation.to_dict(),
            "machine": {**study.family.model.to_dict(), "ranges_a": study.family.amplitudes,
                        "decay": study.family.decay},
            "artefact": {"length_mm": study.length_mm, "x_centres": list(study.x_centres),
                         "probing_um": study.probing_um, "ball_um": study.ball_um},
            "grid": list(study.grid), **result}


def _pct(value) -> str:
    return "n/a" if value is None else f"{value:.0f} %"


def _table(report: dict) -> list[str]:
    lines = [f"VE (median, p95): {report['ve']['median']:.2f}, {report['ve']['p95']:.2f} µm "
             f"over {report['n_machines']} machines",
             f"{'set':<10} {'balls':>5} {'θ (°)':>6} {'VCE med':>8} {'p95':>7} {'impr.':>6} "
             f"{'ident.':>6} {'no noise':>8} {'noise':>6}"]
    for r in report["strategies"]:
        lines.append(f"{r['position_set']:<10} {r['n_balls']:>5} {r['misalignment_deg']:>6g} "
                     f"{r['median']:>8.2f} {r['p95']:>7.2f} {_pct(r['improvement_pct']):>6} "
                     f"{r['n_identified']:>6} {r['noise_free_median']:>8.2f} "
                     f"{r['noise_only_median']:>6.2f}"
                     + ("  " + WHAT_IF if not r["reachable"] else ""))
    if any(not r["reachable"] for r in report["strategies"]):
        lines.append(f"{WHAT_IF}: a ball outside the travel; studied, but no bar can be measured "
                      "so (reachable: false in design.json)")
    return lines


def summary_lines(report: dict) -> list[str]:
    """The table and the findings ``thermocomp design`` prints."""
    lines, f = _table(report), report["findings"]
    what_ifs = {study: sum(not r["reachable"] for r in report["strategies"] if study in r["studies"])
                for study in ("balls", "misalignment", "position_sets")}

    def caveat(study):
        n = what_ifs[study]
        return f" ({n} of its strategies put a ball outside the travel: what-ifs)" if n else ""

    if f.get("balls_for_95pct") is not None:
        lines.append(f"95 % of the best improvement with {f['balls_for_95pct']} balls"
                     f"{caveat('balls')}")
    elif "balls_for_95pct" in f:
        lines.append("no number of balls improves on the uncompensated machine (VCE above VE)")
    for s, m in f.get("misalignment", {}).items():
        lines.append(f"misalignment, {s}: VCE {m['vce_aligned']:.2f} at {m['aligned_deg']:g}° -> "
                     f"{m['vce_best']:.2f} at {m['best_deg']:g}° ({_pct(m['reduction_pct'])} "
                     f"less); noise-free {m['noise_free'][0]:.2f} -> {m['noise_free'][1]:.2f}, "
                     f"noise alone {m['noise_only'][0]:.2f} -> {m['noise_only'][1]:.2f}"
                     f"{caveat('misalignment')}")
    if "best_position_set" in f:
        b = f["best_position_set"]
        lines.append(f"best position set: {b['position_set']} (VCE {b['median']:.2f} µm, "
                     f"{b['n_probings']} probed points)"
                     + (f" {WHAT_IF}: a ball outside the travel" if not b.get("reachable", True)
                        else caveat("position_sets")))
    return lines
