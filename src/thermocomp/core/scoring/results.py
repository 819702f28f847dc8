"""The scores of a run as an object, in the statsmodels manner (pure core).

:class:`EvaluationResult` wraps a ``metrics.json`` document: :meth:`~EvaluationResult.to_json`
gives the document (the CLI.md contract), :meth:`~EvaluationResult.headline` the few figures
per target that MLflow, ``dvc metrics show`` and ``compare``/``promote`` show (each figure
defined once, in :data:`HEADLINES`) and :meth:`~EvaluationResult.summary` the printed table.
:class:`TargetResult` and :class:`Scores` read one target and one block of it.  The keys of
the scores are named in :mod:`thermocomp.core.metrics`; the headline names here; nowhere else.
"""

from __future__ import annotations

import json
from collections.abc import Mapping

import numpy as np

from ...base.errors import listed
from ...base.jsonsafe import json_safe
from ...base.tables import name_width
from ..continuation import carried_text
from ..metrics import (
    E_P95,
    MAE,
    OTHER_BLOCKS,
    PERSISTENCE,
    RMS_AFTER,
    RMS_BEFORE,
    RMS_REDUCTION,
    RMSE,
    RSD_MEAN,
    RSD_SD,
    VALIDATION,
    reduction_pct,
    test_block,
    unit,
    validation_block,
)
from ..metrics import (
    SCORE_KEYS as SPLIT_KEYS,
)

DEPLOYED_MODE = "simulation"   # a deployed compensator runs free: the validation that chooses
HOUR_S = 3600.0

# headline names (DVC headline files, compare's columns, the fleet table)
TEST_RMSE, TEST_RSD_MEAN, TEST_RSD_SD = "test_rmse", "test_rsd_mean", "test_rsd_sd"
VAL_RMSE, VAL_RSD_MEAN, VAL_RSD_SD = "val_rmse", "val_rsd_mean", "val_rsd_sd"
TRAIN_RMSE, TEST_RMS_BEFORE, TEST_RMS_AFTER = "train_rmse", "test_rms_before", "test_rms_after"
E_P95_1H, E_P95_8H = "e_p95_1h", "e_p95_8h"
SCORE_KEYS = (*SPLIT_KEYS, TEST_RMSE, TEST_RSD_MEAN, TEST_RSD_SD, VAL_RMSE, VAL_RSD_MEAN,
              VAL_RSD_SD, TRAIN_RMSE, TEST_RMS_BEFORE, TEST_RMS_AFTER, E_P95_1H, E_P95_8H)
"""Every score key: of ``metrics.json`` (:mod:`thermocomp.core.metrics`) and of the headlines."""

# style -> ((name, block of TargetResult, figure of Scores), ...): what each reader shows
_TEST_FIGURES = (RSD_MEAN, RSD_SD, RMSE, MAE, RMS_REDUCTION, E_P95_1H, E_P95_8H)   # MAE: papers report it
HEADLINES = {
    "dvc": ((TEST_RMSE, "test", RMSE), (TEST_RSD_MEAN, "test", RSD_MEAN),
            (TEST_RSD_SD, "test", RSD_SD), (RMS_REDUCTION, "test", RMS_REDUCTION),
            (VAL_RMSE, VALIDATION, RMSE)),
    "mlflow": (("val.rmse", VALIDATION, RMSE), ("val.rsd_mean", VALIDATION, RSD_MEAN),
               *((f"test.{f}", "test", f)    # MAE beside RMSE: papers (fl_thermal's) report it
                 for f in (RMSE, MAE, RSD_MEAN, RSD_SD, RMS_BEFORE, RMS_AFTER, E_P95_1H, E_P95_8H)),
               *((f"{b}.{RMSE}", b, RMSE) for b in (*OTHER_BLOCKS, PERSISTENCE))),
    "compare": ((VAL_RMSE, "deployed", RMSE), (VAL_RSD_MEAN, "deployed", RSD_MEAN),
                (VAL_RSD_SD, "deployed", RSD_SD), *((f, "test", f) for f in _TEST_FIGURES)),
    "baseline": tuple((f, PERSISTENCE, f) for f in _TEST_FIGURES),
    "fleet": ((TRAIN_RMSE, "train", RMSE), (TEST_RMSE, "test", RMSE),
              (TEST_RMS_BEFORE, "test", RMS_BEFORE), (TEST_RMS_AFTER, "test", RMS_AFTER),
              (VAL_RMSE, VALIDATION, RMSE)),
}
"""The headline figures of each reader: MLflow (``<target>.<name>``), ``dvc metrics show``
(``headline/<target>.json``), ``compare``/``promote`` (validation of the deployed mode, then
the test figures), the persistence baseline's row (``baseline``) beside them, and the fleet table."""


