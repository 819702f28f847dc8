"""The diagnosis report: one Markdown document for every target, and its HTML page.

``report.md`` links its figures under ``plots/``; ``report.html`` (rendered
from it by markdown-it-py) embeds them as ``data:image/png;base64`` URIs, so
the page works alone when copied.  Every link points inside the document
(heading anchors, GitHub's slug rule) or to http(s).
"""

from __future__ import annotations

import base64
import html
import re
from pathlib import Path

import numpy as np
from markdown_it import MarkdownIt

from ...core.metrics import unit
from ...core.scoring.results import TEST_RMSE, TEST_RSD_MEAN, TEST_RSD_SD


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


def effect_head(target: str) -> str:
    """:data:`EFFECT_HEAD` in ``target``'s unit (iso67: a tilt's µm/m, where it said µm)."""
    return EFFECT_HEAD.replace("(µm)", f"({unit(target)})")


def slug(text: str) -> str:
    """The anchor of a heading: lower case, punctuation dropped, spaces to ``-`` (GitHub's rule,
    so the Markdown's own links work where it is rendered too)."""
    return re.sub(r"[^\w\- ]", "", text.strip().lower()).replace(" ", "-")


def _link(text: str, heading: str) -> str:
    return f"[{text}](#{slug(heading)})"


def _named(j: dict) -> str:
    """``mlr`` or ``mlr ati=cmeans``: the model as the run's header names it."""
    ati = j.get("ati", "none")
    return j["model"] + ("" if ati == "none" else f" ati={ati}")


def _intro(j: dict) -> list[str]:
    """How the search validated and what it accepts (shared by every target)."""
    cv, bar = j["cv"], j["bar"]
    if cv.get("scheme") == "forward":
        how = (f"forward chaining: {cv['units']} validation blocks over the last "
               f"{100 * (1 - cv['min_train_fraction']):.0f} % of the rows, each predicted by a model "
               f"trained on the rows before it less a gap of {cv['gap_samples']} samples")
    else:
        how = f"{cv['units']} {cv['unit']}s, held out in {cv['folds']} folds"
    return [f"The model was cross-validated on the {len(cv['train_campaigns'])} train campaign(s) "
            f"({how}, mode `{j['mode']}`); the search never saw the errors of the "
            f"{len(cv['test_campaigns'])} test campaign(s), on which before and after are measured.  "
            f"A candidate is accepted when its CV RMSE gain is at least {bar['min_gain_pct']:g} % and "
            f"the one-sided sign-flip test of the per-unit gains gives p ≤ {bar['alpha']:g} (a removed "
            f"sensor: self-prediction jump ≥ its tolerance), and when it beats the random-walk "
            f"control; at most {bar['max_effects']} effects.", ""]


def _accepted(j: dict) -> list[dict]:
    return [x for x in j["effects"] if x["accepted"]]


def _effect_name(x: dict) -> str:
    return f"{x['kind']}: {x['column'] or '—'} {x['transform']}"


def _caption(name: str, target: str, model: str) -> str:
    """What a figure of :func:`~thermocomp.apps.diagnose.figures.diagnosis_figures` shows, from its name."""
    stem = Path(name).stem
    if stem.startswith("e_p95_"):
        return (f"{target}: E_P95 of the test campaigns against the window length (h), measured error "
                f"and residual of {model} before and after the diagnosed effects")
    step = stem.rsplit("_", 1)[-1]
    return (f"{target}, step {step}: the CV residual before the accepted effect against the part "
            f"the effect explains (left), and both against time in h (right)")


