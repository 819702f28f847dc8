"""What ``thermocomp diagnose`` makes of a :class:`~.diagnosis.Diagnosis`: the search settings
from plain values, the diagnosed model's config, the experiment that reruns it, the written
folder and the printed table (plain values in: the shell turns its config into them).

Reads ``data.path``, runs :func:`thermocomp.apps.diagnose.diagnose` on the
configured model and writes, under ``out``:

* ``diagnosis.json`` -- CLI.md layout, for the primary target (the one with
  the largest CV RMSE before);
* ``diagnosis/``: ``diagnosis_<target>.json`` for every target, ``report.md``
  and ``report.html`` (every target; the HTML embeds the figures), ``plots/``;
* ``diagnosis/conf/model/diagnosed.yaml`` -- the model plus the accepted
  effects -- and ``diagnosis/conf/experiment/diagnosed.yaml`` pinning what the
  diagnosis ran with, so ``thermocomp run hydra.searchpath=[file://<out>/diagnosis/conf]
  experiment=diagnosed data.path=...`` reproduces the "after" figures (in batch: where the
  deployed stream clamps a test row to the training envelope, "after" is the deployed figure
  and the rerun's is ``after.test_rmse_as_run``, :mod:`.deployed`).

The diagnosed model is built from that very config (as ``run`` builds it), so
the figures in the report are the ones the rerun gives.
"""

from __future__ import annotations

import shlex
from collections.abc import Mapping
from pathlib import Path

import yaml

from ...base.files import atomic_dir, write_json
from ...base.tables import name_width
from ...core.scoring.headline import DIAGNOSIS_HEADLINE, diagnosis_headline, write_headline
from ...core.scoring.results import TargetResult
from .augmented import MODEL_NAME
from .candidates import CandidateOptions
from .figures import diagnosis_figures
from .report import write_report
from .search import SearchOptions


def search_options(d: Mapping) -> SearchOptions:
    """``diagnose.*`` (checked against their rules) -> SearchOptions."""
    return SearchOptions(
        max_effects=d["max_effects"], min_gain_pct=float(d["min_gain_pct"]),
        alpha=float(d["alpha"]), shortlist=d["shortlist"], n_folds=d["n_folds"],
        n_blocks=d["n_blocks"], seed=int(d["seed"]), cv=str(d["cv"]),
        min_train_fraction=float(d["min_train_fraction"]), shrink=d["shrink"],
        candidates=CandidateOptions(taus_s=tuple(float(t) for t in d["taus_s"]),
                                    n_squares=d["n_squares"], fault_ratio=float(d["fault_ratio"]),
                                    families=tuple(d["families"]),
                                    initial_directions=tuple(d["initial_directions"])))


def diagnosed_model(estimator: dict, ati: dict | None, reference: str, effects: dict, name: str,
                    alphas: dict | None = None) -> dict:
    """The ``model`` config of the diagnosed model around ``estimator`` (an ATI wrapper,
    ``ati``, moves inside it); ``alphas``: per target, the CV-chosen penalty on the effect
    features (MLR base)."""
    base = dict(estimator)
    if ati is not None:
        inner = {k: v for k, v in ati.items() if k != "_partial_"}
        inner["base_estimator"] = base
        base = inner
    return {"name": name, "estimator": {
        "_target_": "thermocomp.apps.diagnose.AugmentedRegressor", "_convert_": "all",
        "reference": reference,
        "effects": {t: [e.to_dict() for e in es] for t, es in effects.items()},
        "alpha": {t: float(a) for t, a in (alphas or {}).items() if a} or None,
        "estimator": base}}


def experiment(name: str, with_ati: bool, groups: Mapping[str, dict | None], reference: str,
               kept_inputs: list[str] | None, eval_mode: str) -> dict:
    """``conf/experiment/diagnosed.yaml``: the diagnosed model with what the diagnosis ran with
    (``groups``: the ``select`` and ``denoise`` configs)."""
    defaults = [{"override /model": MODEL_NAME}]
    if with_ati:
        defaults.append({"override /ati": "none"})
    for group, node in groups.items():
        if node is not None and node.get("name") is not None:
            defaults.append({f"override /{group}": str(node["name"])})
    out: dict = {"defaults": defaults, "name": f"{name}-{MODEL_NAME}"}
    out.update({group: node for group, node in groups.items() if node is not None})
    data = {"reference": reference}
    if kept_inputs is not None:
        data["inputs"] = list(kept_inputs)
    out["data"] = data
    out["eval"] = {"mode": eval_mode}
    return out


def rerun_command(search_paths: list[str], data_config: str | None, overrides: list[tuple[str, str]],
                  conf_dir: Path, data_path: Path, out: Path, pins_inputs: bool) -> str:
    """The ``thermocomp run`` that reproduces the "after" figures: the written experiment, and
    how this diagnosis read its data, the user's own search path, ``data=`` config and
    ``data.*`` overrides (``(key, override)``) included (without them a lab's ';'-separated
    files were refused)."""
    pinned = {"data.path", "data.interim", "data.reference"} | (
        {"data.inputs"} if pins_inputs else set())     # the experiment pins these
    extra = [o for key, o in overrides if key.startswith("data.") and key not in pinned]
    parts = ["thermocomp run", f"hydra.searchpath=[{','.join([*search_paths, f'file://{conf_dir}'])}]"]
    if data_config not in (None, "default"):
        parts.append(f"data={data_config}")
    parts += [f"experiment={MODEL_NAME}", *extra, f"data.path={data_path}", f"out={out}"]
    return " ".join(shlex.quote(p) if i else p for i, p in enumerate(parts))


def _yaml(header: str, body: dict) -> str:
    return header + yaml.safe_dump(body, sort_keys=False, allow_unicode=True, width=100)