def e_p95_at(e_p95: Mapping | None, seconds: float, curve: str = "after") -> float | None:
    """E_P95 of ``curve`` at a window of ``seconds``, linearly interpolated.

    ``None`` when the campaigns are shorter than the window (the curve stops
    before it) or there is no curve.
    """
    if not e_p95 or not e_p95.get("window_s"):
        return None
    w = np.asarray(e_p95["window_s"], float)
    v = np.asarray([np.nan if x is None else x for x in e_p95[curve]], float)
    ok = np.isfinite(v)
    if not ok.any() or seconds > w[ok].max() or seconds < w[ok].min():
        return None
    return float(np.interp(seconds, w[ok], v[ok]))


class Scores:
    """One block of a target's scores (a split, a baseline, a validation); every figure is
    ``None`` when the block or the figure is absent.

    Parameters
    ----------
    block : mapping or None
        The block of ``metrics.json``, e.g. ``metrics["targets"]["E_X"]["test"]``.
    rms_before : float, optional
        The measured error's RMS the reduction is taken against, when the block has none
        (a baseline: it predicts the same test split).
    """

    def __init__(self, block: Mapping | None, rms_before: float | None = None):
        self.block = block or {}
        self._before = rms_before

    def __bool__(self) -> bool:
        return bool(self.block)

    def get(self, key: str):
        """A figure of the block by its key (``None`` if absent)."""
        return self.block.get(key)

    rmse = property(lambda self: self.get(RMSE))
    mae = property(lambda self: self.get(MAE))
    rsd_mean = property(lambda self: self.get(RSD_MEAN))
    rsd_sd = property(lambda self: self.get(RSD_SD))
    e_p95 = property(lambda self: self.get(E_P95), doc="The E_P95 curves (before, after).")
    e_p95_1h = property(lambda self: e_p95_at(self.e_p95, HOUR_S))
    e_p95_8h = property(lambda self: e_p95_at(self.e_p95, 8 * HOUR_S))

    @property
    def rms_before(self):
        return self.get(RMS_BEFORE) if self._before is None else self._before

    @property
    def rms_after(self):
        return self.get(RMS_AFTER) if self._before is None else self.rmse   # a baseline: its RMSE

    @property
    def rms_reduction_pct(self) -> float | None:
        """:func:`~thermocomp.core.metrics.reduction_pct` of the RMS before and after."""
        return reduction_pct(self.rms_before, self.rms_after)

    def figure(self, name: str):
        """The figure ``name`` (a property of this class: stored, or computed from the block)."""
        return getattr(self, name)


class TargetResult:
    """The scores of one target (``metrics.json`` ``targets.<target>``)."""

    def __init__(self, entry: Mapping):
        self.entry = entry

    train = property(lambda self: Scores(self.entry.get("train")))
    test = property(lambda self: Scores(self.entry.get("test")))
    validation = property(lambda self: Scores(self.entry.get(VALIDATION)),
                          doc="The validation in the run's ``eval.mode``.")

    @property
    def deployed(self) -> Scores:
        """The validation in the deployed mode: ``validation_simulation`` of a run scored in
        ``one_step``, else ``validation`` (of a simulation run; of an old one_step run)."""
        return Scores(self.entry.get(validation_block(DEPLOYED_MODE)) or self.entry.get(VALIDATION))

    @property
    def persistence(self) -> Scores:
        """The persistence baseline, its reduction against the test split's RMS before."""
        return Scores(self.entry.get(PERSISTENCE), self.test.rms_before)

    def block(self, name: str) -> Scores:
        """The block ``name``: a property of this class, else the target's entry of that key."""
        return getattr(self, name) if hasattr(type(self), name) else Scores(self.entry.get(name))

    def test_in(self, mode: str, scored_mode: str) -> Scores:
        """The test figures in ``mode`` of a run scored in ``scored_mode``."""
        return self.test if mode == scored_mode else Scores(self.entry.get(test_block(mode)))

    def headline(self, style: str) -> dict:
        """``{name: figure}`` of :data:`HEADLINES` ``[style]``."""
        return {name: self.block(block).figure(figure) for name, block, figure in HEADLINES[style]}

    def slim(self) -> dict:
        """The figures a fleet keeps per group and target (no curves: hundreds of groups)."""
        val = self.entry.get(VALIDATION) or {}
        keep = (RMSE, RSD_MEAN, RSD_SD, RMS_BEFORE, RMS_AFTER, RMS_REDUCTION)
        return {"train": {RMSE: self.train.rmse}, "test": {k: self.test.get(k) for k in keep},
                VALIDATION: {k: val.get(k) for k in (RMSE, "method")} if val else None}


