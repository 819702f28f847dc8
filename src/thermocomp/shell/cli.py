"""``thermocomp <stage> [overrides]`` (see ``docs/cli.md``).

Hydra is the one source of configuration.  A command composes its own root config (the groups
it reads, :mod:`.config.commands`) once, with the compose API, so that bad config is one line
and exit status 2 (:mod:`.config.overrides`); a run then goes through Hydra's own job runner
with that config (:func:`_run_job`: its callbacks, job logging and run folder, as under
``hydra.main``, which would compose it twice more), while a sweep (``-m`` / ``--multirun``,
its jobs composed first) and Hydra's own flags (``--cfg job`` ...) go through ``hydra.main``
(:func:`_launch`): launchers, sweepers and callbacks work unchanged.  ``-q``/``-v`` (log level)
and ``-h`` (this command's help; ``--help keys``: its keys) are ours and never reach Hydra.

Exit status: 0 success, 2 bad input or bad config (one line on stderr), 1 otherwise.
"""

from __future__ import annotations

import gc
import json
import os
import sys
import traceback
import warnings
from pathlib import Path

from omegaconf import OmegaConf

from ..base.errors import closest
from ..base.extras import missing
from ..base.lifetime import collect_less, end_left_threads, end_local_workers
from ..base.log import version
from ..base.paths import elsewhere_hint, resolve
from .config import overrides
from .config.commands import COMMANDS, groups_of, register, root_name
from .config.overrides import config_errors as _config_errors
from .config.overrides import lenient, rooted_override
from .resolvers import scenario_dataset

# `${root:reports/x}` in the config: the path under the project root (Hydra's own folders).  At
# import: a sweep's job process unpickles its task from this module before Hydra resolves its dir
OmegaConf.register_new_resolver("root", lambda path=".": str(resolve(path)), replace=True)
OmegaConf.register_new_resolver("sim_dataset", scenario_dataset, replace=True)

# conf/hydra/launcher/ray.yaml extends the Ray launcher plugin's config of
# the same name on purpose (Hydra still validates it against the plugin's schema).
warnings.filterwarnings("ignore", message=r"\s*'hydra/launcher/ray' is validated against")

USAGE = """usage: thermocomp [-q | -v] <stage> [key=value ...] [-m]
       thermocomp <stage> --help | --version

stages:
{commands}

overrides: data.path=<dir> data.inputs=[T_*] data.targets=[E_Z] model=mlr select=all denoise=none
           eval.mode=simulation|one_step out=<dir> tracking_uri=<uri> seed=<int>
options:   -q/--quiet (warnings only)  -v/--verbose (debug, progress bars off a terminal too)
Relative paths are resolved against the project root.""".format(
    commands="\n".join(f"  {name:<10} {c.summary}" for name, c in COMMANDS.items()))
LOG_FLAGS = {"-q": "WARNING", "--quiet": "WARNING", "-v": "DEBUG", "--verbose": "DEBUG"}
# BLAS on one thread unless the user says otherwise: this project's matrices are tens of columns
# wide, where a second BLAS thread on a shared 2-core machine spins against the other processes
# (an MLR run on 43 lathe runs: 7.6 s CPU with OpenBLAS's 2 threads, 2.8 s with one). Set before
# numpy loads OpenBLAS (it reads the variable then); sweep jobs and servers inherit it.
BLAS_THREADS_ENV = "OPENBLAS_NUM_THREADS"
if not any(os.environ.get(k) for k in (BLAS_THREADS_ENV, "OMP_NUM_THREADS")):
    os.environ[BLAS_THREADS_ENV] = "1"
# MLflow 3 fetches a config and sends usage events from background threads, and writes an
# installation id under ~/.config/mlflow: a lab's tool sends nothing unasked.  Off in this
# process and those it starts (sweep jobs, the server) unless the user set it (false: on).
TELEMETRY_ENV = "MLFLOW_DISABLE_TELEMETRY"


