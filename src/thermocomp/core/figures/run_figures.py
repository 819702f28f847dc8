"""The figures of a run (``plots=summary|test|all``): drawn by worker processes while the
next numbers are computed (:class:`~.plots.FigurePool`), their data written for ``dvc plots``."""

from __future__ import annotations

from contextlib import contextmanager

from ...base.files import inside, safe_name
from ..metrics import E_MAX, E_P95, ISO_A3, PER_CAMPAIGN, RSD
from ..scoring.iso10791 import a3_campaign
from ..scoring.results import TargetResult


@contextmanager
def plots_folder(stage, level: str):
    """``(draw, folder)``: ``draw(plot, *args)`` queues a figure of ``folder``,
    ``<stage>/plots`` (it replaces ``<out>/plots`` when the run is committed); nothing at all
    with ``plots=none`` (not even a matplotlib import)."""
    if level == "none":
        yield None, None
        return
    from .plots import FigurePool

    folder = stage / "plots"
    folder.mkdir()
    with FigurePool() as pool:
        yield pool.submit, folder


def figure_path(folder, *parts: str):
    """``<folder>/<parts joined>.png``; the name is sanitised and must stay in ``folder`` (column
    and campaign names are checked at ingest, this is the second line of defence)."""
    return inside(folder, safe_name(*parts) + ".png")


def campaign_figures(draw, folder, comp, ds, predictions: dict) -> None:
    """Residual and ISO 10791-10 A.3 figures of every campaign of ``predictions``."""
    from .plotdata import write_residual
    from .plots import iso_a3_plot, residual_plot

    for cid, (meas, pred) in predictions.items():
        time_s = ds.campaigns[cid]["time"].to_numpy()
        for t in comp.targets_:
            y, yhat = meas[t].to_numpy(), pred[t].to_numpy()
            draw(residual_plot, time_s, y, yhat, t, cid, figure_path(folder, "residual", cid, t))
            write_residual(folder, time_s, y, yhat, t, cid)  # the data, for `dvc plots show`
            a3 = a3_campaign(time_s, y, y - yhat)
            if a3["available"]:
                mv = a3["moving"]
                draw(iso_a3_plot, mv["start_s"], mv["range_before"], mv["range_after"], t, cid,
                     figure_path(folder, ISO_A3, cid, t))


def e_p95_figures(draw, folder, targets: dict) -> None:
    """Per target: E_P95 (and E_max) before/after compensation on the test split."""
    from .plotdata import write_e_p95
    from .plots import e_p95_plot

    write_e_p95(folder, targets)  # the curves as data, for `dvc plots show`
    for t, tm in targets.items():
        e, emax = TargetResult(tm).test.e_p95, TargetResult(tm).test.get(E_MAX)
        draw(e_p95_plot, e["window_s"], e["before"], e["after"], t, e["statistic"],
             figure_path(folder, E_P95, t), emax["before"], emax["after"])


def rsd_figures(draw, folder, metrics: dict, test_ambient: dict) -> None:
    """Per target: Rsd per test campaign (with the ATI baselines), the ATI figures of an ATI model."""
    from .plots import ati_intervals_plot, elbow_plot, rsd_plot

    ati = metrics.get("ati", {}).get("targets", {})
    for t, tm in metrics["targets"].items():
        per = {c: v[RSD] for c, v in TargetResult(tm).test.get(PER_CAMPAIGN).items()}
        baselines = {}
        for name, label in (("coldest", "coldest-campaign model"), ("warmest", "warmest-campaign model"),
                            ("single_model", "one model, all train")):
            if name in ati.get(t, {}).get("test", {}):
                camp = metrics["ati"].get("baseline_campaigns", {}).get(name, {}).get("campaign")
                baselines[f"{label} ({camp})" if camp else label] = \
                    ati[t]["test"][name][PER_CAMPAIGN]
        n_int = ati.get(t, {}).get("n_intervals", 1)
        label = metrics["model"] + (f", {n_int} ATIs" if "intervals" in ati.get(t, {}) else "")
        draw(rsd_plot, per, t, figure_path(folder, RSD, t), test_ambient, baselines, label)
        entry = ati.get(t, {})
        if "intervals" in entry:
            draw(ati_intervals_plot, entry["campaign_ambient_c0"], entry["boundaries_c"], t,
                 figure_path(folder, "ati_intervals", t), test_ambient,
                 [i["campaigns"] for i in entry["intervals"]])
            if entry.get("elbow") and entry["elbow"].get("n_intervals"):
                draw(elbow_plot, entry["elbow"], t, figure_path(folder, "ati_elbow", t))


def mutual_figures(draw, folder, mutual: dict) -> None:
    """The mutual prediction heat map of every target."""
    from .plots import mutual_prediction_plot

    for t, mp in mutual.items():
        draw(mutual_prediction_plot, mp["campaigns"], mp[RSD], t,
             figure_path(folder, "mutual_prediction", t), mp["ambient_c0"], mp.get("trained_on"))