class EvaluationResult:
    """A run's scores: the ``metrics.json`` document and what is shown of it.

    Parameters
    ----------
    metrics : dict
        The document (``model``, ``mode``, ``targets``, ...), as :func:`to_json` writes it.
    """

    def __init__(self, metrics: dict):
        self.metrics = metrics

    @property
    def targets(self) -> dict[str, TargetResult]:
        return {t: TargetResult(m) for t, m in self.metrics.get("targets", {}).items()}

    def to_json(self) -> str:
        """``metrics.json``'s text (as :func:`thermocomp.base.files.write_json` writes it)."""
        return json.dumps(json_safe(self.metrics), indent=2, allow_nan=False) + "\n"

    def headline(self, style: str = "dvc") -> dict:
        """The headline figures of one reader.

        Parameters
        ----------
        style : {'dvc', 'mlflow', 'compare', 'baseline', 'fleet'}
            A key of :data:`HEADLINES`.

        Returns
        -------
        dict
            ``{target: {name: figure}}``; for ``dvc`` plus ``volumetric`` (distance and VCE
            RMS, A.3 range, before/after) of a volumetric run; for ``mlflow`` one flat
            ``{"<target>.<name>": figure}`` without the missing figures, the volumetric
            ones included.
        """
        per = {t: r.headline(style) for t, r in self.targets.items()}
        vol = self.metrics.get("volumetric")
        if style == "mlflow":
            flat = {f"{t}.{k}": v for t, fig in per.items() for k, v in fig.items() if v is not None}
            return {**flat, **(volumetric_mlflow(vol) if vol else {})}
        if style == "dvc" and vol:
            per["volumetric"] = volumetric_dvc(vol)
        return per

    def summary(self) -> str:
        """The table ``run`` prints per target: test Rsd SM/SD, RMS before -> after, and the
        test RMSE in simulation and one-step mode next to the persistence baseline's."""
        m = self.metrics
        w = name_width(self.targets)
        angular = [t for t in m["targets"] if unit(t) != "µm"]
        units = "(µm)" if not angular else f"(µm; {listed(angular, 3)} in µm/m)"
        # ATI and denoising named where used: a sweep's jobs over them printed the same header
        named = "".join(f"  {k}={v}" for k, v in (("ati", (m.get("ati") or {}).get("name")),
                                                  ("denoise", m.get("denoise"))) if v and v != "none")
        lines = [f"model={m['model']}  select={m.get('select', 'all')}{named}  mode={m['mode']}  "
                 f"dataset={m.get('dataset', '')}",
                 f"{'target':<{w}} {'test Rsd SM':>11} {'SD':>6}   {'RMS before':>10} -> {'after':>6}"
                 f"  {'reduction':>9}   {'RMSE sim':>8} {'1-step':>6} {'persist.':>8}   {units}",
                 "-" * 96]
        for t, r in self.targets.items():
            te = r.test
            # a target that does not move (a parameter no distance sees, under a prior) has none
            red = (f"{100 * (1 - te.rms_after / te.rms_before):>8.1f}%" if te.rms_before
                   else "     n/a ")
            lines.append(f"{t:<{w}} {_f(te.rsd_mean):>11} {_f(te.rsd_sd):>6}   "
                         f"{te.rms_before:>10.2f} -> {te.rms_after:>6.2f}  {red}   "
                         f"{_f(r.test_in('simulation', m['mode']).rmse):>8} "
                         f"{_f(r.test_in('one_step', m['mode']).rmse):>6} "
                         f"{_f(r.persistence.rmse):>8}")
        if m.get("carry_over"):
            lines.append("state carried over: " + carried_text(m["carry_over"]))
        return "\n".join(lines + worse_than_none(self.targets) + auto_table(m))