def stage_help(stage: str) -> str:
    c = COMMANDS[stage]
    return (f"usage: thermocomp [-q | -v] {stage} [key=value ...]\n\n{stage}: {c.what}\n"
            f"  reads:     {c.reads}\n  writes:    {c.writes}\n  overrides: {c.overrides}\n"
            "  common:    out=<dir> name=<run> track=false tracking_uri=<uri> seed=<int> plots=...\n\n"
            f"its keys:    thermocomp {stage} --help keys [<group>]   (default, type, what each does)\n"
            f"full config: thermocomp {stage} --cfg job   (one group: --cfg job --package model)\n"
            f"Hydra's help: thermocomp {stage} --hydra-help")


def _print_keys(stage: str, group: str | None) -> int:
    """``thermocomp <stage> --help keys [group]``: the keys the command composes, from the schema."""
    from .config.describe import describe

    try:
        cfg = overrides.compose([], stage)
        if group is not None and cfg.get(group) is None:
            _fail(f"--help keys {group}: thermocomp {stage} composes no group {group!r} "
                  f"(it composes {', '.join(groups_of(stage))})")
    except SystemExit as exc:
        return exc.code
    from omegaconf import open_dict

    choices = dict(cfg.hydra.runtime.choices)
    with open_dict(cfg):
        del cfg["hydra"]
    print(describe(cfg, choices, group))
    return 0


def _fail(msg: str):
    # The error line is spelled out at the print: test_no_bare_print_for_progress_in_src
    # tells an error line from a progress print by it.
    said = ' '.join(str(msg).split())
    print(f"thermocomp: error: {said}", file=sys.stderr)
    refused = SystemExit(2)
    refused.said = f"thermocomp: error: {said}"   # a sweep job's reason, kept in its folder
    raise refused


def _guarded(fn, *args):
    """Call ``fn``; bad input/config -> one line on stderr and exit 2 (a file the user named
    that cannot be read -- no permission, a symlink loop -- is bad input too)."""
    try:
        return fn(*args)
    except ModuleNotFoundError as exc:
        if not missing(exc):
            raise
        _fail(missing(exc))
    except _config_errors() as exc:
        if missing(exc):
            _fail(missing(exc))
        # a generator's own check in its __init__ comes wrapped by Hydra's instantiate: its line
        # (our own errors keep theirs: they name the file of the cause they wrap)
        wrapped = not isinstance(exc, _config_errors()[0]) and isinstance(exc.__cause__, _config_errors()[0])
        err = exc.__cause__ if wrapped else exc
        _fail(f"{err}{elsewhere_hint(getattr(err, 'file', None))}")
    except PermissionError as exc:
        _fail(f"file {exc.filename}: cannot be read or written here ({exc.strerror})")
    except RuntimeError as exc:
        if "Symlink loop" not in str(exc):      # pathlib's resolve() on a loop of links
            raise
        _fail(f"{exc}: a path that links to itself")


def _check_seed(cfg) -> None:
    """``seed`` steers every random choice of every stage: an integer, checked before any."""
    from ..base.errors import ConfigError

    seed = cfg.get("seed")
    if isinstance(seed, bool) or not isinstance(seed, int) or not 0 <= seed < 2 ** 32:
        # NumPy's legacy RandomState (random forests, LSTM init) takes seeds below 2**32
        raise ConfigError(f"seed={seed!r} is not an integer in [0, 2**32 - 1]")


def _compose(args: list[str], command: str | None = None):
    """The config a stage gets (no ``hydra`` node), composed as a run composes it; its overrides
    name the MLflow run (a library caller's or a test's way to a command's config)."""
    from hydra.core.hydra_config import HydraConfig
    from omegaconf import open_dict

    cfg = overrides.compose(args, command)
    HydraConfig.instance().set_config(cfg)
    with open_dict(cfg):
        del cfg["hydra"]
    return cfg


def _check_hydra_node(cfg, sweeping: bool) -> None:
    """What Hydra itself builds (callbacks, launcher, sweeper, logging), checked before it does:
    ``hydra.callbacks.x._target_=builtins.open`` was called with its arguments before any job."""
    from .build import check_built
    from .config.apart import check_apart

    _guarded(check_built, cfg.hydra, "hydra")     # resolved: Hydra imports them anyway
    if sweeping:                                  # Hydra writes multirun.yaml there first
        _guarded(check_apart, cfg, ("hydra.sweep.dir",), ())


