"""The ``volumetric`` section of ``metrics.json`` (pure core: a fitted compensator on a
calibrated dataset in, the section and its figures' curves out)."""

from __future__ import annotations

import numpy as np

from ...core.scoring.evaluation import predict_split
from .calibration import flagged, true_parameters
from .series import distance_matrix
from .validation import volumetric_report


def true_changes(truth, cal, times: dict) -> tuple[dict | None, str | None]:
    """(campaign -> the true change of every parameter since the first cycle, None) from a
    simulation's truth, or (None, the first campaign the truth does not hold)."""
    out = {}
    for cid, t in times.items():
        P = true_parameters(truth, cid, cal.setup.model.names, len(t))
        if P is None:
            return None, cid
        out[cid] = P - P[:1]
    return out, None


def _chosen(est) -> dict:
    """The inputs and autoregression an ARX chose (its ``chosen_``); ``model=auto``'s kept
    estimator's, whose own ``chosen_`` names a family or a blend's weights (audit96: read as
    the ARX's, ``run model=auto`` on a volumetric dataset stopped, AttributeError); {} else."""
    chosen = getattr(est, "chosen_", None)
    if isinstance(chosen, dict) and {"n_inputs", "ar"} & set(chosen):
        return chosen
    inner = getattr(est, "estimator_", None)
    return _chosen(inner) if inner is not None and inner is not est else {}


def _models(comp) -> dict:
    """What each parameter's thermal model uses: inputs, autoregression."""
    models = {}
    for name, est in comp.estimators_.items():
        chosen = _chosen(est)
        models[name] = {"n_inputs": int(chosen.get("n_inputs", len(comp.selected_[name]))),
                        "ar": bool(chosen.get("ar", False))}
    return models


def split_series(comp, raw, ds, cal, calibration: dict, mode: str) -> dict:
    """Per test campaign: the identified and predicted parameter changes since the first cycle,
    the distance errors the calibration kept, and the times."""
    pairs = predict_split(comp, ds, "test", mode)
    series = {"changes": {}, "predicted": {}, "distances": {}, "times": {}}
    for cid, (_, pred) in pairs.items():
        P = ds.campaigns[cid][cal.names_].to_numpy(float)
        series["changes"][cid] = P - P[:1]
        Q = np.column_stack([pred[n].to_numpy(float) if n in pred else np.zeros(len(P))
                             for n in cal.names_])
        series["predicted"][cid] = Q - Q[:1]   # the model's change since the first cycle
        D = distance_matrix(raw.campaigns[cid], cal)
        # a distance the calibration left out (an outlier of its cycle, an excluded column) is
        # not a distance error: 1 mm mis-probed once made the RMS after 0.95 -> 4.96 µm
        D[flagged(calibration, cid, cal.design_.columns, len(D))] = np.nan
        series["distances"][cid] = D
        series["times"][cid] = ds.campaigns[cid]["time"].to_numpy(float)
    return series


def volumetric_section(comp, series: dict, cal, truth_changes: dict | None = None
                       ) -> tuple[dict, dict]:
    """(the ``volumetric`` section on the test split, the curves of its figures) from
    :func:`split_series`; ``truth_changes`` (:func:`true_changes`) scores VCE against the
    truth of a simulation instead of the identified parameters."""
    out, curves = volumetric_report(cal, series["distances"], series["changes"],
                                    series["predicted"], series["times"], _models(comp),
                                    truth_changes)
    # the intercepts the thermal models learnt and do not predict (the first cycle's error)
    out["offsets"] = {"mode": getattr(comp, "offsets", "predict"),
                      "dropped": dict(getattr(comp, "offsets_", {}))}
    return out, curves


def validate(comp, ds, raw, cal, calibration: dict, mode: str, truth: dict | None = None,
             truth_path=None) -> tuple[dict, dict]:
    """(the ``volumetric`` section, its figures' curves) of ``comp`` fitted on the parameter
    series ``ds`` identified from the distances ``raw`` by ``cal`` (``calibration``: its report,
    whose outliers the distance errors leave out); VCE against a simulation's ``truth`` where
    it holds every test campaign's series (said where it does not)."""
    from ...base.log import say

    say("volumetric validation: distances, VE/VCE, trajectories, ISO 10791-10 A.3")
    series = split_series(comp, raw, ds, cal, calibration, mode)
    changes, missing = (None, None) if truth is None else true_changes(truth, cal, series["times"])
    if missing is not None:
        say(f"{truth_path} does not hold campaign {missing}'s parameter series: VCE against the "
            "identified parameters")
    return volumetric_section(comp, series, cal, changes)