def worse_than_none(targets: Mapping[str, "TargetResult"]) -> list[str]:
    """The printed table's line naming the targets whose deployed-mode validation RMSE is above
    the uncompensated error's on the same rows (``rms_before`` of the validation): there the
    compensator, deployed, is expected to make the axis worse than no compensation."""
    worse = {t: r.deployed for t, r in targets.items()
             if r.deployed.rmse is not None and r.deployed.rms_before is not None
             and r.deployed.rmse > r.deployed.rms_before}
    if not worse:
        return []
    figures = ", ".join(f"{t} {v.rmse:.3g} > {v.rms_before:.3g}" for t, v in worse.items())
    return [f"WORSE THAN NO COMPENSATION on validation (RMSE against the uncompensated error's "
            f"RMS, the same rows): {figures}; deployed, this model is expected to make "
            f"{'that axis' if len(worse) == 1 else 'those axes'} worse (model=auto keeps a zero "
            "correction where nothing beats none)"]


def _f(v) -> str:
    return "  n/a" if v is None else f"{v:5.2f}"


def auto_table(metrics: dict) -> list[str]:
    """Lines of the printed table: per target the chosen family and every candidate's
    free-run validation RMSE (MLR and persistence always among them); none without auto."""
    rows = {t: m["auto"] for t, m in metrics["targets"].items() if "auto" in m}
    if not rows:
        return []
    names = list(dict.fromkeys(n for a in rows.values() for n in a["candidates"]))
    w = name_width(rows)
    lines = ["model=auto: free-run validation RMSE per candidate (* chosen; the test split chose "
             "nothing; persistence: the previous measured error, one-step)",
             f"{'target':<{w}} {'chosen':<10} " + " ".join(f"{n[:11]:>11}" for n in names)]
    for t, a in rows.items():
        cells = []
        for n in names:
            v = a["candidates"].get(n)
            cells.append(f"{'n/a' if v is None else f'{v:.3g}' + ('*' if n == a['chosen'] else ''):>11}")
        lines.append(f"{t:<{w}} {a['chosen']:<10} " + " ".join(cells))
    lines += [f"  {t} blend: " + ", ".join(f"{n} {w:.2f}" for n, w in a["weights"].items())
              for t, a in rows.items() if len(a.get("weights", {})) > 1]
    skipped = {n: w for a in rows.values() for n, w in a.get("skipped", {}).items()}
    lines += [f"  skipped {n}: {w}" for n, w in skipped.items()]
    tied = {n: w for a in rows.values() for n, w in a.get("validated_as", {}).items()}
    lines += [f"  {n} {w}" for n, w in tied.items()]
    lines += [f"  {t} diagnosed: {_accepted(a['diagnosed'])}" for t, a in rows.items() if "diagnosed" in a]
    return lines


def _accepted(entry: dict) -> str:
    """One line of what ``model.diagnosed``'s search accepted for a target (effects99)."""
    design = f"the design's smallest p {entry['min_p']:.2g}"
    if not entry["accepted"]:
        return f"nothing accepted on the train split ({design})"
    effects = ", ".join(f"{e['effect']} (p {e['p']:.2g})" for e in entry["accepted"])
    alpha = "least squares" if entry["alpha"] is None else f"alpha {entry['alpha']:.3g}"
    return f"{effects}; {alpha}; {design}"


_VOLUMETRIC_BLOCKS = ("distance_error", "vce")
_A3_RANGES = ("range_before", "range_after")


def volumetric_dvc(section: Mapping) -> dict:
    """The volumetric run's own headline (``headline/volumetric.json``)."""
    dist, vce = section["distance_error"], section["vce"]
    return {"distance_rms_before": dist[RMS_BEFORE], "distance_rms_after": dist[RMS_AFTER],
            "vce_rms_before": vce[RMS_BEFORE], "vce_rms_after": vce[RMS_AFTER],
            **{f"iso_a3_{k}": section["iso_a3"].get(k) for k in _A3_RANGES}}


def volumetric_mlflow(section: Mapping) -> dict:
    """The volumetric figures logged as MLflow metrics (``volumetric.<block>.<figure>``)."""
    out = {f"volumetric.{b}.{k}": section[b][k]
           for b in _VOLUMETRIC_BLOCKS for k in (RMS_BEFORE, RMS_AFTER)}
    out.update({f"volumetric.iso_a3.{k}": section["iso_a3"][k]
                for k in _A3_RANGES if section["iso_a3"].get(k) is not None})
    return out
