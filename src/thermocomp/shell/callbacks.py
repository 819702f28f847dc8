"""Hydra callbacks: one MLflow parent run per sweep (``thermocomp <stage> -m ...``).

Registered in ``conf/common.yaml`` under ``hydra.callbacks``.  On
``on_multirun_start`` a parent run is created and its id exported as
``THERMOCOMP_PARENT_RUN_ID`` before the launcher starts any job, so every job's
stage run (:func:`thermocomp.shell.tracking.stage_run`) becomes its child, whether the
job runs in this process (basic launcher), in a joblib worker process (the
workers inherit the environment) or on a SLURM node (submitit exports the
environment; Ray: the launcher's runtime environment, see
``conf/hydra/launcher/ray.yaml``).  The id is also written to
``<sweep dir>/sweep.json`` so ``thermocomp compare compare.sweep=<sweep dir>``
finds the sweep again.  ``on_multirun_end`` closes the parent run and prints the
comparison table.  :class:`SweepObjective` hands a search sweeper (Optuna) each
job's validation score.
"""

from __future__ import annotations

import atexit
import os
import sys
from pathlib import Path
from typing import Any

from hydra.experimental.callback import Callback
from omegaconf import DictConfig, OmegaConf

from .tracking import enabled, sweep_name

FAILED_JOBS_ENV = "THERMOCOMP_FAILED_JOBS"   # folder where a sweep's failed jobs leave a note
FAILED_JOB = "failed.json"    # in a failed sweep job's own folder: its overrides, exit, why
SWEEP_PID_ENV = "THERMOCOMP_SWEEP_PID"       # the process that launches a sweep's jobs


def _say(msg: str) -> None:
    from ..base.log import logger

    logger.info(msg)


class MlflowSweepCallback(Callback):
    """Parent MLflow run around a Hydra multirun; compares its children at the end.

    Parameters
    ----------
    compare : bool
        Print and save the comparison table (``thermocomp compare``) when the sweep ends.
    """

    def __init__(self, compare: bool = True):
        self.compare = compare
        self.run_id: str | None = None
        self._previous: str | None = None

    def on_multirun_start(self, config: DictConfig, **kwargs: Any) -> None:
        os.environ[SWEEP_PID_ENV] = str(os.getpid())   # jobs of local workers die with it
        if not enabled(config):
            return
        from .tracking import PARENT_ENV, start_parent_run

        overrides = list(config.hydra.overrides.task)
        sweep_dir = Path(str(config.hydra.sweep.dir))
        tags = {"sweep.overrides": " ".join(overrides)[:5000], "sweep.dir": str(sweep_dir),
                "launcher": str(config.hydra.launcher.get("_target_", "")).rsplit(".", 1)[-1],
                "sweeper": str(config.hydra.sweeper.get("_target_", "")).rsplit(".", 1)[-1]}
        self.run_id = start_parent_run(config, sweep_name(overrides, config.get("name")), tags)
        self._previous = os.environ.get(PARENT_ENV)
        os.environ[PARENT_ENV] = self.run_id
        from ..base.files import write_json
        from ..base.paths import resolve
        from .sweeps import SWEEP_FILE

        write_json(resolve(sweep_dir) / SWEEP_FILE, {"parent_run_id": self.run_id,
                                                     "overrides": overrides})
        _say(f"sweep parent run {self.run_id}")
        # A sweep stopped early (Ctrl-C, SIGTERM, a launcher's failure) skips on_multirun_end:
        # close the parent run anyway.  A failing job does not stop it (cli._job_failed).
        atexit.register(self._abandon, config)

    def on_job_start(self, config: DictConfig, **kwargs: Any) -> None:
        """A sweep job's folder says what ran: ``.hydra/overrides.yaml`` and ``.hydra/config.yaml``
        (Hydra's own layout; written here because ``hydra.output_subdir`` is null so that
        single runs leave no ``.hydra/`` in the project root).  A job in a worker process of a
        local launcher (joblib) ends with the sweep's process, even a SIGKILLed one."""
        from hydra.types import RunMode

        from ..base.lifetime import watch_parent

        if os.environ.get(SWEEP_PID_ENV):   # a local launcher's worker (joblib) ends with the sweep
            sweep = int(os.environ[SWEEP_PID_ENV])
            watch_parent(sweep)
            if os.getppid() == sweep:     # a process of the sweep's own, about to import the
                # stack (joblib sweep, 4 jobs on 2 workers: 16.1 -> 15.2 s of CPU)
                from ..base.lifetime import collect_less

                collect_less()
        if config.hydra.mode != RunMode.MULTIRUN or config.hydra.output_subdir is not None:
            return
        from ..base.files import atomic_write_text

        folder = Path(str(config.hydra.runtime.output_dir)) / ".hydra"
        task = OmegaConf.masked_copy(config, [k for k in config if k != "hydra"])
        atomic_write_text(folder / "overrides.yaml", OmegaConf.to_yaml(config.hydra.overrides.task))
        atomic_write_text(folder / "config.yaml", OmegaConf.to_yaml(task))

    def _abandon(self, config: DictConfig) -> None:
        if self.run_id is None:
            return
        from .tracking import end_parent_run

        try:
            end_parent_run(config, self.run_id, "FAILED")
            _say(f"sweep parent run {self.run_id} closed as FAILED (the sweep stopped early)")
        except Exception as exc:  # interpreter exit: report, never raise
            _say(f"could not close sweep parent run {self.run_id}: {exc}")
        self.run_id = None

    def on_multirun_end(self, config: DictConfig, **kwargs: Any) -> None:
        if self.run_id is None:
            return
        from mlflow import MlflowClient

        from .tracking import PARENT_ENV, child_runs, connect, end_parent_run

        run_id = self.run_id
        children = child_runs(MlflowClient(connect(config)), run_id)
        # a job that failed before its child run started (bad data: read first) has no child;
        # the shell's note (local launchers) and the sweep's size count it
        notes = os.environ.get(FAILED_JOBS_ENV)
        noted = len(list(Path(notes).glob("*.json"))) if notes and Path(notes).is_dir() else 0
        failed = max(sum(r.info.status != "FINISHED" for r in children), noted)
        jobs = max(len(children), sweep_size(config.hydra.overrides.task, config.hydra.sweeper) or 0)
        _log_search_results(config, run_id)
        end_parent_run(config, run_id, "FAILED" if failed else "FINISHED",
                       {"sweep.jobs": jobs, "sweep.failed_jobs": failed})
        atexit.unregister(self._abandon)
        self.run_id = None
        if self._previous is None:
            os.environ.pop(PARENT_ENV, None)
        else:
            os.environ[PARENT_ENV] = self._previous
        _say(f"sweep parent run {run_id}: {jobs} jobs ({len(children)} child runs), {failed} failed")
        if self.compare and children:
            try:
                from ..base.paths import resolve
                from .stages.compare import compare_sweep

                given = any(o.startswith("compare.out=") for o in config.hydra.overrides.task)
                compare_sweep(config, run_id, out=resolve(str(
                    config.compare.out if given else config.hydra.sweep.dir)))
            except Exception as exc:  # the sweep itself succeeded; say why there is no table
                _say(f"no comparison table: {' '.join(str(exc).split())}")


