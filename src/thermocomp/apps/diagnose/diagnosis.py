"""``diagnose``: the whole closed loop on a dataset, and its result in the layout of ``diagnosis.json``."""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np
from sklearn.base import clone
from threadpoolctl import threadpool_limits

from ...base.jsonsafe import json_safe
from ...base.log import logger
from ...core.compensator import Compensator, with_chosen_hyperparameters
from ...core.continuation import fit_campaigns, fit_joined
from ...core.denoise import denoise_campaigns
from ...core.first_probe import completed, late_starts
from ...core.frame import stack
from ...core.io.contract import ContractError, Dataset
from ...core.metrics import P2P_AFTER, split_scores
from ...core.model_selection import ForwardChaining, LeaveCampaignsOut, cv_scheme, forward_gap, unit_labels
from ...core.model_selection.blocks import decorrelation_length
from ...core.scoring.evaluation import require_split, sample_period, split_residuals
from ...core.scoring.results import TEST_RMSE, TEST_RSD_MEAN, TEST_RSD_SD, Scores, TargetResult
from ...core.timerule import median_step
from .augmented import AugmentedRegressor
from .candidates import CONTROL, random_walk
from .cv import Problem, smallest_p, units_needed
from .deployed import deployed_scores
from .features import Effect
from .search import Search, SearchOptions, SearchResult, sensor_health
from .sensors import self_prediction


def augment(template: Compensator, effects: Mapping[str, list], excluded=(),
            inputs=None, alphas: Mapping[str, float | None] | None = None) -> Compensator:
    """An unfitted copy of ``template`` whose estimator adds ``effects`` (per target).

    ``excluded`` sensors (accepted ``sensor_fault``) leave the declared inputs:
    ``inputs`` (the resolved input columns, default ``template.inputs_``)
    without them become the explicit input list.  ``alphas``: per target, the
    penalty on the effect features (MLR base, chosen by the CV).
    """
    base_inputs = list(inputs) if inputs is not None else list(getattr(template, "inputs_", []))
    kept = [c for c in base_inputs if c not in set(excluded)] if excluded else template.inputs
    est = AugmentedRegressor(template.estimator,
                             {t: [Effect.to_dict(e) if isinstance(e, Effect) else dict(e) for e in es]
                              for t, es in effects.items()},
                             template.reference,
                             {t: a for t, a in (alphas or {}).items() if a} or None)
    return clone(template).set_params(estimator=est, inputs=kept)


@dataclass
class TargetDiagnosis:
    """Everything found for one target."""

    target: str
    search: SearchResult
    original_cv_rmse: float
    final_cv_rmse: float
    before: dict             # test-split scores of the original model (metrics.json layout)
    after: dict              # ... of the diagnosed model
    # the same in batch, as ``run`` scores it, where ``before``/``after`` are the deployed
    # stream's (:mod:`.deployed`); None where they are the batch ones
    before_as_run: dict | None = None
    after_as_run: dict | None = None

    @property
    def accepted(self):
        return self.search.accepted