def _target_section(j: dict, figures: list[str], primary: bool) -> list[str]:
    """One target: its own contents, before/after, accepted effects, figures, evidence."""
    t, b, a, e = j["target"], j["before"], j["after"], j["test_e_p95"]
    h = {k: f"{t}: {k}" for k in ("before and after", "accepted effects", "figures",
                                  "evidence, round by round", "sensor self-prediction")}
    rounds = [(r, f"{t} sensor health" if r["step"] == 0 else f"{t} round {r['step']}")
              for r in j["rounds"]]
    accepted = _accepted(j)
    um = unit(t)                  # (iso67: a tilt's figures in µm/m, where every one said µm)
    lines = [f"## {t}", "",
             ("Primary target (largest CV RMSE before; `diagnosis.json`).  " if primary else "")
             + f"Test RMSE {_f(b[TEST_RMSE])} → {_f(a[TEST_RMSE])} {um}; accepted: "
             + (", ".join(_effect_name(x) for x in accepted) or "nothing") + ".", "",
             f"- {_link('Before and after (test split)', h['before and after'])}",
             f"- {_link('Accepted effects', h['accepted effects'])}"]
    if figures:
        lines.append(f"- {_link('Figures', h['figures'])}")
    lines.append(f"- {_link('Evidence, round by round', h['evidence, round by round'])}")
    lines += [f"  - {_link(title.removeprefix(t + ' ').capitalize(), title)}" for _, title in rounds]
    if j["self_prediction"]:
        lines.append(f"- {_link('Sensor self-prediction (paper 002)', h['sensor self-prediction'])}")
    lines += ["", f"### {h['before and after']}", "",
              "| figure | before | after | change |", "|---|---:|---:|---:|"]
    for label, key in ((f"test RMSE ({um})", TEST_RMSE), (f"test Rsd SM ({um})", TEST_RSD_MEAN),
                       (f"test Rsd SD ({um})", TEST_RSD_SD),
                       (f"CV RMSE, train campaigns ({um})", "cv_rmse")):
        lines.append(f"| {label} | {_f(b[key])} | {_f(a[key])} | {_change(b[key], a[key])} |")
    for hours in (1.0, 4.0):
        _, eb, ea = _window(e, hours)
        lines.append(f"| E_P95({e['statistic']}), {hours:g} h window ({um}) | {_f(eb)} | {_f(ea)} | "
                     f"{_change(eb, ea)} |")
    lines += [f"| measured error RMS, no compensation ({um}) | {_f(b['test_rms_measured'])} | | |", ""]
    lines += [f"### {h['accepted effects']}", ""]
    if accepted:
        lines += [f"| step | kind | column | transform | CV RMSE after ({um}) |", "|---:|---|---|---|---:|"]
        lines += [f"| {x.get('step', '—')} | {x['kind']} | {x['column'] or '—'} | {x['transform']} | "
                  f"{_f((x.get('evidence') or {}).get('cv_rmse'))} |" for x in accepted]
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
                      f"{_f(ev['cv_rmse_gain'])} {um} ({_f(ev['cv_rmse_gain_pct'], 1, True)}), "
                      f"p = {_p(ev['p_value'])}; {verdict}."]
    lines.append("")
    if figures:
        lines += [f"### {h['figures']}", ""]
        for f in figures:
            caption = _caption(f, t, j["model"])
            lines += [f"![{caption}]({f})", "", f"*{caption}.*", ""]
    lines += [f"### {h['evidence, round by round']}", ""]
    for r, title in rounds:
        lines += [f"#### {title}", "", f"CV RMSE at the start of this round: {_f(r['cv_rmse'])} {um}.",
                  "", effect_head(t)]
        lines += [_effect_row(x) for x in r["evaluated"]]
        if r["screened"]:
            top = ", ".join(f"{s['kind']} {s['column'] or ''} {s['transform']} ({s['screen_r2']:.2f})"
                            .replace("  ", " ") for s in r["screened"][:6])
            lines += ["", f"Screening (partial R² of the CV residual), best: {top}."]
        lines.append("")
    if j["self_prediction"]:
        lines += [f"### {h['sensor self-prediction']}", "",
                  "Each declared sensor predicted from the others (paper 002) on each train campaign "
                  "by a fit without it.  Jump ratio = the smaller of its worst campaign against the "
                  "median sensor's (cross) and against its own lower-quartile campaign (own).", "",
                  "| sensor | CV RMSE (°C) | worst campaign | its RMSE (°C) | cross | own | jump ratio |",
                  "|---|---:|---|---:|---:|---:|---:|"]
        lines += [f"| {s['sensor']} | {s['cv_rmse_c']:.3f} | {s['worst_unit']} ({s['worst_unit_split']}) | "
                  f"{s['worst_unit_rmse_c']:.3f} | {s['cross_ratio']:.1f} | {s['own_ratio']:.1f} | "
                  f"{s['jump_ratio']:.1f} |" for s in j["self_prediction"]]
        lines.append("")
    if j.get("test_sensor_warnings"):
        lines += ["Broken in the test split's temperatures (the fit on all train campaigns; not acted "
                  "on: the search never sees the test split, `thermocomp monitor` excludes such a "
                  "sensor online):", "",
                  "| sensor | test campaign | its RMSE (°C) | jump ratio |", "|---|---|---:|---:|"]
        lines += [f"| {w['sensor']} | {w['campaign']} | {w['rmse_c']:.3f} | {w['jump_ratio']:.1f} |"
                  for w in j["test_sensor_warnings"]]
        lines.append("")
    return lines


