r"""Validation of the volumetric thermal twin on held-out campaigns (paper 000, Sects. 2.3-4.4).

Everything is in the first-cycle frame of each campaign, as the thermal model predicts it:
:math:`\Delta p(t)` is the change of the identified parameters since the campaign's first
cycle, :math:`\Delta\hat p(t)` the thermal model's prediction of it.  Then

* distance errors: before :math:`\Delta d(t)`, after :math:`\Delta d(t) - A\,\Delta\hat p(t)`
  (every measured distance of every cycle), RMS and P2P;
* VE/VCE on a 3D grid of commands (paper 001, Eqs. 4 and 7, in the thermal frame): before the
  TCP error of :math:`\Delta p`, after that of :math:`\Delta p - \Delta\hat p`, RMS over grid
  points and cycles;
* TCP error along three mid-range trajectories, one per axis: per error direction, the
  E_P95(σ) curve (the 95th percentile of the error's standard deviation over every window of
  each length, pooled over the trajectory's points) before and after;
* the ISO 10791-10 A.3 virtual test on the axial (Z) error where its test piece sits, on the
  table (X and Y mid-range, Z at the bottom of its travel), started at every cycle: the slot
  range before/after, mean and max;
* per parameter (the paper's Table 1): P2P and RMS before, their reduction after, the number
  of inputs and whether the autoregressive term was kept.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ...core.metrics import (
    P2P_AFTER,
    P2P_BEFORE,
    P2P_REDUCTION,
    RMS_AFTER,
    RMS_BEFORE,
    RMS_REDUCTION,
    e_p95,
    p2p,
    reduction_pct,
    window_lengths,
)
from ...core.scoring.iso10791 import a3_report
from ...core.timerule import median_step
from .identify import ArtefactCalibration
from .kinematics import AXES, workspace_grid

GRID = (20, 8, 8)
TRAJECTORY_POINTS = 21
A3_POINT = (0.5, 0.5, 0.0)      # the A.3 test piece: fractions of the X, Y, Z travel


def trajectory(model, axis: str, n: int = TRAJECTORY_POINTS) -> np.ndarray:
    """(n, 3) commands along ``axis`` through the middle of the other two ranges."""
    mid = np.array([0.5 * sum(model.ranges[a]) for a in AXES])
    out = np.tile(mid, (n, 1))
    out[:, AXES.index(axis)] = np.linspace(*model.ranges[axis], n)
    return out


def _finite(x) -> np.ndarray:
    x = np.ravel(np.asarray(x, float))
    return x[np.isfinite(x)]


def _rms(x) -> float:
    x = _finite(x)
    return float(np.sqrt(np.mean(x ** 2))) if x.size else float("nan")


def _pair(before, after) -> dict:
    b, a = _rms(before), _rms(after)
    return {RMS_BEFORE: b, RMS_AFTER: a, RMS_REDUCTION: reduction_pct(b, a),
            P2P_BEFORE: p2p(_finite(before)), P2P_AFTER: p2p(_finite(after))}


def volumetric_report(cal: ArtefactCalibration, distances: Mapping[str, np.ndarray],
                      changes: Mapping[str, np.ndarray], predicted: Mapping[str, np.ndarray],
                      times: Mapping[str, np.ndarray], models: Mapping[str, dict],
                      truth: Mapping[str, np.ndarray] | None = None, grid_shape=GRID,
                      max_points: int | None = 60) -> tuple[dict, dict]:
    """``(the metrics.json "volumetric" section, curves for the figures)``.

    Parameters
    ----------
    cal : fitted ArtefactCalibration (its ``names_`` are the parameter columns)
    distances : campaign -> (n, m) measured distance deviations (µm, absolute; NaN: not measured
        or left out), each taken from its first cycle measured
    changes, predicted : campaign -> (n, k) identified parameter change since the first cycle,
        and the thermal model's prediction of it (0 where a parameter is not modelled)
    times : campaign -> (n,) s since the campaign start
    models : parameter -> {"n_inputs": int, "ar": bool} of its thermal model
    truth : campaign -> (n, p) change of every model parameter since the first cycle, when the
        data were simulated: the TCP figures (VE/VCE, trajectories, A.3) are then those of the
        true machine (paper 001, Eq. 7) rather than of the identified parameters, whose
        identification noise they would otherwise include.
    """
    model = cal.setup.model
    ids = list(changes)
    identified = {c: cal.full(changes[c]) for c in ids}
    compensation = {c: cal.full(predicted[c]) for c in ids}
    full = dict(truth) if truth is not None else identified
    resid = {c: full[c] - compensation[c] for c in ids}

    d_before, d_after = {}, {}
    for c in ids:      # each distance from its first cycle measured (NaN: left out or not measured)
        D = distances[c]
        first = np.argmax(np.isfinite(D), axis=0)
        residual = D - cal.predict(predicted[c])
        cols = np.arange(D.shape[1])
        d_before[c] = D - D[first, cols]
        d_after[c] = residual - residual[first, cols]
    out = {"reference": "truth" if truth is not None else "identified",
           "campaigns": ids, "n_cycles": int(sum(len(times[c]) for c in ids)),
           "distance_error": _pair(np.concatenate([d_before[c] for c in ids]),
                                   np.concatenate([d_after[c] for c in ids]))}

    basis = model.basis(workspace_grid(model, grid_shape))                         # (g, 3, p)
    ve = np.concatenate([np.linalg.norm(basis @ full[c].T, axis=1).T for c in ids])     # (t, g)
    vce = np.concatenate([np.linalg.norm(basis @ resid[c].T, axis=1).T for c in ids])
    out["vce"] = {**_pair(ve, vce), "grid": list(grid_shape)}
    if truth is not None:      # what a measured dataset would report: noise of identification in
        ve_i = np.concatenate([np.linalg.norm(basis @ identified[c].T, axis=1).T for c in ids])
        vce_i = np.concatenate([np.linalg.norm(basis @ (identified[c] - compensation[c]).T,
                                               axis=1).T for c in ids])
        out["vce_identified"] = _pair(ve_i, vce_i)

    curves = {"trajectories": {}, "iso_a3": None}
    out["trajectories"] = {}
    period = median_step([times[c] for c in ids]) or float("nan")
    longest = max(len(times[c]) for c in ids)
    lengths = window_lengths(longest, max_points)
    for axis in AXES:
        tb = model.basis(trajectory(model, axis))                          # (s, 3, p)
        entry = {}
        for k, direction in enumerate(AXES):
            before = [tb[:, k] @ full[c].T for c in ids]                   # (s, t) per campaign
            after = [tb[:, k] @ resid[c].T for c in ids]
            eb = e_p95([row for b in before for row in b], lengths, "std")
            ea = e_p95([row for a in after for row in a], lengths, "std")
            entry[f"E_{direction}"] = {
                "window_s": (period * (lengths - 1)).tolist(), "before": eb.tolist(),
                "after": ea.tolist(),
                "whole_test_sigma_before": _rms([np.std(r) for b in before for r in b]),
                "whole_test_sigma_after": _rms([np.std(r) for a in after for r in a])}
        out["trajectories"][axis] = entry
    curves["trajectories"] = out["trajectories"]

    point = np.array([[lo + f * (hi - lo) for f, (lo, hi) in zip(A3_POINT, model.ranges.values())]])
    centre = model.basis(point)[:, 2]                                      # its Z error per parameter
    a3 = a3_report(dict(times), {c: (centre @ full[c].T)[0] for c in ids},
                   {c: (centre @ resid[c].T)[0] for c in ids}, keep_curves=True)
    summary = a3.get("summary")
    if summary:
        out["iso_a3"] = {"range_before": summary["range_before_mean"],
                         "range_after": summary["range_after_mean"],
                         "range_before_max": summary["range_before_max"],
                         "range_after_max": summary["range_after_max"],
                         "mean_reduction_pct": summary["mean_reduction_pct"],
                         "n_starts": summary["n_starts"], "direction": "Z",
                         "point_mm": point[0].tolist()}
        curves["iso_a3"] = {c: p["moving"] for c, p in a3["per_campaign"].items() if p["available"]}
    else:
        out["iso_a3"] = {"range_before": None, "range_after": None, "reason": a3.get("reason")}

    params = {}
    for j, name in enumerate(cal.names_):
        before = np.concatenate([changes[c][:, j] for c in ids])
        after = np.concatenate([changes[c][:, j] - predicted[c][:, j] for c in ids])
        rb, ra = _rms(before), _rms(after)
        params[name] = {"unit": model.parameters[cal.kept_[j]].unit,
                        P2P_BEFORE: p2p(before), RMS_BEFORE: rb, P2P_AFTER: p2p(after),
                        RMS_AFTER: ra, "reduction_pct": reduction_pct(rb, ra),
                        P2P_REDUCTION: reduction_pct(p2p(before), p2p(after)),
                        **models.get(name, {"n_inputs": 0, "ar": False})}
    out["parameters"] = params
    return out, curves


def headline_table(section: dict) -> str:
    """The printed headline of the ``volumetric`` section (what the per-parameter table above it
    does not say): distance errors, VCE and the A.3 range, before -> after, µm."""
    def row(label: str, block: dict | None, before=RMS_BEFORE, after=RMS_AFTER):
        if not block or block.get(before) is None:
            return None
        red = reduction_pct(block[before], block[after])
        return (f"{label:<58} {block[before]:>8.2f} -> {block[after]:>6.2f}  "
                + (f"{red:>8.1f}%" if red is not None else "      n/a"))

    truth = section.get("reference") == "truth"
    grid = " x ".join(map(str, section["vce"].get("grid", [])))
    a3 = section["iso_a3"]
    lines = [f"volumetric: test split, {section['n_cycles']} cycles, µm (RMS of the change since each "
             "campaign's first cycle)",
             f"{'':<58} {'before':>8} -> {'after':>6}  {'reduction':>9}", "-" * 96,
             row("distance errors", section["distance_error"]),
             row(f"VCE on a {grid} grid (against the "
                 f"{'simulated machine' if truth else 'identified parameters'})", section["vce"]),
             row("VCE against the identified parameters", section.get("vce_identified")),
             row("ISO 10791-10 A.3, Z on the table: mean slot range", a3, "range_before", "range_after"),
             row("ISO 10791-10 A.3: max slot range", a3, "range_before_max", "range_after_max")]
    if a3.get("range_before") is None:
        lines.append(f"ISO 10791-10 A.3: n/a ({a3.get('reason')})")
    return "\n".join(line for line in lines if line is not None)