@dataclass
class Diagnosis:
    """Result of :func:`diagnose`: per target, plus the fitted models before and after."""

    model: str
    dataset: str
    mode: str
    targets: dict                      # target -> TargetDiagnosis
    excluded: list
    before_model: Compensator
    after_model: Compensator
    predictions: dict                  # "before"/"after" -> {campaign: (measured, predicted)}
    options: SearchOptions
    cv: dict
    seconds: float = 0.0
    test_sensors: list = field(default_factory=list)   # broken in the test split: said, not acted on
    ati: str = "none"                  # the ATI wrapper around ``model`` (``cmeans``), or none
    # how the test figures were scored: "deployed" (streamed, envelope on), else "batch" (why)
    scored: str = "batch"
    clamped: dict = field(default_factory=dict)        # "before"/"after" -> test rows clamped
    # "before"/"after" -> {target: test rows whose correction the guard changed}
    guarded: dict = field(default_factory=dict)

    @property
    def primary(self) -> str:
        """The target with the largest CV RMSE before (the one the machine suffers most from)."""
        return max(self.targets, key=lambda t: self.targets[t].original_cv_rmse)

    def effects(self) -> dict[str, list[Effect]]:
        return {t: d.search.effects for t, d in self.targets.items()}

    def to_json(self, target: str | None = None) -> dict:
        """``diagnosis.json`` of one target (CLI.md keys first, then the extras)."""
        t = target or self.primary
        d = self.targets[t]
        s = d.search
        last = s.rounds[-1] if s.rounds else None
        # the random-walk control is no effect (CLI.md: a `signal` is a column the model did not
        # use): it is reported apart, under `control`
        rejected = [ev for ev in (last.evaluated if last else []) if not ev.accepted and not ev.control]
        effects = [ev.entry() | {"step": i + 1} for i, ev in enumerate(s.accepted)]
        effects += [ev.entry() for ev in rejected]
        control = last.control.entry() if last and last.control else None
        te_b, te_a = TargetResult(d.before).test, TargetResult(d.after).test
        return json_safe({
            "target": t,
            "model": self.model,
            "before": _summary(te_b, d.original_cv_rmse) | self._as_run(d.before_as_run, "before", t),
            "effects": effects,
            "after": _summary(te_a, d.final_cv_rmse) | self._as_run(d.after_as_run, "after", t),
            "dataset": self.dataset,
            "mode": self.mode,
            "ati": self.ati,
            "test_scored": self.scored,
            "test_rmse_after_pct_of_before": (100.0 * te_a.rmse / te_b.rmse
                                              if te_b.rmse > 0 else None),
            "steps": [{"step": 0, "effect": None, "cv_rmse": d.original_cv_rmse}]
                     + [dict(step=i + 1, **st) for i, st in enumerate(s.steps)],
            "excluded_inputs": list(self.excluded),
            "control": control,
            "control_ever_clears_bar": any(r.control is not None and r.control.clears_bar
                                           for r in s.rounds),
            "bar": {"min_gain_pct": self.options.min_gain_pct, "alpha": self.options.alpha,
                    "test": "one-sided sign flip of the test blocks' CV MSE gains (signed ranks "
                            "of blocks finer than the CV units, else shares of each unit's MSE), "
                            "family-wise over the round (step-down max-T); a gain where no fold "
                            "extrapolates and, with ranks, a positive 95 % lower bound of the gain",
                    "min_p": self.cv["min_p"],
                    "max_effects": self.options.max_effects},
            "cv": self.cv,
            "test_e_p95": {"statistic": te_b.e_p95["statistic"],
                           "window_s": te_b.e_p95["window_s"],
                           "measured": te_b.e_p95["before"],
                           "before": te_b.e_p95["after"],
                           "after": te_a.e_p95["after"]},
            "self_prediction": [
                {"sensor": name, "cv_rmse_c": float(r["cv_rmse"]), "worst_unit": r["worst_unit"],
                 "worst_unit_split": "test" if r["worst_unit"] in self.cv["test_campaigns"] else "train",
                 "worst_unit_rmse_c": float(r["worst_unit_rmse"]),
                 "cross_ratio": float(r["cross_ratio"]), "own_ratio": float(r["own_ratio"]),
                 "jump_ratio": float(r["jump_ratio"])}
                for name, r in s.self_prediction.iterrows()],
            "test_sensor_warnings": self.test_sensors,
            "rounds": [r.to_dict() for r in s.rounds],
            "other_targets": {o: {"before_test_rmse": TargetResult(x.before).test.rmse,
                                  "after_test_rmse": TargetResult(x.after).test.rmse,
                                  "accepted": [ev.effect.title for ev in x.accepted]}
                              for o, x in self.targets.items() if o != t},
            "seconds": self.seconds,
        })


    def _as_run(self, as_run: dict | None, which: str, target: str) -> dict:
        """The batch test RMSE (``thermocomp run``'s of the written config), the test rows the
        deployed stream clamped and those of ``target`` whose correction its guard changed,
        beside deployed figures (why the two differ)."""
        if as_run is None:
            return {}
        return {"test_rmse_as_run": TargetResult(as_run).test.rmse,
                "test_rows_clamped": self.clamped.get(which, 0),
                "test_rows_guarded": self.guarded.get(which, {}).get(target)}