RERUN = "Rerun the diagnosed model"


def markdown(jsons: dict[str, dict], figures: dict[str, list[str]] | None = None,
             rerun: str | None = None, primary: str | None = None) -> str:
    """The Markdown report of a diagnosis, every target in one document.

    Parameters
    ----------
    jsons : dict
        Target -> its ``diagnosis_<target>.json`` content, in report order.
    figures : dict, optional
        Target -> paths of its PNGs, relative to the report's folder.
    rerun : str, optional
        The command that reproduces the "after" figures.
    primary : str, optional
        The target ``diagnosis.json`` holds (shown first).
    """
    figures = figures or {}
    order = sorted(jsons, key=lambda t: t != primary)       # primary first, then as given
    first = jsons[order[0]]
    lines = [f"# Residual diagnosis: {_named(first)} on {first['dataset']}", ""] + _intro(first)
    lines += ["## Contents", ""]
    for t in order:
        b, a = jsons[t]["before"], jsons[t]["after"]
        lines.append(f"- {_link(t, t)}{' (primary)' if t == primary else ''}: test RMSE "
                     f"{_f(b[TEST_RMSE])} → {_f(a[TEST_RMSE])} {unit(t)}, "
                     f"{len(_accepted(jsons[t]))} effect(s) accepted")
    if rerun:
        lines.append(f"- {_link(RERUN, RERUN)}")
    tilts = [t for t in order if unit(t) != "µm"]
    units = "(µm)" if not tilts else f"(µm; {', '.join(tilts)} in µm/m)"
    lines += ["", f"| target | test RMSE before → after {units} | CV RMSE before → after {units} "
              "| accepted effects |", "|---|---:|---:|---|"]
    for t in order:
        j = jsons[t]
        lines.append(f"| {_link(t, t)} | {_f(j['before'][TEST_RMSE])} → {_f(j['after'][TEST_RMSE])} | "
                     f"{_f(j['before']['cv_rmse'])} → {_f(j['after']['cv_rmse'])} | "
                     + ("; ".join(_effect_name(x) for x in _accepted(j)) or "none") + " |")
    lines.append("")
    for t in order:
        lines += _target_section(jsons[t], figures.get(t, []), t == primary)
    if rerun:
        lines += [f"## {RERUN}", "",
                  "The accepted effects are a model config (`conf/model/diagnosed.yaml`, with "
                  "`conf/experiment/diagnosed.yaml` pinning what the diagnosis ran with); this "
                  "reproduces the \"after\" figures and can be swept and promoted like any model:", "",
                  "```", rerun, "```", ""]
        clamped = {t: j["after"].get("test_rows_clamped") for t, j in jsons.items()}
        guarded = {t: j["after"].get("test_rows_guarded") for t, j in jsons.items()}
        if any(clamped.values()) or any(guarded.values()):
            # the deployed stream held test inputs to the training envelope or its guard bounded
            # a correction: run scores the model's own prediction in batch
            lines += ["\"After\" is the model as deployed (promote, replay, exported code: "
                      f"{max(n or 0 for n in clamped.values())} test row(s) clamped to the "
                      "training envelope; corrections bounded or rate-limited by the guard on "
                      + (", ".join(f"{t} {n}" for t, n in guarded.items() if n) or "none")
                      + " test row(s)); this run scores it in batch: test RMSE "
                      + ", ".join(f"{t} {j['after']['test_rmse_as_run']:.3f} {unit(t)}"
                                  for t, j in jsons.items() if clamped[t] is not None) + ".", ""]
    lines.append(f"_Diagnosis time: {first['seconds']:.1f} s._")
    return "\n".join(lines) + "\n"


