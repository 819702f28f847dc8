"""``thermocomp <stage> [overrides]`` (see ``docs/cli.md``).

Hydra is the one source of configuration.  A command composes its own root
config (the groups it reads, :mod:`.config.commands`) with the compose API first,
so that bad config is one line and exit status 2; then a run, a sweep (``-m`` /
``--multirun``) and Hydra's own flags (``--cfg job`` ...) all go through
``hydra.main`` (:func:`_launch`), the one entry point: launchers, sweepers and
callbacks work unchanged.  ``-q``/``-v`` (log level) and ``-h`` (this command's
help; ``--help keys``: its keys) are ours and never reach Hydra.

Exit status: 0 success, 2 bad input or bad config (one line on stderr), 1 otherwise.
"""

from __future__ import annotations

import difflib
import json
import os
import sys
import traceback
import warnings
from pathlib import Path

from omegaconf import OmegaConf

from ..base.errors import closest
from ..base.extras import missing
from ..base.log import version
from ..base.paths import resolve
from .config.commands import COMMANDS, groups_of, register, root_name
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
# Objects built from `_target_`: `~key` of an argument leaves the constructor's default.
BUILT = ("model.estimator", "ati.estimator", "denoise.denoiser", "select.selector", "sim.generator")
# Config nodes that are free-form maps: `key={...}` adds keys there (Hydra wants `++key={...}`).
FREE_MAPS = ("data.columns", "data.split_overrides", "sim.generator.effect_params", "design.studies",
             "model.candidate_defaults")



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
        cfg = _compose_hydra([], stage)
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


def _config_errors() -> tuple[type, ...]:
    from hydra.errors import HydraException
    from omegaconf.errors import OmegaConfBaseException

    from ..base.errors import ThermocompError

    return (ThermocompError, HydraException, OmegaConfBaseException)


def _fail(msg: str):
    print(f"thermocomp: error: {' '.join(str(msg).split())}", file=sys.stderr)
    sys.exit(2)


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
        _fail(exc.__cause__ if wrapped else exc)
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


# Another primary config or config folder would escape the check of what Hydra builds.
CONFIG_FLAGS = ("-cp", "--config-path", "-cn", "--config-name", "-cd", "--config-dir")


def _check_hydra_node(args: list[str], command: str) -> None:
    """The config composed before ``hydra.main`` runs, so that a run's bad override is one line
    (Hydra's report of it is many, exit 1), and what Hydra itself builds (callbacks, launcher,
    sweeper, logging) checked: ``hydra.callbacks.x._target_=builtins.open`` was called with its
    arguments before any job.  A sweep composes its ``hydra`` node without sweep overrides (a
    job's own errors are the job's)."""
    from hydra.core.override_parser.overrides_parser import OverridesParser

    flag = next((a.split("=")[0] for a in args if a.split("=")[0] in CONFIG_FLAGS), None)
    if flag:
        _fail(f"{flag}: thermocomp composes conf/ of its project; add config folders with "
              "hydra.searchpath=[file://<dir>]")
    plain = not any(a.startswith("-") for a in args)     # a run: no sweep, no Hydra flag
    parser = OverridesParser.create()
    fixed = list(args) if plain else []
    for arg in [] if plain else args:
        if arg.startswith("-"):
            continue
        try:
            if parser.parse_override(arg).is_sweep_override():
                continue
        except Exception:
            return                    # Hydra reports it, before building anything
        fixed.append(arg)
    try:
        cfg = _compose_hydra(fixed, command)
    except _config_errors() as exc:
        if missing(exc):              # a launcher config its plugin (an extra) registers
            _fail(missing(exc))
        if plain:
            _fail(_explain(exc, command))
        return                        # as above: Hydra's own message, nothing built
    from .build import check_built
    from .config.apart import check_apart

    _guarded(check_built, cfg.hydra, "hydra")     # resolved: Hydra imports them anyway
    if any(a in ("-m", "--multirun") for a in args):   # Hydra writes multirun.yaml there first
        _guarded(check_apart, cfg, ("hydra.sweep.dir",), ())


def _root(command: str | None) -> str:
    """The root config ``command`` composes (None: the whole ``conf/config.yaml``)."""
    if command is None:
        return "config"
    register()
    return root_name(command)


def _compose_hydra(overrides: list[str], command: str | None = None):
    from hydra import compose, initialize_config_dir

    from ..base.paths import conf_dir

    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3",
                               job_name="thermocomp"):
        return compose(config_name=_root(command), overrides=overrides, return_hydra_config=True)


def _compose(overrides: list[str], command: str | None = None):
    from hydra.core.hydra_config import HydraConfig
    from omegaconf import open_dict

    cfg = _compose_hydra(overrides, command)
    HydraConfig.instance().set_config(cfg)   # the overrides name the MLflow run, as under hydra.main
    with open_dict(cfg):
        del cfg["hydra"]
    return cfg


