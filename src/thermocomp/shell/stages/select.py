"""`thermocomp select`: choose the inputs (TSPs) per target -> models/<name>/selection.json.

Reads the training data as ``train`` will see it (``data.processed`` when it matches the
config, i.e. already denoised; else the ingested data, denoised here if ``denoise`` asks for
it) and fits the configured selector per target on the train split in the reference frame
(:func:`thermocomp.core.select.per_target.select_on_campaigns`).  ``selection.json`` holds, per
target, the selected sensors (in order), every candidate's score and the information
criterion per size, plus a fingerprint of the settings; ``train`` uses it when the fingerprint
matches, so both stages agree and selection runs once.  Figure: ``<out>/select/selection.png``.
"""

from __future__ import annotations

from omegaconf import DictConfig

from ...base.files import atomic_dir, write_json
from ...base.log import say
from ...base.paths import resolve
from ..chain import denoise_step, handed_denoised, select_step
from ..config.checks import check_config
from ..source import open_source
from ..tracking import stage_run
from .artifacts import processed_data, selection_fingerprint, selection_path


def select(cfg: DictConfig) -> dict:
    """Fit the selector per target on the train split and write ``selection.json``."""
    check_config(cfg, outputs=("out", "model_path"), inputs=("data.interim", "data.processed"))
    ds = open_source(cfg, ingested=True)
    processed = processed_data(cfg, ds)     # the denoise stage's output, where it matches
    denoised = (handed_denoised(cfg, ds, processed) if processed is not None else
                denoise_step(cfg, ds))
    result, scores, names = select_step(cfg, ds, denoised)
    for t, entry in result.items():
        say(f"{t}: {cfg.select.name} -> {', '.join(entry['selected'])}")
    doc = {"select": cfg.select.name, "fingerprint": selection_fingerprint(cfg, ds),
           "train_campaigns": ds.ids("train"), "targets": result}
    path = write_json(selection_path(cfg), doc)
    figures = resolve(cfg.out) / "select"
    with atomic_dir(figures) as tmp:      # plots=none: emptied, not an earlier run's figures
        if cfg.plots != "none":
            from ...core.figures.plots import selection_plot

            selection_plot({t: {k: (float("nan") if v is None else v) for k, v in s.items()}
                            for t, s in scores.items()},
                           {t: e["selected"] for t, e in result.items()}, names,
                           tmp / "selection.png")
    with stage_run(cfg, "select") as tr:
        tr.log_metrics({"n_selected": {t: len(e["selected"]) for t, e in result.items()}})
        tr.log_artifact(path)
        tr.log_artifacts(figures, "select")
    say(f"selection: {path}")
    return doc