def test_scores(comp: Compensator, ds: Dataset, ids, mode: str, statistic: str, points
                ) -> tuple[dict, dict]:
    """``{target: {"test": ...}}`` as :func:`thermocomp.core.scoring.evaluation.score` computes the test split
    (``metrics.json`` layout, without the ISO virtual test), and the predictions."""
    ids = list(ids)
    pred, meas, series = split_residuals(comp, ds, ids, mode)   # state carried over where it applies
    dt = sample_period(ds, ids)
    out = {t: {"test": split_scores(y, r, dt, statistic, points, with_before_after=True)}
           for t, (y, r) in series.items()}
    return out, {c: (meas[c], pred[c]) for c in ids}


def _in_frame(before: Compensator, m) -> dict[str, np.ndarray]:
    """``{target: label}`` of the stacked train rows ``m`` the search's CV fits and scores: as
    measured, but in the first-sample frame, where a campaign's first measurement comes after
    its first row, completed by ``before``'s own estimate of the unmeasured drift before it, as
    the compensator itself was fitted (:mod:`thermocomp.core.first_probe`)."""
    Y = m.Y[before.targets_].to_numpy(float)
    if before.reference == "first_sample" and late_starts(Y, m.groups):
        Y = completed(Y, before.predict_stacked(m), m.groups, from_start=True)
    return {t: Y[:, k] for k, t in enumerate(before.targets_)}


def _summary(test: Scores, cv_rmse: float) -> dict:
    return {TEST_RMSE: test.rmse, "cv_rmse": cv_rmse,
            TEST_RSD_MEAN: test.rsd_mean, TEST_RSD_SD: test.rsd_sd,
            "test_rms_measured": test.rms_before, "test_p2p_residual": test.get(P2P_AFTER)}


def diagnose(ds: Dataset, compensator: Compensator, targets=None, mode: str = "simulation",
             options: SearchOptions | None = None,
             make_compensator: Callable[[dict, list, list], Compensator] | None = None,
             e_p95_statistic: str = "range", e_p95_points: int | None = 200,
             model_name: str = "", ati: str = "none",
             deployed_of: Callable[[Compensator, dict, list], dict] | None = None) -> Diagnosis:
    """Find what ``compensator`` misses on the train split, fix it, report before/after on test.

    Parameters
    ----------
    ds : Dataset
        Needs ``train`` and ``test`` campaigns; ``val`` campaigns are ignored.
    compensator : Compensator
        The configured model (unfitted template; it is not modified).
    targets : list of str, optional
        ``E_`` columns to diagnose (default: every target of the model), in
        order; a sensor found faulty for one stays out for the next ones.
    mode : {'simulation', 'one_step'}
    options : SearchOptions
    make_compensator : callable, optional
        ``(effects: dict target -> list[Effect], excluded: list[str],
        inputs: list[str], alphas: dict target -> float or None) -> Compensator``,
        the diagnosed model, given the resolved declared inputs and the
        penalties on the effect features (default :func:`augment` of the template;
        the ``diagnose`` stage builds it from the config it writes, so
        ``thermocomp run`` with that config gives the same "after").
    model_name, ati : str, optional
        What ``diagnosis.json`` names the model (``mlr``) and the ATI wrapper around it
        (``cmeans``; ``none``).
    deployed_of : callable, optional
        ``(fitted compensator, train campaigns, test ids) -> figures``: ``promote``'s own "as
        deployed" test figures of the model (:func:`.deployed.deployed_scores`).  Given (and
        ``mode='simulation'``), "before" and "after" are the test figures of the models so
        deployed, the batch ones kept as ``*_as_run``; a model that cannot be streamed keeps
        its batch figures (said).

    Returns
    -------
    Diagnosis
    """
    # The matrices are ~10-40 columns wide: BLAS threads only add contention (several times
    # slower on a busy machine), so the whole loop runs single-threaded.
    with threadpool_limits(limits=1, user_api="blas"):
        return _diagnose(ds, compensator, targets, mode, options or SearchOptions(),
                         make_compensator, e_p95_statistic, e_p95_points, model_name, ati,
                         deployed_of)