def lenient(args: list[str]) -> list[str]:
    """The overrides as Hydra wants them, for the values the README writes.

    ``key=value`` that Hydra's grammar rejects (``data.delimiter=;``, ``data.decimal=,``
    as bash passes ``";"`` and ``","``) is retried with the value quoted; ``key={...}``
    on a free-form map (:data:`FREE_MAPS`) becomes ``++key={...}`` (add keys).  Nothing
    else is rewritten, so a typo still fails.
    """
    from hydra.core.override_parser.overrides_parser import OverridesParser

    parser = OverridesParser.create()
    out = []
    for arg in args:
        key, eq, value = arg.partition("=")
        if arg.startswith("-") or not eq:
            out.append(arg)
        elif key in FREE_MAPS and value.startswith("{"):
            out.append(f"++{arg}")
        else:
            try:
                parser.parse_override(arg)
                out.append(arg)
            except Exception:
                plain = not any(c in value for c in "[]{}()'\"") and not value.endswith("\\")
                out.append(f"{key}='{value}'" if plain else arg)
    return out


def _fix_key(key: str, config: dict) -> str | None:
    """``key`` with its first unknown segment replaced by the closest existing one, or None."""
    node, done = config, []
    parts = key.split(".")
    for i, part in enumerate(parts):
        if not isinstance(node, dict):
            return None
        if part not in node:
            close = closest(part, [str(k) for k in node])
            return ".".join([*done, close[0], *parts[i + 1:]]) if close else None
        node, done = node[part], [*done, part]
    return None


def _explain(exc: BaseException, command: str | None = None) -> str:
    """Hydra's message, with the closest option or key when the user made a typo, or the
    groups ``command`` reads when the key is of another."""
    import re

    from hydra.errors import MissingConfigException

    msg = " ".join(str(exc).split())
    if isinstance(exc, MissingConfigException) and exc.missing_cfg_file and exc.options:
        group, _, option = exc.missing_cfg_file.rpartition("/")
        ranked = sorted(exc.options, key=lambda o: -difflib.SequenceMatcher(None, option, o).ratio())
        return f"unknown {group} {option!r}; options, closest first: {', '.join(ranked)}"
    m = re.match(r"Could not override '([^']+)'", msg)
    if m:
        key = m.group(1)
        if _unread_group(key, command):
            return _unread_group(key, command)
        close = _fix_key(key, _whole_config())
        if close:
            return f"unknown config key {key!r}; did you mean {close!r}? ({msg})"
    return msg


def _whole_config() -> dict:
    """``conf/config.yaml`` as composed (every group, unresolved): where a typo's hint is found,
    whatever group it is of."""
    from omegaconf import OmegaConf, open_dict

    cfg = _compose_hydra([])
    with open_dict(cfg):
        del cfg["hydra"]
    return OmegaConf.to_container(cfg, resolve=False)


def _unread_group(key: str, command: str | None) -> str | None:
    """Why ``key`` is not in ``command``'s config when it is a key (or the choice) of a group
    the command does not compose (its root config, :mod:`.config.commands`), else None."""
    group = key.lstrip("+~").replace("/", ".").split(".")[0]
    if command is None or group in groups_of(command) or _group_options(group) is None:
        return None
    node = _whole_config()
    for part in key.lstrip("+~").split("."):
        if not isinstance(node, dict) or part not in node:
            return None                  # not a key of the group either: a typo, hinted
        node = node[part]
    return (f"{key}: thermocomp {command} does not read the {group} group (it composes "
            f"{', '.join(groups_of(command))})")


def _check_overrides(args: list[str], command: str) -> None:
    """What Hydra accepts but no stage would read as meant, refused with one line (exit 2):
    a config group set to ``null`` or removed with ``~`` (Hydra's ValueError or OmegaConf's
    'not in struct' name no key), a swept group option that does not exist (many lines, exit
    1), and a key added with ``+``/``++`` that the config does not have (``+diagnose.alpah``
    was silently ignored)."""
    from hydra.core.override_parser.overrides_parser import OverridesParser

    parser = OverridesParser.create()
    parsed, base = [], []
    for arg in args:
        if arg.startswith("-"):
            continue
        try:
            parsed.append((arg, parser.parse_override(arg)))
        except Exception:
            base.append(arg)         # composing reports it with Hydra's message
    sweeping = any(a in ("-m", "--multirun") for a in args)
    if sweeping and any(a.startswith("out=") for a in args):
        from ..base.log import logger

        logger.warning("in a sweep every job writes to <hydra.sweep.dir>/<job number>: out= is "
                       "not used (set hydra.sweep.dir=...)")
    added = []
    for arg, o in parsed:
        if _check_group_or_deletion(arg, o, sweeping and not any(
                a.startswith("hydra.searchpath") for a in args)):    # options from elsewhere
            added.append(o.key_or_group)
        elif not o.is_sweep_override():
            base.append(arg)
    if added:
        _check_added_keys(added, base, command)
    if sweeping:
        _check_sweep_jobs([a for a in args if not a.startswith("-")], command)