def _log_search_results(config: DictConfig, run_id: str) -> None:
    """A search sweeper's ``optimization_results.yaml`` (Optuna: best params and value) on the
    parent run, its best value as the metric ``sweep.best_value``."""
    results = Path(str(config.hydra.sweep.dir)) / "optimization_results.yaml"
    if not results.is_file():
        return
    from mlflow import MlflowClient

    from .tracking import connect, retry_locked

    client = MlflowClient(connect(config))
    retry_locked(client.log_artifact, run_id, str(results))
    best = OmegaConf.load(results).get("best_value")
    if best is not None:
        retry_locked(client.log_metric, run_id, "sweep.best_value", float(best))


def _searches(config: DictConfig) -> bool:
    """Whether the sweeper proposes the jobs from their scores (Optuna) rather than a grid."""
    target = str(config.hydra.sweeper.get("_target_", ""))
    return bool(target) and not target.endswith("BasicSweeper")


class SweepObjective(Callback):
    """Hydra callback: a search sweeper's objective, each job's validation score.

    A search sweeper (``hydra/sweeper=optuna``) needs a number back from every
    job; ``run`` returns its metrics.  When the job ends, its return value
    becomes ``promote.criterion`` of ``promote.target`` (default ``val_rmse``,
    mean over targets): the figure ``compare`` ranks by and ``promote`` chooses
    by, from the val split or cross-validation on the train split, never the test
    split.  So the best trial is the run ``thermocomp promote`` promotes.  A job
    without that figure (``eval.validation=false``) returns NaN: a failed trial.
    """

    def on_multirun_start(self, config: DictConfig, **kwargs: Any) -> None:
        from ..core.scoring.leaderboard import VAL_FIGURES, is_validation

        criterion = str(config.promote.criterion)
        if _searches(config) and not is_validation(criterion):
            # exit 2 with one line, as any bad config (Hydra would turn a raise into status 1)
            print(f"thermocomp: error: promote.criterion={criterion!r} cannot be a search objective: "
                  f"only a validation figure ({', '.join(VAL_FIGURES)}) may choose", file=sys.stderr)
            raise SystemExit(2)

    def on_job_end(self, config: DictConfig, job_return, **kwargs: Any) -> None:
        from hydra.core.utils import JobStatus

        if not _searches(config) or job_return.status != JobStatus.COMPLETED:
            return
        from .sweeps import objective

        metrics = job_return.return_value
        if isinstance(metrics, dict) and "targets" in metrics:
            value = objective(metrics, str(config.promote.criterion), str(config.promote.target))
            _say(f"objective {config.promote.criterion} ({config.promote.target}): {value:.6g}")
            job_return.return_value = value


def sweep_size(task_overrides, sweeper=None) -> int | None:
    """Number of jobs of a sweep, or None: a search sweeper's ``n_trials``, else the product of
    the sweep overrides' lengths (a grid)."""
    from hydra.core.override_parser.overrides_parser import OverridesParser

    trials = (sweeper or {}).get("n_trials")
    if trials is not None:
        return int(trials)
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
        total = sweep_size(config.hydra.overrides.task, config.hydra.sweeper)
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
        value = job_return.return_value if job_return.status == JobStatus.COMPLETED else None
        # a job the shell caught (cli._job_failed) completes for Hydra with NaN, the sweep goes on
        failed = job_return.status != JobStatus.COMPLETED or (isinstance(value, float) and value != value)
        status = "FAILED" if failed else "ok"
        overrides = " ".join(config.hydra.overrides.task)
        _say(f"sweep: {n}/{total or '?'} jobs done (#{num} {status}: {overrides})")

    def on_multirun_end(self, config, **kwargs) -> None:
        import shutil

        # the marks only count jobs: the sweep folder keeps its job folders and nothing else
        shutil.rmtree(Path(str(config.hydra.sweep.dir)) / ".done", ignore_errors=True)