def test_sensor_warnings(search: Search, excluded, later, options: SearchOptions) -> list[dict]:
    """Sensors whose self-prediction breaks only in the test split's temperatures (never its
    errors): said, and left in.  Acting on them would let the test split choose the model
    (and flatter its "after"); a deployed compensator meets such a sensor with ``monitor``,
    which excludes it online."""
    tol = options.candidates.fault_ratio
    if later is None or not len(later.X):
        return []
    table = self_prediction(search.problem, search.inputs(excluded), later.X, later.groups, tol)
    test_ids = set(np.asarray(later.groups, dtype=object))
    out = [{"sensor": name, "campaign": r["worst_unit"], "rmse_c": float(r["worst_unit_rmse"]),
            "jump_ratio": float(r["jump_ratio"]), "acted_on": False}
           for name, r in table.iterrows() if r["jump_ratio"] >= tol and r["worst_unit"] in test_ids]
    for w in out:
        logger.warning(f"diagnose: sensor {w['sensor']} breaks from its neighbours in test campaign "
                       f"{w['campaign']} (self-prediction {w['rmse_c']:.2g} °C, jump ratio "
                       f"{w['jump_ratio']:.1f}); left in: the search never sees the test split "
                       "(`thermocomp monitor` excludes such a sensor online)")
    return out


def _gap(context, groups, options: SearchOptions) -> int:
    """Forward chaining's gap: the longest lag tried in samples, capped at half a block."""
    t = context["time"].to_numpy(float)
    dt = median_step(t, groups) or 1.0
    taus = [float(x) for x in options.candidates.taus_s] or [0.0]
    block = ForwardChaining(options.n_blocks, min_train_fraction=options.min_train_fraction) \
        .block_size(len(t))
    return forward_gap(max(taus) / dt, block)


def _design(scheme, m, labels, context, before, compensator, targets, mode, options):
    """``(searches, start results, gap)`` of ``scheme`` with the test's blocks set: each target's
    as long as its own residual takes to decorrelate; the deployed penalty's standard error over
    the slowest target's (one length for every target, as before diag82)."""
    units = unit_labels(m.groups, options.n_blocks) if scheme == "campaigns" else m.groups
    gap = _gap(m.context, m.groups, options) if scheme == "forward" else 0
    # every fold fits at the choices the deployed base made on all train rows (diag74), so a
    # candidate gains by what it adds, not by moving the base's own choices (Search's docstring)
    estimator = with_chosen_hyperparameters(compensator, before).estimator
    searches = {t: Search(Problem(m.X, labels[t], context, m.groups, units, t, mode,
                                  before.reference, options.n_folds, scheme, options.n_blocks, gap,
                                  options.min_train_fraction),
                          estimator, compensator.selector, before.inputs_, options)
                for t in targets}
    start = {t: s.cv.run(s.inputs([]), []) for t, s in searches.items()}
    # (an error measured on 1 row in N: its measured series at its own spacing, the length in
    # measured samples; each test block then holds that many measurements)
    # each target on blocks as long as its own residual takes to decorrelate (diag81b): the
    # family-wise test is per target and round, and a block's gain is that target's residuals
    length = {t: decorrelation_length(r.residual, m.groups, searches[t].problem.validated,
                                      searches[t].problem.held_out)
              for t, r in start.items()}
    # the deployed penalty's one-SE rule reads squared errors, whose blocks stay dependent where
    # a fast residual is not (the gantry's E_Z_error: 5040 one-sample blocks shrank its standard
    # error 3x and the penalty, test +6.9 %; benchmarks/bench_diag82.py): the longest length
    for t, s in searches.items():
        s.problem.set_test_blocks(length[t], max(length.values()))
        start[t] = s.cv._result(start[t].prediction, start[t].alpha)   # scored on the blocks
    return searches, start, gap