STYLE = ("body{font-family:system-ui,sans-serif;max-width:72rem;margin:2rem auto;padding:0 1rem;"
         "line-height:1.45}table{border-collapse:collapse;font-size:.9rem;margin:.5rem 0}"
         "th,td{border:1px solid #ccc;padding:.25rem .5rem}th{background:#f3f3f3}"
         "img{max-width:100%}code,pre{background:#f6f6f6}pre{padding:.5rem;overflow-x:auto}"
         "h2{border-top:2px solid #ddd;padding-top:1rem}")


def _embed(src: str, base: Path | None) -> str:
    """A relative PNG under ``base`` as a ``data:`` URI; anything else unchanged."""
    if base is None or re.match(r"^[a-z][a-z0-9+.-]*:", src, re.I) or src.startswith("/"):
        return src
    path = base / src
    if not path.is_file():
        return src
    return "data:image/png;base64," + base64.b64encode(path.read_bytes()).decode("ascii")


def to_html(md: str, title: str, base=None) -> str:
    """A standalone HTML page of the Markdown report ``md``.

    Headings get ``id`` anchors (:func:`slug`); images whose path is relative
    to the folder ``base`` are embedded as ``data:image/png;base64`` URIs.
    """
    parser = MarkdownIt("commonmark").enable("table")
    base = None if base is None else Path(base)
    render_image = parser.renderer.rules["image"]

    def heading_open(self, tokens, idx, options, env):
        tokens[idx].attrSet("id", slug(tokens[idx + 1].content))
        return self.renderToken(tokens, idx, options, env)

    def image(self, tokens, idx, options, env):
        tokens[idx].attrSet("src", _embed(tokens[idx].attrGet("src") or "", base))
        return render_image(tokens, idx, options, env)

    parser.add_render_rule("heading_open", heading_open)
    parser.add_render_rule("image", image)
    body = parser.render(md)
    return (f"<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{html.escape(title)}</title><style>{STYLE}</style></head><body>\n{body}</body></html>\n")


def write_report(folder, jsons: dict[str, dict], figures: dict[str, list[str]] | None = None,
                 rerun: str | None = None, primary: str | None = None) -> tuple[Path, Path]:
    """Write ``report.md`` and ``report.html`` (every target) into ``folder``, where the figures
    are (paths in ``figures`` relative to it); returns both paths."""
    folder = Path(folder)
    md = markdown(jsons, figures, rerun, primary)
    first = jsons[primary] if primary in jsons else next(iter(jsons.values()))
    page = to_html(md, f"Diagnosis: {_named(first)} on {first['dataset']}", folder)
    (folder / "report.md").write_text(md, encoding="utf-8")
    (folder / "report.html").write_text(page, encoding="utf-8")
    return folder / "report.md", folder / "report.html"