MAX_CHECKED_JOBS = 100   # jobs of a grid sweep composed up front (~0.1-0.3 s each)


def _check_sweep_jobs(args: list[str], command: str) -> None:
    """Compose the jobs of a grid sweep before any runs.  Hydra composes each job in its
    launcher, and one it cannot compose (a key that only some of the swept models have) ended
    the whole sweep with Hydra's multi-line message, exit 1, no job run; here it is one line
    naming the job, exit 2.  A search sweeper's intervals are not enumerated."""
    import itertools

    from hydra import compose, initialize_config_dir
    from hydra.core.override_parser.overrides_parser import OverridesParser
    from hydra.errors import OverrideParseException

    from ..base.paths import conf_dir

    parser = OverridesParser.create()
    fixed, groups, keys = [], {}, []
    try:
        for arg in args:
            o = parser.parse_override(arg)
            if not o.is_sweep_override():
                fixed.append(arg)
            elif _group_options(o.key_or_group) is not None:
                groups[o.key_or_group] = [f"{o.get_key_element()}={v}" for v in o.sweep_string_iterator()]
            else:
                keys.append(o)
    except Exception:     # an interval, a sweeper's own syntax, a parse error: Hydra says it
        return
    # what can fail is a key set inside a swept group that some of its options lack: one job
    # per combination of the swept groups, a swept key at its first value
    inside = [a.lstrip("+~").split("=", 1)[0] for a in fixed] + [o.key_or_group for o in keys]
    if not any(k.startswith(f"{g.replace('/', '.')}.") for k in inside for g in groups):
        return
    fixed += [f"{o.get_key_element()}={next(iter(o.sweep_string_iterator()))}" for o in keys]
    failed = None
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3", job_name="thermocomp"):
        for job in itertools.islice(itertools.product(*groups.values()), MAX_CHECKED_JOBS):
            try:
                compose(config_name=_root(command), overrides=[*fixed, *job])
            except OverrideParseException:   # a value this re-spelling does not quote as typed
                return
            except _config_errors() as exc:
                failed = job, exc
                break
    if failed:                             # explained outside: the explanation composes too
        _fail(f"sweep job {' '.join(failed[0])}: {_explain(failed[1], command)}")


def _group_options(key: str) -> list[str] | None:
    """The options of config group ``key`` (``conf/<key>/*.yaml``), None if it is no group."""
    from ..base.paths import conf_dir

    folder = conf_dir() / key.replace(".", "/")
    return sorted(f.stem for f in folder.glob("*.yaml")) if folder.is_dir() else None


def _check_group_or_deletion(arg: str, o, check_swept: bool) -> bool:
    """Refuse a deletion outside an object's arguments or a free map, a group set to null, a
    swept group option that does not exist; True when ``o`` adds a key (checked later)."""
    from hydra.core.override_parser.types import OverrideType

    key = o.key_or_group
    if o.type == OverrideType.DEL and not any(key.startswith(f"{m}.") for m in (*FREE_MAPS, *BUILT)):
        _fail(f"~{key}: thermocomp reads every key and group of its config; set it instead "
              f"({key}=...)")
    options = _group_options(key)
    if options is None:
        return o.type in (OverrideType.ADD, OverrideType.FORCE_ADD) and not key.startswith("hydra.")
    if not o.is_sweep_override() and o.value() is None:
        _fail(f"{key}=null: the config group {key!r} needs one of its options ({', '.join(options)})")
    if check_swept and o.is_sweep_override():
        try:
            values = list(o.sweep_string_iterator())
        except Exception:            # a search dimension (interval, glob): the sweeper reports it
            values = []
        for value in values:
            if value not in options:
                _fail(f"unknown {key} {value!r} in the sweep {arg}; options: {', '.join(options)}")
    return False


def _check_added_keys(added: list[str], base: list[str], command: str) -> None:
    """Each added key exists in the config composed without them, or lies under a free-form
    map (:data:`FREE_MAPS`) or an object built by ``_target_`` (its constructor checks it)."""
    from omegaconf import OmegaConf

    config = OmegaConf.to_container(_compose_or_explain(base, command), resolve=False)
    for key in added:
        node, parts = config, key.split(".")
        for i, part in enumerate(parts):
            if ".".join(parts[:i]) in FREE_MAPS or (isinstance(node, dict) and "_target_" in node):
                break
            if not isinstance(node, dict) or part not in node:
                if _unread_group(key, command):
                    _fail(_unread_group(key, command))
                close = _fix_key(key, _whole_config())
                hint = f"; did you mean {close!r}?" if close else ""
                _fail(f"unknown config key {key!r} (added with '+'): thermocomp reads no such "
                      f"key{hint}")
            node = node[part]