def _blocks(design) -> int:
    """The fewest test blocks over the targets (the slowest target's: the design's reach)."""
    return min(s.problem.n_blocks_tested for s in design[0].values())


def _reach(design) -> float:
    """The smallest p ``design``'s test can give."""
    return smallest_p(_blocks(design))


@dataclass
class Searched:
    """What the search found on the train campaigns, and the design it tested on (``cv``)."""

    found: dict                        # target -> SearchResult
    original: dict                     # target -> the CV result of the model as it is
    excluded: list                     # sensors accepted as faulty
    searches: dict                     # target -> Search
    problem: Problem                   # the design's target of fewest test blocks
    scheme: str
    why: str | None
    gap: int
    designs: dict
    start_blocks: tuple
    reach: float
    n_train: int


def search_train(ds: Dataset, compensator: Compensator, options: SearchOptions | None = None,
                 mode: str = "simulation", train_ids=None, targets=None) -> Searched:
    """The closed loop's search on the train campaigns alone: what :func:`diagnose` finds and
    accepts (the same search and acceptance test), without a test split (nothing scored, no
    test sensor warnings).  ``train_ids``: default the train split of ``ds``; ``targets``:
    default every target of the model.  ``model=auto``'s
    ``diagnosed`` candidate is built from its accepted effects (``model.diagnosed``)."""
    with threadpool_limits(limits=1, user_api="blas"):
        ids = list(train_ids) if train_ids is not None else require_split(ds, "train")
        before = fit_joined(clone(compensator), ds, ids)
        return _search(ds, compensator, before, ids, list(targets or before.targets_), mode,
                       options or SearchOptions())