def _log_folder(stage: str, cfg):
    """Where the run's ``thermocomp.log`` goes: the stage's output folder."""
    def folder():
        if stage == "compare" and cfg.get("compare") is not None:
            out = cfg.compare.get("out")     # null: beside the sweep (set once it is known)
            return resolve(out) if out is not None else None
        if stage == "rows":      # it writes on stdout only: no log file left in `out`
            return None
        return resolve(cfg.out) if cfg.get("out") else None
    return folder


def _per_job(cfg):
    """In a multirun every job writes under its own Hydra output folder."""
    from hydra.core.hydra_config import HydraConfig
    from omegaconf import open_dict

    if _multirun():
        out = HydraConfig.get().runtime.output_dir
        with open_dict(cfg):
            cfg.out = out
            cfg.model_path = f"{out}/model.pkl"
    return cfg


def _run(stage: str, cfg, args: list[str]):
    """Run ``stage`` on ``cfg`` with its log file (``<out>/thermocomp.log`` on success)."""
    from ..base import log
    from ..base.files import signals_raise
    from .build import check_targets
    from .config.rules import check_schema
    from .stages import stage as lookup

    _guarded(_check_seed, cfg)   # before anything is written, the log file included
    _guarded(check_targets, cfg)     # a _target_ of the project's, named anywhere in it
    # every value within its domain (what check_config starts with) before the stage's module
    # loads its libraries: a mistyped value is refused in a second, not after SciPy and sklearn
    _guarded(check_schema, cfg)
    fn = lookup(stage)
    # SIGTERM anywhere in the stage (reading, fitting) ends it with status 1 and a message,
    # as the contract's statuses say, not 143; a library's warnings go to the log, one line each;
    # what the reader says of a file, once however often the stage reads it
    with signals_raise(), log.warnings_logged(), log.said_once(), log.run_log(_log_folder(stage, cfg)):
        log.logger.debug("thermocomp %s: %s %s", version(), stage, " ".join(args))
        return _guarded(fn, cfg)


def _job_failed(exc: BaseException) -> float:
    """A sweep job that failed: said on stderr and noted for the end of the sweep, which goes
    on (its MLflow child run is already FAILED).  NaN: a failed trial for a search sweeper."""
    from hydra.core.hydra_config import HydraConfig

    from ..base.files import write_json
    from ..base.log import logger
    from .callbacks import FAILED_JOB, FAILED_JOBS_ENV

    code = exc.code if isinstance(exc, SystemExit) and isinstance(exc.code, int) else 1
    job = HydraConfig.get().job
    overrides = list(HydraConfig.get().overrides.task)
    if not isinstance(exc, SystemExit):
        traceback.print_exc()
    logger.error("sweep job %s (%s) failed with exit status %d; the sweep goes on",
                 job.num, " ".join(overrides), code)
    note = {"job": job.num, "overrides": overrides, "exit": code,
            "said": getattr(exc, "said", None) or (f"{type(exc).__name__}: {exc}"
                                                   if not isinstance(exc, SystemExit) else None)}
    # (audit99) why, in the job's own folder: a job refused on its data has no child run, and
    # compare's "their errors are in the sweep's log" named a log no sweep with a failed job keeps
    own = Path(HydraConfig.get().runtime.output_dir)
    if own.is_dir():
        write_json(own / FAILED_JOB, note)
    folder = os.environ.get(FAILED_JOBS_ENV)
    if folder and Path(folder).is_dir():    # absent on a remote node (Ray, SLURM): MLflow has it
        write_json(Path(folder) / f"{job.num}.json", note)
    return float("nan")


def _task(stage: str, args: list[str], raised: list):
    """The function Hydra runs as a job: the stage on the job's config.  A run's exception is
    kept in ``raised`` (Hydra would report it in many lines, exit 1), for :func:`main` to say as
    it says any; a sweep job's failure is noted and the sweep goes on."""
    from ..base.files import Terminated

    def task(cfg):
        # the stage's module is imported by the process that runs it (in _run): a sweep's parent
        # only launches its jobs (joblib, Ray, SLURM) and never needs the models' libraries
        try:
            return _run(stage, _per_job(cfg), args)
        except Terminated:
            raise
        except (SystemExit, Exception) as exc:   # one bad job of a sweep does not end the others
            if _multirun() and not (isinstance(exc, SystemExit) and exc.code in (0, None)):
                return _job_failed(exc)
            if isinstance(exc, SystemExit):
                raise
            raised.append(exc)
    return task


