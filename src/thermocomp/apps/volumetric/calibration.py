"""Artefact calibration of a whole volumetric dataset: every cycle's error parameters.

Reads a volumetric dataset as recorded (an empty cell is a distance not measured in that cycle),
checks every pose of the set-up has its distances, identifies every cycle
(:class:`~thermocomp.apps.volumetric.identify.ArtefactCalibration`), leaves out a distance column
flagged in most cycles, and gives the parameter series as a dataset with the report of
``calibration.json``.  Used by ``thermocomp calibrate`` and by ``run`` on a volumetric dataset.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pandas as pd

from ...base.errors import ConfigError, ContractError
from ...base.log import logger
from ...core import io
from .artefact import COLUMN, SETUP_FILE
from .identify import ArtefactCalibration, CycleError, equivalent_truth
from .series import check_columns, distance_matrix, load_setup

ALPHA = 1e-6      # of the chi-square test of the residuals' scatter against the uncertainties
SCATTER = 2.0     # and the factor in RMS it must be off by too, before a warning


def _kinds(setup) -> dict:
    return {p.name: p for p in setup.model.parameters}


FAINT = 100.0     # a parameter known per cycle to no better than this × the distance noise is not seen


def _require_seen(cal: ArtefactCalibration, setup, kinds) -> None:
    """A pose set that cannot see a parameter of a required kind is bad input: name both.  So is
    one that sees it only faintly (an outside probe's two bars in the XY plane at 10°: Z's
    straightness and squareness seen through the balls' 20 mm offsets alone, E_ZX1 to ±788 µm a
    cycle, and a 'compensated' VCE of 617 µm, exit 0): a rank test passes it, its standard
    uncertainty per cycle more than FAINT times the noise of one distance does not."""
    params = _kinds(setup)
    poses = ", ".join(p.name for p in setup.poses)
    fix = ("add poses (position sets S1 axes, S2 volume diagonals, S3 face diagonals) or "
           "calibrate.require_seen=[]")
    unseen = [n for n in cal.unidentifiable_ if params[n].kind in kinds]
    if unseen:
        what = ", ".join(f"{n} ({params[n].kind})" for n in unseen)
        raise ContractError(f"the poses {poses} cannot see {what}: {fix}", file=setup_path(cal))
    if cal.prior_sd is not None:        # a prior bounds every uncertainty: nothing is unseen
        return
    noise = math.hypot(setup.probing_um, setup.ball_um)
    faint = sorted(((u, n) for u, n in zip(cal.uncertainty_, cal.names_)
                    if params[n].kind in kinds and u > FAINT * noise), reverse=True)
    if faint:
        what = ", ".join(f"{n} ({params[n].kind}, ±{u:.3g} {params[n].unit})" for u, n in faint[:4])
        more = f" and {len(faint) - 4} more" if len(faint) > 4 else ""
        raise ContractError(f"the poses {poses} see {what}{more} only faintly: standard uncertainty "
                            f"per cycle over {FAINT:g} times the {noise:.2g} µm noise of a distance "
                            f"(probing and ball uncertainty_um); {fix}", file=setup_path(cal))


def prior_sd(model, prior: dict | None):
    """The calibration's prior standard deviations from ``calibrate.prior`` (a uniform range
    ``[-a, a]`` per kind, as ``design.ranges``), or None."""
    from .design import MachineFamily, kind

    if prior is None:
        return None
    check_prior_kinds(prior, {kind(p) for p in model.parameters})
    amplitudes = {k: v for k, v in dict(prior).items() if k != "decay"}
    return MachineFamily(model, amplitudes, float(dict(prior).get("decay", 0.3))).sd()


def check_prior_kinds(prior, needed) -> None:
    """``calibrate.prior`` gives a range for each kind in ``needed`` and no other kind."""
    from .kinematics import KINDS

    missing = [k for k in KINDS if k in needed and k not in prior]
    unknown = sorted(set(prior) - set(KINDS) - {"decay"})
    if missing or unknown:
        raise ConfigError(f"calibrate.prior needs a range for every kind of the machine's parameters: "
                          f"{'missing ' + str(missing) if missing else 'unknown ' + str(unknown)} "
                          f"(kinds {list(KINDS)}, and decay)")


_FITTED: dict[tuple, ArtefactCalibration] = {}
_KEPT = 2        # set-ups (33 MB each at 1430 distances): a process calibrates one or two


def fitted(setup, outlier_z: float, prior_sd=None) -> ArtefactCalibration:
    """``ArtefactCalibration(setup, outlier_z, prior_sd).fit()``, fitted once per set-up in a
    process (its design, factor and identifiability: 0.1 s for 1430 distances): ``run`` fits
    it to identify the cycles and again to evaluate against the distances."""
    key = (json.dumps(setup.to_dict(), sort_keys=True), float(outlier_z),
           None if prior_sd is None else tuple(np.asarray(prior_sd, float).ravel()))
    if key not in _FITTED:
        cal = ArtefactCalibration(setup, outlier_z=float(outlier_z), prior_sd=prior_sd).fit()
        while len(_FITTED) >= _KEPT:
            _FITTED.pop(next(iter(_FITTED)))
        _FITTED[key] = cal
    return _FITTED[key].copy()


def setup_path(cal) -> str:
    return getattr(cal, "source_", SETUP_FILE)


def _identify(cal, ds, distances, skipped, excluded=()):
    """Per campaign ``(P, flagged)`` of its ``distances``, the columns in ``excluded`` left out of
    every cycle (``skipped``: campaign -> rows trimmed at its start, for the rows named)."""
    cols = cal.design_.columns
    out = {}
    for cid in ds.campaigns:
        D = distances[cid]
        if excluded:
            D = D.copy()
            D[:, [cols.index(c) for c in excluded]] = np.nan
        try:
            out[cid] = cal.identify(D)
        except CycleError as exc:
            if exc.missing == exc.total and not excluded:      # a row of temperatures alone
                raise ContractError(f"campaign {cid}: 0 of the {exc.total} distances measured in "
                                    "this cycle (every E_ cell of the row empty): a cycle not "
                                    "measured identifies nothing; drop the row", file=ds.file_path(cid),
                                    row=skipped[cid] + exc.cycle + 1) from None
            raise ContractError(f"campaign {cid}: {exc.total - exc.missing} of the {exc.total} distances "
                                "measured in this cycle (the others empty"
                                f"{' or excluded' if excluded else ''}), with any outliers left out, "
                                f"cannot identify the parameters{f' ({exc.why})' if exc.why else ''}: "
                                "measure its poses again or drop the row",
                                file=ds.file_path(cid),
                                row=skipped[cid] + exc.cycle + 1) from None
    return out


def _without_a_cut_cycle(cal, ds, distances, skipped) -> dict:
    """Each campaign's last cycle, where some of its distances are empty and those measured
    cannot identify the parameters, left out of ``ds`` and ``distances`` with a warning naming
    its file and row: a lab's export cut by the end of logging while a cycle was measured
    (leftovers67: refused whole, "measure its poses again or drop the row").  A cycle so
    measured before a campaign's last is still refused (:func:`_identify`): a measurement
    that went wrong mid-record is for the lab to look at.  ``{campaign: {"row", "measured",
    "of"}}`` of the cycles left out."""
    cut = {}
    for cid, df in list(ds.campaigns.items()):
        last = distances[cid][-1:]
        if len(df) < 2 or np.isfinite(last).all():
            continue
        try:
            cal.identify(last)
        except CycleError as exc:
            row, measured = skipped[cid] + len(df), exc.total - exc.missing
            logger.warning(f"{ds.file_path(cid)}, data row {row}: campaign {cid}'s last cycle, "
                           f"{measured} of its {exc.total} distances measured (the export cut "
                           "while it was measured?), cannot identify the parameters: left out "
                           "(a cycle measured so before a campaign's last is refused)")
            ds.campaigns[cid] = df.iloc[:-1]
            distances[cid] = distances[cid][:-1]
            cut[cid] = {"row": row, "measured": measured, "of": exc.total}
    return cut


def without_cut_cycles(raw, report: dict):
    """``raw`` (a distance dataset) without the campaigns' last cycles the calibration
    ``report`` (``calibration.json``) left out (:func:`_without_a_cut_cycle`): the distances
    ``evaluate`` validates an ingested parameter series against, cycle for cycle."""
    for cid in report.get("cut_cycles") or {}:
        if cid in raw.campaigns:
            raw.campaigns[cid] = raw.campaigns[cid].iloc[:-1]
    return raw


def _check_fits(cal: ArtefactCalibration, ds, distances, skipped) -> None:
    """Refuse distances that do not fit the set-up at all, before identifying every cycle.

    The first, middle and last cycles are screened; when two of them (or every one, with fewer)
    have a tenth of their distances gross outliers by both searches of
    :meth:`ArtefactCalibration._robust_cycle`, the distances are not deviations in µm from the
    artefact's calibrated ones, or the artefact, machine or prior is described wrongly.  No
    outlier rule mends that, and searching every cycle would only end in a meaningless fit.
    """
    if not np.isfinite(cal.outlier_z):
        return
    rows = [(cid, k) for cid, df in ds.campaigns.items() for k in range(len(df))]
    picks = sorted({0, len(rows) // 2, len(rows) - 1})
    bad = []
    for i in picks:
        cid, k = rows[i]
        try:
            out, capped = cal.screen(distances[cid][k])
        except ValueError:          # too few distances measured: identifying it names the row
            continue
        if capped:
            bad.append((cid, k, out))
    if len(bad) < min(2, len(picks)):
        return
    cid, k, out = bad[0]
    worst = max(out, key=lambda o: abs(o["z"]))
    where = _described(worst["column"])
    raise ContractError(
        f"the distances do not fit the artefact and machine described here: in campaign {cid}, "
        f"row {skipped[cid] + k + 1}, the outlier search left out a tenth of the {len(cal.design_.columns)} "
        f"distances ({len(out)}) and the rest still do not fit, the worst pose {where['pose']} balls "
        f"{where['balls'][0]}-{where['balls'][1]} off by {worst['residual_um']:.1f} µm "
        f"(z = {worst['z']:.0f}); so in {len(bad)} of the {len(picks)} cycles screened; check that "
        "the E_ columns are measured minus calibrated distances in µm, the artefact (n_balls, "
        "length_mm, misalignment_deg), the poses, the machine's order, uncertainty_um (declared "
        "too small?)"
        f"{', calibrate.prior (ranges narrower than the machine?)' if cal.prior_sd is not None else ''}"
        ", or fit them as they are with calibrate.outlier_z=inf",
        file=setup_path(cal), column=worst["column"])


def flagged(report: dict, campaign: str, columns: list[str], n_cycles: int) -> np.ndarray:
    """``(n_cycles, len(columns))`` True where calibration ``report`` (``calibration.json``) left
    a distance out of its cycle: an outlier of that cycle, or a column ``excluded`` from all."""
    mask = np.zeros((n_cycles, len(columns)), bool)
    where = {c: j for j, c in enumerate(columns)}
    for e in report.get("excluded", []):
        if e["column"] in where:
            mask[:, where[e["column"]]] = True
    start = report.get("trimmed", {}).get(campaign, {}).get("start", 0)
    for o in report.get("outliers", []):
        cycle = o["row"] - 1 - start         # rows named are the file's
        if o["campaign"] == campaign and o["column"] in where and 0 <= cycle < n_cycles:
            mask[cycle, where[o["column"]]] = True
    return mask


def _described(column: str) -> dict:
    m = COLUMN.match(column)
    return {"column": column, "pose": m["pose"], "balls": [int(m["i"]), int(m["j"])]}


def _rows_of_distances(exc: ContractError, setup) -> ContractError | None:
    """The refusal of a file that lists a cycle's distances a row each (a pose's name in a
    cell beside two ball numbers: an artefact software's export per cycle,
    ``S2x1d1;1;2;-0,0013``), saying the layout
    the reader takes; None where the refused file holds no declared pose in its first lines."""
    path = Path(exc.file) if exc.file is not None else None
    if path is None or not path.is_file() or path.suffix.lower() not in (".csv", ".txt"):
        return None
    poses = {p.name for p in setup.poses}
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            head = [f.readline() for _ in range(60)]
    except OSError:
        return None
    for n, text in enumerate(head, 1):
        cells = [c.strip().strip('"') for c in text.replace("\t", ";").replace(",", ";").split(";")]
        pose = next((c for c in cells if c in poses), None)
        balls = [c for c in cells if c.isdigit() and 1 <= int(c) <= setup.array.n_balls]
        if pose is not None and len(balls) >= 2:     # a pose and its two balls: a distance
            return ContractError(
                f"one distance per row (pose {pose!r} in a cell: {text.strip()[:60]!r}) where "
                "the reader takes one measurement cycle per row: its time, "
                "its temperatures and a column E_<pose>_B<i>_B<j> per distance (E_"
                f"{pose}_B01_B02; µm, or its unit in the header: 'E_{pose}_B01_B02 [mm]'), "
                "one file per campaign (docs/data-format.md, 'A volumetric dataset'): put "
                "each cycle's distances into one row", file=path, line=n)
    return None


def layout_refusal(exc: ContractError, root: Path) -> ContractError | None:
    """:func:`_rows_of_distances` for a folder ``root`` read as a volumetric dataset (its
    set-up beside the files), the one rule ``calibrate``, ``run`` and ``init`` refuse such an
    export by; None for any other folder, or where ``exc`` is about something else."""
    if not Path(root).is_dir() or not (Path(root) / SETUP_FILE).is_file():
        return None
    try:
        setup = load_setup(root)
    except ContractError:
        return None                   # (its own refusal comes from the read that needs it)
    return _rows_of_distances(exc, setup)


def calibrate_folder(root: Path, data_cfg: dict, outlier_z: float = 6.0, column_share: float = 0.5,
                     require_seen=("positioning", "straightness"), prior=None):
    """``(parameter dataset, calibration, report, distance dataset)`` of the volumetric dataset
    in ``root`` (the arguments: ``calibrate.*``, docs/cli.md)."""
    setup = load_setup(root)
    if setup is None:
        raise ContractError(f"not a volumetric dataset: no {SETUP_FILE} (write one with "
                            "thermocomp simulate sim=large_mill_volumetric, or see docs/data-format.md)",
                            file=root)
    # an empty E_ cell is a distance not measured; the temperatures are read as for any dataset
    try:
        ds, read = io.read_dataset(root, data_cfg, missing="keep_errors")
    except ContractError as exc:       # a measuring software's export: a row per distance?
        raise _rows_of_distances(exc, setup) or exc from None
    skipped = {cid: e["trimmed"]["start"] for cid, e in read["campaigns"].items()}
    check_columns(ds, setup)
    cal = fitted(setup, outlier_z, prior_sd(setup.model, prior))
    cal.source_ = str(root / SETUP_FILE)
    _require_seen(cal, setup, list(require_seen or []))
    n_cycles = sum(len(df) for df in ds.campaigns.values())
    distances = {cid: distance_matrix(df, cal) for cid, df in ds.campaigns.items()}   # once each
    cut = _without_a_cut_cycle(cal, ds, distances, skipped)
    n_cycles -= len(cut)
    _check_fits(cal, ds, distances, skipped)
    result = _identify(cal, ds, distances, skipped)
    counts: dict[str, int] = {}
    for _, flagged in result.values():
        for f in flagged:
            counts[f["column"]] = counts.get(f["column"], 0) + 1
    excluded = sorted(col for col, k in counts.items() if k > float(column_share) * n_cycles)
    if excluded:     # a column off in most cycles is the artefact or its label, not a cycle
        logger.warning("calibrate: %d distance column(s) flagged in more than %.0f %% of the cycles, "
                       "left out of every cycle: %s", len(excluded), 100 * float(column_share),
                       ", ".join(excluded[:5]))
        result = _identify(cal, ds, distances, skipped, excluded)
    report = _report(cal, setup, ds, distances, result, excluded, counts, n_cycles, skipped)
    report["prior"] = prior
    report["suspect_poses"] = _suspect_poses(report["outliers"], n_cycles)
    report["repairs"] = read["repairs"]          # T_/S_ gaps interpolated (data.max_gap_samples)
    report["trimmed"] = {cid: e["trimmed"] for cid, e in read["campaigns"].items()
                         if any(e["trimmed"].values())}
    report["cut_cycles"] = cut
    campaigns = {}
    for cid, df in ds.campaigns.items():
        keep = df[[col for col in df.columns if not col.startswith("E_")]]
        P = pd.DataFrame(result[cid][0], index=df.index, columns=cal.names_)
        campaigns[cid] = pd.concat([keep, P], axis=1)
    params = io.Dataset(ds.manifest.copy(), campaigns, name=ds.name, meta=dict(ds.meta))
    return params, cal, report, ds


SUSPECT = 0.05    # a pose with outliers in more than this share of the cycles is described wrongly?


def _suspect_poses(outliers: list[dict], n_cycles: int) -> list[dict]:
    """Poses with outliers in more than ``SUSPECT`` of the cycles (and 3 at least), worst first,
    with a warning: a mis-probed ball is one cycle's, a pose whose direction, centre or the
    artefact's misalignment is declared wrong is off in many (an outside probe's θ declared
    -10° for 10°: 144 outliers in 84 of 218 cycles of one pose, 191 in all, and no word)."""
    cycles: dict[str, set] = {}
    for o in outliers:
        cycles.setdefault(o["pose"], set()).add((o["campaign"], o["row"]))
    out = sorted(({"pose": p, "cycles": len(c), "share": len(c) / n_cycles} for p, c in cycles.items()
                  if len(c) >= 3 and len(c) > SUSPECT * n_cycles), key=lambda e: -e["cycles"])
    if out:
        logger.warning("calibrate: %s: is the direction or centre of %s, or the artefact's "
                       "n_balls, length_mm or misalignment_deg declared right in %s?",
                       ", ".join(f"pose {e['pose']} has outliers in {e['cycles']} of {n_cycles} cycles"
                                 for e in out[:3]),
                       "it" if len(out) == 1 else "them", SETUP_FILE)
    return out


def _report(cal, setup, ds, distances, result, excluded, counts, n_cycles, skipped) -> dict:
    params = _kinds(setup)
    cols = cal.design_.columns
    outliers, sq, n, expected = [], 0.0, 0, 0.0
    for cid, (P, flagged) in result.items():
        df = ds.campaigns[cid]
        R = distances[cid] - cal.predict(P)
        skip = np.zeros_like(R, dtype=bool)
        for col in excluded:
            skip[:, cols.index(col)] = True
        for f in flagged:
            skip[f["cycle"], cols.index(f["column"])] = True
            outliers.append({"campaign": cid, "time": float(df["time"].iloc[f["cycle"]]),
                             "row": skipped[cid] + int(f["cycle"]) + 1, **_described(f["column"]),
                             "residual_um": f["residual_um"], "z": f["z"]})
        ok = np.isfinite(R) & ~skip
        sq += float(np.sum(R[ok] ** 2))
        n += int(ok.sum())
        # each distance's residual variance with every distance measured: near enough (and
        # far cheaper than a solver per cycle) for a test of a factor 2
        expected += float(np.sum(np.where(ok, cal.residual_sd_ ** 2, 0.0)))
    return {
        "parameters": {name: {"unit": params[name].unit, "uncertainty": float(u),
                              "kind": params[name].kind}
                       for name, u in zip(cal.names_, cal.uncertainty_)},
        "unidentifiable": dict(cal.unidentifiable_),
        "outliers": outliers,
        "excluded": [{**_described(col), "cycles_flagged": counts[col],
                      "share": counts[col] / n_cycles} for col in excluded],
        "n_cycles": n_cycles,
        "n_distances": len(cols),
        "poses": [p.name for p in setup.poses],
        "residual_rms_um": math.sqrt(sq / n) if n else None,
        "fit": _consistency(sq / n if n else 0.0, expected / n if n else 0.0, cal, setup),
        "campaigns": {cid: len(df) for cid, df in ds.campaigns.items()},
    }


def _consistency(observed: float, expected: float, cal, setup) -> dict:
    """The residuals' scatter against what the declared uncertainties predict: the RMS of the
    distances' residuals over the RMS their GLS covariance gives (1 when ``uncertainty_um`` is
    right), with a warning when it is off both statistically and by a factor of 2.

    The sum of squares of a cycle is a weighted chi-square of ``cal.residual_dof_`` effective
    degrees of freedom; the cycles share the artefact's ball errors, so they are not
    independent draws and the bound is that of one cycle, the widest the pooled value can
    spread.  It decides on small set-ups; on large ones it is tight, and the factor 2 is what
    decides: distances in mm or nm, or uncertainties declared 2x off or more."""
    from scipy import stats

    if not expected > 0:
        return {"expected_rms_um": None, "rms_ratio": None, "effective_dof": None, "accepted": None,
                "consistent": None}
    ratio, nu = math.sqrt(observed / expected), cal.residual_dof_
    lo = min(math.sqrt(stats.chi2.ppf(ALPHA / 2, nu) / nu), 1 / SCATTER)
    hi = max(math.sqrt(stats.chi2.isf(ALPHA / 2, nu) / nu), SCATTER)    # beyond both, to warn
    consistent = bool(lo <= ratio <= hi)
    if not consistent:
        logger.warning(
            "calibrate: the distances' residuals scatter %.3g times what the declared uncertainties "
            "(uncertainty_um: probing %g, ball %g µm) predict (RMS %.3g µm instead of %.3g; expected "
            "%.2f..%.2f times): the E_ distances may be in another unit than µm, or the uncertainties "
            "in %s wrong; the parameters' uncertainties and the outliers flagged rest on them",
            ratio, setup.probing_um, setup.ball_um, math.sqrt(observed), math.sqrt(expected), lo, hi,
            SETUP_FILE)
    return {"expected_rms_um": math.sqrt(expected), "rms_ratio": ratio, "effective_dof": nu,
            "accepted": [lo, hi], "consistent": consistent}


def roundtrip(cal: ArtefactCalibration, result: dict, truth: dict) -> dict | None:
    """z = (identified - equivalent truth) / uncertainty over every parameter and cycle, or None
    when the truth does not hold this dataset's parameter series.  With a prior every parameter
    is estimated and compared with its own truth (the posterior's uncertainty holds what the
    distances cannot tell apart)."""
    z = []
    for cid, (P, _) in result.items():
        full = true_parameters(truth, cid, cal.setup.model.names, len(P))
        if full is None:
            return None
        ref = full if cal.prior_sd is not None else equivalent_truth(cal, full)
        z.append((P - ref) / cal.uncertainty_)
    z = np.vstack(z)
    return {"n_parameters": int(z.shape[1]), "max_abs_z": float(np.max(np.abs(z))),
            "share_within_2u": float(np.mean(np.abs(z) <= 2.0)), "n_values": int(z.size),
            "z_sd": float(np.std(z))}


def true_parameters(truth: dict, campaign: str, names: list[str], n_cycles: int):
    """``(n_cycles, p)``: a simulated campaign's true parameters (every one of ``names``) from its
    ground truth document, or None when the truth does not hold that series."""
    series = ((truth.get("campaigns") or {}).get(campaign) or {}).get("parameters")
    if not series or set(series) != set(names) or len(series[names[0]]) != n_cycles:
        return None
    return np.column_stack([series[n] for n in names])
