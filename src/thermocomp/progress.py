"""Progress of long loops (``tqdm`` bars) and of sweeps (jobs done), always on stderr.

A bar shows on a terminal, or anywhere at ``-v``; never with ``-q``, never on
stdout (the result table stays clean when piped).
"""

from __future__ import annotations

import logging
import sys
from pathlib import Path

from hydra.experimental.callback import Callback

from .log import level_name

log = logging.getLogger("thermocomp")


def bar(iterable=None, desc: str | None = None, total: int | None = None, unit: str = "it",
        disable: bool | None = None, **kwargs):
    """``tqdm(iterable)`` on stderr: shown on a TTY or at ``-v``, hidden at ``-q`` or when the
    caller passes ``disable=True`` (a loop too short to need one)."""
    from tqdm import tqdm

    level = level_name()
    if disable is not True:
        disable = True if level == "WARNING" else (False if level == "DEBUG" else None)
    return tqdm(iterable, desc=desc, total=total, unit=unit, file=sys.stderr, disable=disable,
                leave=False, dynamic_ncols=True, **kwargs)


def sweep_size(task_overrides) -> int | None:
    """Number of jobs of a basic sweep (the product of the sweep overrides' lengths), or None."""
    from hydra.core.override_parser.overrides_parser import OverridesParser

    try:
        n = 1
        for o in OverridesParser.create().parse_overrides(list(task_overrides)):
            if o.is_sweep_override():
                n *= len(list(o.sweep_iterator()))
        return n
    except Exception:  # another sweeper's syntax: no total
        return None


class SweepProgress(Callback):
    """Hydra callback: one line per finished sweep job, ``sweep: 3/8 jobs done``.

    Jobs may run in other processes (joblib, SLURM): each marks itself done in
    ``<sweep dir>/.done/`` and counts the marks, so the count is across processes.
    """

    def on_multirun_start(self, config, **kwargs) -> None:
        total = sweep_size(config.hydra.overrides.task)
        done = Path(str(config.hydra.sweep.dir)) / ".done"
        done.mkdir(parents=True, exist_ok=True)
        for f in done.iterdir():  # a rerun into the same folder counts afresh
            f.unlink()
        (done / "total").write_text("" if total is None else str(total))

    def on_job_end(self, config, job_return, **kwargs) -> None:
        from hydra.core.utils import JobStatus

        done = Path(str(config.hydra.sweep.dir)) / ".done"
        if not done.is_dir():
            return
        num = config.hydra.job.num
        (done / f"job{num}").touch()
        n = sum(1 for f in done.iterdir() if f.name.startswith("job"))
        total = (done / "total").read_text() if (done / "total").is_file() else ""
        status = "ok" if job_return.status == JobStatus.COMPLETED else "FAILED"
        overrides = " ".join(config.hydra.overrides.task)
        log.info(f"sweep: {n}/{total or '?'} jobs done (#{num} {status}: {overrides})")