def _run_job(stage: str, args: list[str], cfg) -> None:
    """A run: Hydra's own job runner on the config composed once (what ``hydra.main`` does for a
    run after composing it twice more): its callbacks, job logging and run folder."""
    from hydra._internal.callbacks import Callbacks
    from hydra.core.utils import run_job
    from hydra.types import HydraContext, RunMode

    raised = []
    cfg.hydra.mode = RunMode.RUN
    callbacks = Callbacks(cfg)
    callbacks.on_run_start(config=cfg, config_name=root_name(stage))
    ret = run_job(task_function=_task(stage, args, raised), config=cfg, job_dir_key="hydra.run.dir",
                  job_subdir_key=None,     # run_job reads only the callbacks of its context
                  hydra_context=HydraContext(config_loader=None, callbacks=callbacks))
    callbacks.on_run_end(config=cfg, config_name=root_name(stage), job_return=ret)
    _ = ret.return_value     # an exception that escaped the task: raised again, as Hydra's run does
    if raised:
        raise raised[0]


def _launch(stage: str, args: list[str]) -> None:
    """Run ``stage`` under ``hydra.main``: a sweep (``-m``: Hydra's launchers, sweepers and
    callbacks) and Hydra's own flags (``--cfg job`` ...)."""
    import tempfile

    import hydra

    from ..base.log import logger
    from ..base.paths import conf_dir
    from .callbacks import FAILED_JOBS_ENV

    register(stage)
    raised = []
    task = hydra.main(config_path=str(conf_dir()), config_name=root_name(stage),
                      version_base="1.3")(_task(stage, args, raised))
    sys.argv = [f"thermocomp-{stage}", *args]
    with tempfile.TemporaryDirectory(prefix="thermocomp-sweep-") as notes:
        previous = os.environ.get(FAILED_JOBS_ENV)
        os.environ[FAILED_JOBS_ENV] = notes
        try:
            task()
        finally:
            if previous is None:
                os.environ.pop(FAILED_JOBS_ENV, None)
            else:
                os.environ[FAILED_JOBS_ENV] = previous
            end_local_workers()
        failed = [json.loads(f.read_text()) for f in sorted(Path(notes).glob("*.json"))]
    if raised:
        raise raised[0]
    if failed:
        logger.error("%d sweep job(s) failed: %s", len(failed), "; ".join(
            f"{f['job']} ({' '.join(f['overrides'])}): exit {f['exit']}" for f in failed))
        raise SystemExit(max(f["exit"] for f in failed))


def _multirun() -> bool:
    from hydra.core.hydra_config import HydraConfig
    from hydra.types import RunMode

    return HydraConfig.initialized() and HydraConfig.get().mode == RunMode.MULTIRUN


# Hydra's flags whose next word is theirs (`--cfg job`, `--package data`), and `--info`'s topics
# (its word is optional): no file that `init` / `rows` names
VALUED_FLAGS = {"-c", "--cfg", "-p", "--package", "--experimental-rerun", *overrides.CONFIG_FLAGS}
INFO_TOPICS = {"all", "config", "defaults", "defaults-tree", "plugins", "searchpath"}


def _positional_path(args: list[str]) -> list[str]:
    """``thermocomp init <path>`` (``rows <path>``): the path (relative to the current folder, as a shell user
    names a file) as ``data.path``; a word a Hydra flag takes (``--cfg job``) left to it."""
    out = []
    for arg in args:
        flag = out[-1] if out else ""
        owned = flag in VALUED_FLAGS or (flag in ("-i", "--info") and arg in INFO_TOPICS)
        if "=" not in arg and not arg.startswith("-") and not owned:
            path = Path(arg).expanduser()
            arg = f"data.path={path.resolve() if path.exists() else arg}"
        out.append(arg)
    return out


_signalled: list[str] = []     # the command main() runs was ended by SIGTERM or Ctrl-C


