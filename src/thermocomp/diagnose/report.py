"""The diagnosis as a Markdown report (and HTML, rendered from it by markdown-it-py)."""

from __future__ import annotations

import html

import numpy as np
from markdown_it import MarkdownIt


def _f(v, digits: int = 2, pct: bool = False) -> str:
    if v is None or (isinstance(v, float) and not np.isfinite(v)):
        return "n/a"
    return f"{v:.{digits}f}{' %' if pct else ''}"


def _p(v) -> str:
    if v is None or not np.isfinite(v):
        return "n/a"
    return "< 0.0001" if v < 1e-4 else f"{v:.4f}"


def _window(e: dict, hours: float) -> tuple[float | None, float | None, float | None]:
    """E_P95 (measured, before, after) at the window closest to ``hours``."""
    w = np.asarray(e["window_s"], float) / 3600.0
    if not w.size:
        return None, None, None
    i = int(np.argmin(np.abs(w - hours)))
    return e["measured"][i], e["before"][i], e["after"][i]


def _change(before, after) -> str:
    if before in (None, 0) or after is None:
        return ""
    return f"{100.0 * (after - before) / before:+.0f} %"


def _effect_row(e: dict) -> str:
    ev = e.get("evidence") or {}
    col = "control (random walk)" if e.get("control") else (e["column"] or "—")
    extra = f" (jump {ev['self_prediction_jump_ratio']:.1f})" if ev.get("self_prediction_jump_ratio") else ""
    return (f"| {e['kind']} | {col} | {e['transform']}{extra} | {_f(ev.get('cv_rmse'))} | "
            f"{_f(ev.get('cv_rmse_gain'))} | {_f(ev.get('cv_rmse_gain_pct'), 1, True)} | "
            f"{_f(ev.get('cv_rmse_gain_lcb'))} | {_p(ev.get('p_value'))} | "
            f"{'yes' if ev.get('clears_bar') else 'no'} | {'**yes**' if e['accepted'] else 'no'} |")


EFFECT_HEAD = ("| kind | column | transform | CV RMSE (µm) | gain (µm) | gain | gain 95 % LCB (µm) "
               "| p | clears bar | accepted |\n|---|---|---|---:|---:|---:|---:|---:|---|---|")


