"""The candidate effects of one search round, and the random control signal.

Families (issue 6): ``signal`` -- every column the model does not use
(undeclared ``T_``/``S_`` columns, declared sensors the selector dropped), raw
and through first-order lags; ``dynamics`` -- low-pass copies of the model
inputs (unmeasured masses, delays, the AR pole), all together (optionally with
the transient of the campaign's initial disequilibrium) or one at a time; ``ambient_interval`` -- the
inputs times the initial ambient (linear, or a step at a threshold between
the train campaigns' ambients); ``interaction`` -- products of a state signal
and a temperature, and of a state and the rises of all the inputs; ``nonlinear`` --
squares of the strongest inputs.

A state signal (``S_`` column) is tried in both frames: absolute and as its
change since the campaign's first sample (like the error with
``reference=first_sample``), raw, lagged, and times the rise of every
temperature -- whichever the data's reference is: an axis that dwells away
from its home position tilts the tool through the lever :math:`p - p(0)`,
a spindle speed acts through its absolute value.  (``sensor_fault``,
removing a declared sensor whose self-prediction jumps, is weighed before the
search for all targets at once: :func:`thermocomp.apps.diagnose.search.sensor_health`.)

The control is a random walk, independent per campaign, with no physical
effect on anything: it goes through the same transforms as a real signal and
must never clear the bar.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ...core.io.contract import is_ambient
from .features import Effect, spanned_directions

CONTROL = "control:random_walk"


@dataclass
class CandidateOptions:
    """What the candidate families contain."""

    taus_s: tuple = (900.0, 1800.0, 3600.0, 7200.0, 14400.0)
    n_squares: int = 3
    fault_ratio: float = 3.0
    families: tuple = ("signal", "dynamics", "ambient_interval", "interaction", "nonlinear",
                       "sensor_fault")
    min_units_per_side: int = 2
    initial_directions: tuple = (2, 3)   # lags also tried from the initial state, k directions
    extra_columns: list = field(default_factory=list)   # more context columns to try as signals


def random_walk(campaigns: np.ndarray, seed: int = 0) -> np.ndarray:
    """A standard random walk per campaign (starts at 0), seeded: the control signal."""
    rng = np.random.default_rng(seed)
    steps = rng.standard_normal(len(campaigns))
    out = np.empty(len(campaigns))
    campaigns = np.asarray(campaigns, dtype=object)
    for cid in dict.fromkeys(campaigns):
        rows = np.flatnonzero(campaigns == cid)
        walk = np.cumsum(steps[rows])
        out[rows] = walk - walk[0]
    return out


def _varies(values: np.ndarray) -> bool:
    return bool(np.nanstd(values) > 1e-12)


def _start_varies(problem, column: str) -> bool:
    """True when ``column``'s first valid value differs between the train campaigns.

    Otherwise its absolute and referenced frames differ by one constant, and
    so do their lags: one candidate, not two (a single record included).
    """
    first = pd.Series(problem.context[column].to_numpy(float)).groupby(
        np.asarray(problem.campaigns, dtype=object), sort=False).first()
    return first.nunique() > 1


def ambient_thresholds(ambient_by_unit: pd.Series, min_per_side: int) -> list[float]:
    """Midpoints between consecutive campaign ambients with enough campaigns on each side."""
    a = np.sort(ambient_by_unit.dropna().to_numpy(float))
    out = []
    for i in range(min_per_side - 1, len(a) - min_per_side):
        if a[i + 1] - a[i] > 1e-6:
            out.append(round(float((a[i] + a[i + 1]) / 2), 2))
    return sorted(set(out))


def candidates(problem, model_inputs: list[str], excluded: set, accepted: list[Effect],
               options: CandidateOptions, used: set = frozenset()) -> list[Effect]:
    """Every candidate effect of one round, the control included (sensor faults are found
    before the search, :func:`thermocomp.apps.diagnose.search.sensor_health`).  ``used``: columns
    the estimator reads beside ``model_inputs`` (an ARX+RF's state column): like the inputs,
    they are no ``signal`` (CLI.md: a column the model did not use); a declared ``S_`` input's
    lags are tried as ``dynamics``."""
    ctx, fam = problem.context, set(options.families)
    taus = [float(t) for t in options.taus_s]
    out: list[Effect] = []
    t_cols = [c for c in ctx.columns if c.startswith("T_") and c not in excluded]
    s_cols = [c for c in ctx.columns if c.startswith("S_") and c not in excluded]
    s_cols += [c for c in options.extra_columns if c in ctx.columns and c not in s_cols]
    s_cols = [c for c in s_cols if problem.varies(c)]
    unused_t = [c for c in t_cols if c not in model_inputs and problem.varies(c)]

    # the frame of a state other than the data's (the data's own is the legacy frame=None)
    other_frame = "absolute" if problem.reference == "first_sample" else "referenced"

    def signal_family(col: str, frame: str | None = None) -> list[Effect]:
        return [Effect("signal", "raw", col, frame=frame)] + [
            Effect("signal", "first_order_lag", col, tau_s=t, frame=frame) for t in taus]
    if "signal" in fam:
        unused_s = [c for c in s_cols if c not in model_inputs and c not in used]
        for col in unused_t + unused_s:
            out += signal_family(col)
        for col in unused_s:
            if _start_varies(problem, col):
                out += signal_family(col, other_frame)
    if "dynamics" in fam:
        temps_in = tuple(c for c in model_inputs if c.startswith("T_"))
        field_temps = tuple(c for c in temps_in if not (c == "T_amb" or c.startswith("T_amb_")))
        n_campaigns = len(dict.fromkeys(problem.campaigns))
        # a lag from the initial state only where the campaigns start in different states: where
        # not even the first direction of their initial distances is spanned beyond the sensors'
        # noise (a room that soaks the machine at each run's level) the block has no state to read
        # and fits one level per campaign by chance (diag107c: climate_lag 10123 E_X +28.8 %)
        wanted = [int(k) for k in options.initial_directions
                  if 1 <= k <= len(field_temps) and n_campaigns >= k + 3]
        if wanted and not spanned_directions(ctx, field_temps, problem.campaigns, 1):
            wanted = []
        starts = [{}] + [{"initial_state": field_temps, "initial_directions": k} for k in wanted]
        states_in = [c for c in model_inputs if c.startswith("S_") and c in s_cols]
        for t in taus:
            out += [Effect("dynamics", "lowpass_inputs", tau_s=t, **st) for st in starts]
            out += [Effect("dynamics", "first_order_lag", c, tau_s=t, **st)
                    for c in temps_in for st in starts]
            out += [Effect("dynamics", "first_order_lag", c, tau_s=t) for c in states_in]
    if "ambient_interval" in fam and "ambient_c0" in ctx and np.isfinite(ctx["ambient_c0"]).all():
        by_unit = ctx["ambient_c0"].groupby(problem.units, sort=False).first()
        if by_unit.nunique() >= 2 * options.min_units_per_side:
            out.append(Effect("ambient_interval", "ambient_linear"))
            # the room's level law leanly (diag106e): one regressor, for where the law of every input
            # saturates the campaigns and so can never be taken, yet vetoes or buries real effects;
            # elsewhere Search.run drops them (diag107: Search._bank_untestable)
            out.append(Effect("ambient_interval", "ambient_mean"))
            out.append(Effect("ambient_interval", "ambient_scaled"))
            out += [Effect("ambient_interval", "ambient_step", threshold_c=thr)
                    for thr in ambient_thresholds(by_unit, options.min_units_per_side)]
    if "interaction" in fam:
        temps = [c for c in model_inputs if c.startswith("T_")] + unused_t
        out += [Effect("interaction", "product", s, other=t) for s in s_cols for t in temps]
        # the state, referenced and absolute, times a temperature rise (with reference=first_sample
        # the referenced one is the legacy product; the absolute one differs from the referenced
        # one by S(0) times the rise, the same candidate when S(0) is the same in every campaign)
        for s in s_cols:
            frames = ([] if problem.reference == "first_sample" else ["referenced"]) + (
                ["absolute"] if _start_varies(problem, s) else [])
            out += [Effect("interaction", "product", s, other=t, frame=f) for f in frames for t in temps]
        # the state's change times a temperature's rise over the air's (each ambient sensor's): a
        # tilt is a structure's gradient, one face held by the air, which no sensor's rise alone
        # reads; through the lever p - p(0) only, one product per sensor; the search keeps them
        # only where the bank below cannot be tested (Search._bank_untestable, planted72)
        airs = [c for c in temps if is_ambient(c)]
        lever = None if problem.reference == "first_sample" else "referenced"
        out += [Effect("interaction", "product", s, other=t, frame=lever, over=a)
                for s in s_cols for a in airs for t in temps if not is_ambient(t)]
        # the state times the rise of every model input at once (its lever on each structure's
        # growth): a law of two sensors' rises times a position is no single product
        out += [Effect("interaction", "inputs_product", s, frame=f) for s in s_cols
                for f in ["referenced"] + (["absolute"] if _start_varies(problem, s) else [])]
    if "nonlinear" in fam and options.n_squares > 0:
        X = problem.X[model_inputs].to_numpy(float)[problem.measured]
        y = problem.y[problem.measured]
        corr = np.abs([np.corrcoef(X[:, j], y)[0, 1] if _varies(X[:, j]) else 0.0
                       for j in range(X.shape[1])])
        strongest = [model_inputs[j] for j in np.argsort(-np.nan_to_num(corr))[:options.n_squares]]
        out += [Effect("nonlinear", "square", c) for c in strongest if c.startswith("T_")]
    out += signal_family(CONTROL)
    done = set(accepted)
    return [e for e in dict.fromkeys(out) if e not in done]