def _search(ds, compensator, before, train_ids, targets, mode, options) -> Searched:
    """The search of every target on the train campaigns ``train_ids`` (``before``: the
    template fitted on them)."""
    train = {c: ds.campaigns[c] for c in train_ids}
    if getattr(before, "denoiser_", None) is not None:
        train = denoise_campaigns(before.denoiser_, train, causal=False)
    # the search's CV sees the train split in the frame it was fitted in: a run of files that
    # continue one another is one campaign (one CV unit; one alone: forward chaining over it)
    train = fit_campaigns(ds, train, train_ids, before.reference)
    m = stack(train, before.inputs_, before.targets_, before.reference)
    context = m.context.copy()
    context[CONTROL] = random_walk(m.groups, options.seed)
    scheme, why, design, kept = cv_scheme(m.groups, options.cv), None, None, None
    need = units_needed(options.alpha)
    labels = _in_frame(before, m)

    def designed(name):
        return _design(name, m, labels, context, before, compensator, targets, mode, options)
    if options.cv == "auto" and scheme == "campaigns" and len(train) < need:
        # too few campaigns for the test to ever pass: validation blocks of the campaigns taken
        # as one time line instead, as for one long record -- unless that design cannot reach
        # alpha either while the test's time blocks within the campaigns can (cvpick69: the
        # block counts decide, never a candidate's statistic)
        few = (f"{len(train)} train campaigns are too few for the sign-flip test to reach "
               f"alpha={options.alpha:g} (it needs {need})")
        forward = designed("forward")
        kept = designed("campaigns") if _reach(forward) > options.alpha else None
        if kept is not None and _reach(kept) <= options.alpha:
            design = kept
            why = (f"forward chaining's {_blocks(forward)} test blocks cannot reach "
                   f"alpha={options.alpha:g} (min p {_reach(forward):.2g}) while {_blocks(kept)} "
                   f"time blocks within the {len(train)} train campaigns can (min p "
                   f"{_reach(kept):.2g}): the campaigns kept (held out whole, {few})")
            logger.info(f"diagnose: {why}")
        else:
            scheme, design, why = "forward", forward, few
            logger.info(f"diagnose: {why}: forward chaining over them, {options.n_blocks} blocks")
    searches, start, gap = design or designed(scheme)
    # the design's reach: the target of fewest test blocks (each target has its own, diag82)
    problem = min((s.problem for s in searches.values()), key=lambda p: p.n_blocks_tested)
    reach = smallest_p(problem.n_blocks_tested)
    # each target's starting design (its rounds re-cut their blocks on their residual, diag82f)
    designs = {t: {"test_blocks": s.problem.n_blocks_tested, "block_samples": s.problem.block_samples,
                   "min_p": smallest_p(s.problem.n_blocks_tested)} for t, s in searches.items()}
    if reach > options.alpha:
        # (stranger69: a grinder's 7 runs, 5 and 3 forward blocks; over the campaigns, blocks
        # within them, the planted effect was accepted at 0.01 on both records)
        advice = ("the record is short for its residual's memory (test blocks are as long as it "
                  "takes to decorrelate); try diagnose.cv=campaigns (time blocks within the "
                  "train campaigns as the test's units), or raise diagnose.alpha"
                  if scheme == "forward" and kept is None
                  else f"raise diagnose.alpha (the campaigns' {_blocks(kept)} time blocks cannot "
                       f"reach it either: min p {_reach(kept):.2g})"
                  if scheme == "forward"
                  else "raise diagnose.n_blocks or diagnose.alpha")
        # each target is tested on its own blocks: the warning says which of them it holds for
        # (fl_thermal: E_ch3's 6 blocks cannot reach 0.01, E_ch1 / E_ch2 / E_ch5's 12-19 can)
        short = [t for t, d in designs.items() if d["min_p"] > options.alpha]
        can = ", ".join(f"{t} {d['test_blocks']}" for t, d in designs.items() if t not in short)
        where = ("so no effect can be accepted" if not can else
                 f"so no effect can be accepted on {', '.join(short)} (the others, {can} test "
                 "blocks, can reach it)")
        logger.warning(f"diagnose: {problem.n_units} CV units ({scheme}) in "
                       f"{problem.n_blocks_tested} test blocks: the sign-flip test cannot reach "
                       f"alpha={options.alpha:g} (min p {reach:.2g}; it needs {need} blocks), "
                       f"{where}; {advice}")
    # sensor health on the train campaigns only: the search never sees the test split
    start_blocks = (problem.n_blocks_tested, problem.block_samples)
    excluded, faults, health, original, table = sensor_health(searches, options=options, start=start)
    found = {t: s.run(original[t], faults[t], health[t], table) for t, s in searches.items()}
    return Searched(found, original, excluded, searches, problem, scheme, why, gap, designs, start_blocks,
                    reach, len(train))