def markdown(j: dict, figures: list[str] | None = None, rerun: str | None = None,
             others: dict | None = None) -> str:
    """Markdown report of one target's ``diagnosis.json`` content ``j``.

    ``figures``: relative paths of the PNGs; ``rerun``: the command that
    reproduces the "after" figures; ``others``: target -> report file name.
    """
    b, a = j["before"], j["after"]
    e = j["test_e_p95"]
    bar = j["bar"]
    lines = [f"# Residual diagnosis: {j['model']} on {j['dataset']}, target {j['target']}", ""]
    accepted = [x for x in j["effects"] if x["accepted"]]
    cv = j["cv"]
    if cv.get("scheme") == "forward":
        how = (f"forward chaining: {cv['units']} validation blocks over the last "
               f"{100 * (1 - cv['min_train_fraction']):.0f} % of the rows, each predicted by a model "
               f"trained on the rows before it less a gap of {cv['gap_samples']} samples")
    else:
        how = f"{cv['units']} {cv['unit']}s, held out in {cv['folds']} folds"
    lines += [f"The model was cross-validated on the {len(cv['train_campaigns'])} train campaign(s) "
              f"({how}, mode `{j['mode']}`); the search never saw the errors of the {len(cv['test_campaigns'])} "
              f"test campaign(s), "
              f"on which before and after are measured.  A candidate is accepted when its CV RMSE gain "
              f"is at least {bar['min_gain_pct']:g} % and the one-sided sign-flip test of the "
              f"per-unit gains gives p ≤ {bar['alpha']:g} (a removed sensor: self-prediction jump "
              f"≥ its tolerance), and when it beats the random-walk control; at most "
              f"{bar['max_effects']} effects.", ""]
    lines += ["## Before and after (test split)", "",
              "| figure | before | after | change |", "|---|---:|---:|---:|",
              f"| test RMSE (µm) | {_f(b['test_rmse'])} | {_f(a['test_rmse'])} | "
              f"{_change(b['test_rmse'], a['test_rmse'])} |",
              f"| test Rsd SM (µm) | {_f(b['test_rsd_mean'])} | {_f(a['test_rsd_mean'])} | "
              f"{_change(b['test_rsd_mean'], a['test_rsd_mean'])} |",
              f"| test Rsd SD (µm) | {_f(b['test_rsd_sd'])} | {_f(a['test_rsd_sd'])} | "
              f"{_change(b['test_rsd_sd'], a['test_rsd_sd'])} |",
              f"| CV RMSE, train campaigns (µm) | {_f(b['cv_rmse'])} | {_f(a['cv_rmse'])} | "
              f"{_change(b['cv_rmse'], a['cv_rmse'])} |"]
    for hours in (1.0, 4.0):
        _, eb, ea = _window(e, hours)
        lines.append(f"| E_P95({e['statistic']}), {hours:g} h window (µm) | {_f(eb)} | {_f(ea)} | "
                     f"{_change(eb, ea)} |")
    lines += [f"| measured error RMS, no compensation (µm) | {_f(b['test_rms_measured'])} | | |", ""]
    lines += ["## Accepted effects", ""]
    if accepted:
        lines += ["| step | kind | column | transform | CV RMSE after (µm) |", "|---:|---|---|---|---:|"]
        for x in accepted:
            ev = x.get("evidence") or {}
            lines.append(f"| {x.get('step', '—')} | {x['kind']} | {x['column'] or '—'} | "
                         f"{x['transform']} | {_f(ev.get('cv_rmse'))} |")
        if j["excluded_inputs"]:
            lines += ["", f"Sensors taken out of the inputs (`sensor_fault`): "
                          f"{', '.join(j['excluded_inputs'])}."]
    else:
        lines.append("Nothing cleared the bar: no candidate effect improves the cross-validated "
                     "error reliably, so the model is left as it is.")
    control = j.get("control")
    if control:
        ev = control["evidence"]
        verdict = ("it cleared the bar in some round: the bar is too low"
                   if j["control_ever_clears_bar"] else "it never cleared the bar")
        lines += ["", f"Random-walk control (no physical effect), last round: CV RMSE gain "
                      f"{_f(ev['cv_rmse_gain'])} µm ({_f(ev['cv_rmse_gain_pct'], 1, True)}), "
                      f"p = {_p(ev['p_value'])}; {verdict}."]
    lines += ["", "## Evidence, round by round", ""]
    for r in j["rounds"]:
        title = (f"Sensor health (before the search): CV RMSE {_f(r['cv_rmse'])} µm" if r["step"] == 0
                 else f"Round {r['step']}: CV RMSE {_f(r['cv_rmse'])} µm")
        lines += [f"### {title}", "", EFFECT_HEAD]
        lines += [_effect_row(x) for x in r["evaluated"]]
        if r["screened"]:
            top = ", ".join(f"{s['kind']} {s['column'] or ''} {s['transform']} ({s['screen_r2']:.2f})"
                            .replace("  ", " ") for s in r["screened"][:6])
            lines += ["", f"Screening (partial R² of the CV residual), best: {top}."]
        lines.append("")
    if j["self_prediction"]:
        lines += ["## Sensor self-prediction (paper 002)", "",
                  "Each declared sensor predicted from the others: on each train campaign by a fit "
                  "without it, on each test campaign (its temperatures only -- what a deployed "
                  "compensator sees) by the fit on all train campaigns.  Jump ratio = the smaller of "
                  "its worst campaign against the median sensor's (cross) and against its own "
                  "lower-quartile campaign (own).", "",
                  "| sensor | CV RMSE (°C) | worst campaign | its RMSE (°C) | cross | own | jump ratio |",
                  "|---|---:|---|---:|---:|---:|---:|"]
        lines += [f"| {s['sensor']} | {s['cv_rmse_c']:.3f} | {s['worst_unit']} ({s['worst_unit_split']}) | "
                  f"{s['worst_unit_rmse_c']:.3f} | {s['cross_ratio']:.1f} | {s['own_ratio']:.1f} | "
                  f"{s['jump_ratio']:.1f} |" for s in j["self_prediction"]]
        lines.append("")
    if figures:
        lines += ["## Figures", ""] + [f"![{f}]({f})" for f in figures] + [""]
    if rerun:
        lines += ["## Rerun the diagnosed model", "",
                  "The accepted effects are a model config (`conf/model/diagnosed.yaml`, with "
                  "`conf/experiment/diagnosed.yaml` pinning what the diagnosis ran with); this "
                  "reproduces the \"after\" figures and can be swept and promoted like any model:", "",
                  "```", rerun, "```", ""]
    if others:
        lines += ["## Other targets", ""] + [f"- [{t}]({name})" for t, name in others.items()] + [""]
    lines.append(f"_Diagnosis time: {j['seconds']:.1f} s._")
    return "\n".join(lines) + "\n"


def to_html(md: str, title: str) -> str:
    """A standalone HTML page of the Markdown report."""
    body = MarkdownIt("commonmark").enable("table").render(md)
    style = ("body{font-family:system-ui,sans-serif;max-width:72rem;margin:2rem auto;padding:0 1rem;"
             "line-height:1.45}table{border-collapse:collapse;font-size:.9rem;margin:.5rem 0}"
             "th,td{border:1px solid #ccc;padding:.25rem .5rem}th{background:#f3f3f3}"
             "img{max-width:100%}code,pre{background:#f6f6f6}pre{padding:.5rem;overflow-x:auto}")
    return (f"<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{html.escape(title)}</title>"
            f"<style>{style}</style></head><body>\n{body}</body></html>\n")