def _compose_or_explain(args: list[str], command: str):
    try:
        return _compose(args, command)
    except _config_errors() as exc:
        _fail(_explain(exc, command))


def _log_folder(stage: str, cfg):
    """Where the run's ``thermocomp.log`` goes: the stage's output folder."""
    def folder():
        if stage == "compare" and cfg.get("compare") is not None:
            out = cfg.compare.get("out")     # null: beside the sweep (set once it is known)
            return resolve(out) if out is not None else None
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


def _run(stage: str, fn, cfg, args: list[str]):
    """Run stage ``fn`` on ``cfg`` with its log file (``<out>/thermocomp.log`` on success)."""
    from ..base import log
    from ..base.files import signals_raise
    from .build import check_targets

    _guarded(_check_seed, cfg)   # before anything is written, the log file included
    _guarded(check_targets, cfg)     # a _target_ of the project's, named anywhere in it
    # SIGTERM anywhere in the stage (reading, fitting) ends it with status 1 and a message,
    # as the contract's statuses say, not 143; a library's warnings go to the log, one line each
    with signals_raise(), log.warnings_logged(), log.run_log(_log_folder(stage, cfg)):
        log.logger.debug("thermocomp %s: %s %s", version(), stage, " ".join(args))
        return _guarded(fn, cfg)


def _job_failed(exc: BaseException) -> float:
    """A sweep job that failed: said on stderr and noted for the end of the sweep, which goes
    on (its MLflow child run is already FAILED).  NaN: a failed trial for a search sweeper."""
    from hydra.core.hydra_config import HydraConfig

    from ..base.files import write_json
    from ..base.log import logger
    from .callbacks import FAILED_JOBS_ENV

    code = exc.code if isinstance(exc, SystemExit) and isinstance(exc.code, int) else 1
    job = HydraConfig.get().job
    overrides = list(HydraConfig.get().overrides.task)
    if not isinstance(exc, SystemExit):
        traceback.print_exc()
    logger.error("sweep job %s (%s) failed with exit status %d; the sweep goes on",
                 job.num, " ".join(overrides), code)
    folder = os.environ.get(FAILED_JOBS_ENV)
    if folder and Path(folder).is_dir():    # absent on a remote node (Ray, SLURM): MLflow has it
        write_json(Path(folder) / f"{job.num}.json", {"job": job.num, "overrides": overrides,
                                                       "exit": code})
    return float("nan")


def _launch(stage: str, args: list[str]) -> None:
    """Run ``stage`` under ``hydra.main``: the one entry point of a run and of a sweep (``-m``:
    Hydra's launchers, sweepers and callbacks).  A run's exception is raised again past Hydra
    (which would report it in many lines, exit 1), for :func:`main` to say as it says any."""
    import tempfile

    import hydra

    from ..base.files import Terminated
    from ..base.log import logger
    from ..base.paths import conf_dir, rooted_override
    from .callbacks import FAILED_JOBS_ENV
    from .stages import stage as lookup

    fn = lookup(stage)
    raised = []

    @hydra.main(config_path=str(conf_dir()), config_name=_root(stage), version_base="1.3")
    def task(cfg):
        try:
            return _run(stage, fn, _per_job(cfg), args)
        except Terminated:
            raise
        except (SystemExit, Exception) as exc:   # one bad job of a sweep does not end the others
            if _multirun() and not (isinstance(exc, SystemExit) and exc.code in (0, None)):
                return _job_failed(exc)
            if isinstance(exc, SystemExit):
                raise
            raised.append(exc)

    sys.argv = [f"thermocomp-{stage}", *map(rooted_override, args)]
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


def _positional_path(args: list[str]) -> list[str]:
    """``thermocomp init <path>``: the path (relative to the current folder, as a shell user
    names a file) as ``data.path``."""
    out = []
    for arg in args:
        if "=" not in arg and not arg.startswith("-"):
            path = Path(arg).expanduser()
            arg = f"data.path={path.resolve() if path.exists() else arg}"
        out.append(arg)
    return out


def main(argv: list[str] | None = None) -> int:
    from ..base import log

    argv = list(sys.argv[1:] if argv is None else argv)
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
    if stage == "init":
        args = _positional_path(args)
    try:
        args = lenient(args)
        _check_overrides(args, stage)
        _check_hydra_node(args, stage)
        _launch(stage, args)
    except Terminated:  # the contract's statuses are 0, 2 and 1 for anything else
        logger.warning("%s terminated (SIGTERM)", stage)
        return 1
    except SystemExit as exc:
        return exc.code if isinstance(exc.code, int) else 1
    except KeyboardInterrupt:
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