def _diagnose(ds, compensator, targets, mode, options, make_compensator, e_p95_statistic,
              e_p95_points, model_name, ati, deployed_of=None) -> Diagnosis:
    t0 = time.perf_counter()
    train_ids, test_ids = require_split(ds, "train"), require_split(ds, "test")
    # fitted as run fits it (train files that continue one another joined): "before" is the
    # run's test figure, "after" the rerun of the config written
    before = fit_joined(clone(compensator), ds, train_ids)
    before_scores, before_pred = test_scores(before, ds, test_ids, mode, e_p95_statistic,
                                             e_p95_points)
    targets = list(before.targets_) if targets is None else (
        [targets] if isinstance(targets, str) else list(targets))
    unknown = [t for t in targets if t not in before.targets_]
    if unknown:
        raise ContractError(f"diagnose.targets names no modelled target (have {before.targets_})",
                            column=",".join(unknown))
    s = _search(ds, compensator, before, train_ids, targets, mode, options)
    # the test split's temperatures (never its errors): sensor health on what the model will face
    test = {c: ds.campaigns[c] for c in test_ids}
    if getattr(before, "denoiser_", None) is not None:
        test = denoise_campaigns(before.denoiser_, test)
    later = stack(test, before.inputs_, [], before.reference)   # (the test targets stay out)
    found, original, excluded, problem = s.found, s.original, s.excluded, s.problem
    test_sensors = test_sensor_warnings(next(iter(s.searches.values())), excluded, later, options)
    effects = {t: r.effects for t, r in found.items()}
    alphas = {t: r.alpha for t, r in found.items()}
    build = make_compensator or (lambda eff, exc, inputs, al: augment(compensator, eff, exc, inputs, al))
    after = fit_joined(build(effects, excluded, list(before.inputs_), alphas), ds, train_ids)
    after_scores, after_pred = test_scores(after, ds, test_ids, mode, e_p95_statistic, e_p95_points)
    out = {t: TargetDiagnosis(t, r, original[t].rmse, r.final.rmse, before_scores[t], after_scores[t])
           for t, r in found.items()}
    scored, clamped, guarded = _deployed(out, {"before": before, "after": after}, ds, train_ids,
                                         test_ids, mode, deployed_of)
    if s.scheme == "forward":
        cv = {"scheme": "forward", "units": problem.n_units, "unit": "validation block",
              "folds": problem.n_units, "gap_samples": s.gap,
              "min_train_fraction": options.min_train_fraction}
    else:
        cv = {"scheme": "campaigns", "units": problem.n_units,
              "unit": "campaign" if s.n_train > 1 else "time block",
              "folds": LeaveCampaignsOut(options.n_folds).get_n_splits(groups=problem.units)}
    if s.why:
        cv["why"] = s.why
    cv |= {"test_blocks": s.start_blocks[0], "block_samples": s.start_blocks[1], "min_p": s.reach,
           # each target's own starting test blocks (their residuals' memory, diag82; each
           # round's own in its ``rounds``); the above: fewest
           "designs": s.designs,
           "in_range_share": float(problem.in_range[problem.validated].mean()),
           "mode": "simulation",   # the search scores what the machine runs, whatever ``mode`` is
           "shrink_alpha": {t: r.alpha for t, r in found.items()},
           # an error measured now and then: the held-out rows scored (measured), per target;
           # ``block_samples`` then counts measured samples
           "measured_rows": ({t: int(x.problem.validated.sum()) for t, x in s.searches.items()}
                             if any(x.problem.sparse for x in s.searches.values()) else None),
           "train_campaigns": train_ids, "test_campaigns": test_ids}
    return Diagnosis(model_name or type(compensator.estimator).__name__, ds.name, mode, out,
                     excluded, before, after, {"before": before_pred, "after": after_pred},
                     options, cv, time.perf_counter() - t0, test_sensors, ati, scored, clamped,
                     guarded)


def _deployed(out: dict, models: dict, ds, train_ids, test_ids, mode, deployed_of
              ) -> tuple[str, dict, dict]:
    """Put the deployed test figures of ``models`` (``{"before"|"after": fitted}``)
    in ``out``'s TargetDiagnosis, the batch ones kept as ``*_as_run``; ``(scored, clamped,
    guarded)``."""
    if deployed_of is None:
        return "batch", {}, {}
    if mode != "simulation":     # the stream runs in simulation: one_step's figures stay batch
        return f"batch (eval.mode={mode})", {}, {}
    train = {c: ds.campaigns[c] for c in train_ids}
    scores, clamped, guarded = {}, {}, {}
    try:
        for which, comp in models.items():
            scores[which], clamped[which], guarded[which] = deployed_scores(
                comp, test_ids, deployed_of, train)
    except ValueError as exc:    # a model without the streaming protocol: its batch figures
        logger.warning(f"diagnose: the test figures are run's (batch), not the deployed "
                       f"stream's: {exc}")
        return "batch (not streamed)", {}, {}
    for t, d in out.items():
        d.before_as_run, d.after_as_run = d.before, d.after
        d.before, d.after = scores["before"][t], scores["after"][t]
    if any(clamped.values()):
        logger.info(f"diagnose: the deployed stream clamps {clamped['after']} test row(s) to the "
                    "training envelope (promote.envelope); before/after are its figures, run's "
                    "batch ones are after.test_rmse_as_run")
    return "deployed", clamped, guarded