def write_outputs(out: Path, result, model: dict, experiment_config: dict, rerun: str,
                  header: str, plots: bool) -> tuple[Path, Path]:
    """``diagnosis.json``, its headline and the ``diagnosis/`` folder (per-target JSONs, the
    config to rerun the diagnosed model, figures, report): (folder, diagnosis.json)."""
    out.mkdir(parents=True, exist_ok=True)
    folder = out / "diagnosis"
    conf_dir = folder / "conf"
    jsons = {}
    for t in result.targets:
        j = result.to_json(t)
        j.update(config=str(conf_dir / "model" / f"{MODEL_NAME}.yaml"),
                 experiment=str(conf_dir / "experiment" / f"{MODEL_NAME}.yaml"),
                 rerun=rerun, report=str(folder / "report.html"))
        jsons[t] = j
    with atomic_dir(folder) as tmp:
        figures = diagnosis_figures(result, tmp / "plots") if plots else {}
        (tmp / "conf" / "model").mkdir(parents=True)
        (tmp / "conf" / "experiment").mkdir(parents=True)
        (tmp / "conf" / "model" / f"{MODEL_NAME}.yaml").write_text(_yaml(header, model))
        (tmp / "conf" / "experiment" / f"{MODEL_NAME}.yaml").write_text(
            _yaml("# @package _global_\n" + header, experiment_config))
        for t, j in jsons.items():
            write_json(tmp / f"diagnosis_{t}.json", j)
        write_report(tmp, jsons, {t: [f"plots/{p.name}" for p in ps] for t, ps in figures.items()},
                     rerun, result.primary)
    main = write_json(out / "diagnosis.json", jsons[result.primary])
    write_headline(out / DIAGNOSIS_HEADLINE, diagnosis_headline(jsons))  # `dvc metrics show`
    return folder, main


def tracked(result) -> tuple[dict, dict]:
    """(metrics, tags) of a diagnosis for the tracker."""
    metrics = {"diagnose": {t: {
        "before_test_rmse": TargetResult(d.before).test.rmse,
        "after_test_rmse": TargetResult(d.after).test.rmse,
        "before_cv_rmse": d.original_cv_rmse, "after_cv_rmse": d.final_cv_rmse,
        "n_accepted": len(d.accepted)} for t, d in result.targets.items()},
        "diagnose_seconds": result.seconds}
    tags = {"diagnose.primary": result.primary,
            "diagnose.accepted": "; ".join(
                f"{t}: {ev.effect.kind} {ev.effect.column or ''} {ev.effect.label}"
                for t, d in result.targets.items() for ev in d.accepted) or "none"}
    return metrics, tags


def parted_lines(result) -> list[str]:
    """Where the deployed stream clamped a test input or its guard changed a correction, a line
    saying so and run's batch figures (the model's own prediction, ``*_as_run``) beside the
    deployed ones the table shows; nothing where they are one computation."""
    which = ("before", "after")
    clamped = [result.clamped.get(w, 0) for w in which]
    guarded = {t: [result.guarded.get(w, {}).get(t, 0) for w in which] for t in result.targets}
    guarded = {t: n for t, n in guarded.items() if any(n)}
    if not any(clamped) and not guarded:
        return []
    causes = [f"{clamped[0]} / {clamped[1]} test row(s) clamped to the training envelope"] * any(clamped)
    causes += ["the guard (monitor.guard) bounded or rate-limited the correction on "
               + ", ".join(f"{t} {b} / {a}" for t, (b, a) in guarded.items())
               + " test row(s)"] * bool(guarded)
    as_run = "; ".join(f"{t} {TargetResult(d.before_as_run).test.rmse:.3f} -> "
                       f"{TargetResult(d.after_as_run).test.rmse:.3f}"
                       for t, d in result.targets.items() if d.after_as_run is not None)
    return [f"test RMSE as deployed (promote/replay/export: the stream; before / after: "
            f"{'; '.join(causes)}); `thermocomp run` scores the model's own prediction in batch: "
            f"{as_run}"]


def summary_table(result, named: str = "") -> str:
    """What the stage prints: per target, test RMSE before -> after and the accepted effects;
    ``named``: what the header says after the model (`` ati=cmeans``)."""
    w = name_width(result.targets)
    lines = [f"model={result.model}{named}  dataset={result.dataset}  mode={result.mode}"
             + ("" if result.mode == "simulation" else " (test; CV: simulation)"),
             f"{'target':<{w}} {'test RMSE before':>16} -> {'after':>6}   {'CV before':>9} -> {'after':>6}"
             "   accepted effects", "-" * 96]
    for t, d in result.targets.items():
        acc = ", ".join(ev.effect.title for ev in d.accepted) or "none"
        before, after = TargetResult(d.before).test.rmse, TargetResult(d.after).test.rmse
        lines.append(f"{t:<{w}} {before:>16.2f} -> {after:>6.2f}   "
                     f"{d.original_cv_rmse:>9.2f} -> {d.final_cv_rmse:>6.2f}   {acc}")
    lines += parted_lines(result)
    cv = result.cv
    samples = "measured samples" if cv.get("measured_rows") is not None else "samples"
    lines.append(f"acceptance test: {cv['test_blocks']} time blocks of ~{cv['block_samples']} {samples} "
                 f"in {cv['units']} CV units; smallest reachable p {cv['min_p']:.2g} "
                 f"(alpha {result.options.alpha:g})")
    designs = cv.get("designs") or {}
    if len({(d["test_blocks"], d["block_samples"]) for d in designs.values()}) > 1:
        lines.append("  each target on its own blocks: " + ", ".join(
            f"{t} {d['test_blocks']} of ~{d['block_samples']} (min p {d['min_p']:.2g})"
            for t, d in designs.items()))
    return "\n".join(lines)