def main(argv: list[str] | None = None) -> int:
    """``thermocomp <argv>`` (the command line's when None); its exit status."""
    if argv is None:      # the process is the command's (the console script, python -m)
        collect_less()
    _signalled.clear()
    code = _command(list(sys.argv[1:] if argv is None else argv))
    if argv is None:
        if _signalled:     # what the signal left of a library's threads ends with the process
            end_left_threads(code)
        # The process ends with this status (the console script, `python -m thermocomp`): its
        # objects frozen out of the collector, the interpreter's last collections do not walk
        # every imported module's objects (~0.6 s of CPU per command; the atexit handlers, the
        # stream flushes and the module teardown still run).
        gc.freeze()
    return code


def _command(argv: list[str]) -> int:
    from ..base import log

    os.environ.setdefault(TELEMETRY_ENV, "true")     # before anything imports MLflow
    levels = [LOG_FLAGS[a] for a in argv if a in LOG_FLAGS]
    argv = [a for a in argv if a not in LOG_FLAGS]
    log.configure(levels[-1] if levels else "INFO")
    if argv and argv[0] in ("-V", "--version"):
        print(f"thermocomp {version()}")
        return 0
    if not argv or argv[0] in ("-h", "--help", "help"):
        print(USAGE)
        return 0 if argv else 2
    stage, args = argv[0], argv[1:]
    from ..base.files import Terminated
    from ..base.log import logger
    from .stages import STAGES

    if stage not in STAGES:
        close = closest(stage, STAGES)
        hint = f"; did you mean {close[0]!r}?" if close else ""
        print(f"thermocomp: error: unknown stage {stage!r}{hint} (stages: {', '.join(STAGES)})",
              file=sys.stderr)
        return 2
    if any(a in ("-h", "--help") for a in args):
        topic = [a for a in args if a not in ("-h", "--help")]
        if topic[:1] == ["keys"]:       # its keys: default, type and domain, what each does
            return _print_keys(stage, topic[1] if len(topic) > 1 else None)
        print(stage_help(stage))
        return 0
    if stage in ("init", "rows"):
        args = _positional_path(args)
    try:
        args = [rooted_override(a) for a in lenient(args)]
        _guarded(overrides.refuse, args)
        for why in overrides.unread(args, stage):
            logger.warning(why)
        if not any(a.startswith("-") for a in args):       # a run: composed once
            cfg = _guarded(overrides.compose_checked, args, stage)
            _check_hydra_node(cfg, sweeping=False)
            _run_job(stage, args, cfg)
            return 0
        if any(a in ("-m", "--multirun") for a in args):  # a sweep: its jobs composed first
            if any(a.startswith("out=") for a in args):
                logger.warning("in a sweep every job writes to <hydra.sweep.dir>/<job number>: "
                               "out= is not used (set hydra.sweep.dir=...)")
            cfg = _guarded(overrides.check_jobs, args, stage)
            if cfg is not None:
                _check_hydra_node(cfg, sweeping=True)
        elif not any(a in ("-sc", "--shell-completion") for a in args):
            # a Hydra flag (`--cfg job`, `--info`): its overrides composed as a run's are, so a
            # mistyped key or option is exit 2 in one line (Hydra's own composition said it in
            # a multi-line trace, exit 1, and took `--cfg job` with an unknown key as exit 1)
            _guarded(overrides.compose_checked, [a for a in args if "=" in a and not a.startswith("-")],
                     stage)
        _launch(stage, args)                               # a sweep, a Hydra flag: hydra.main
    except Terminated:  # the contract's statuses are 0, 2 and 1 for anything else
        _signalled.append("SIGTERM")
        logger.warning("%s terminated (SIGTERM)", stage)
        return 1
    except SystemExit as exc:
        return exc.code if isinstance(exc.code, int) else 1
    except KeyboardInterrupt:
        _signalled.append("SIGINT")
        logger.warning("%s interrupted (Ctrl-C)", stage)
        return 1
    except Exception as exc:  # anything else is a bug or an environment failure: status 1
        if missing(exc):      # ... but for an optional dependency not installed: its extra
            print(f"thermocomp: error: {missing(exc)}", file=sys.stderr)
            return 2
        traceback.print_exc()
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
