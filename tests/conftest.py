"""Shared fixtures: small simulated datasets, written once per session."""

from __future__ import annotations

import contextlib
import copy
import functools
import inspect
import io
import os
import shutil
import subprocess
import sys
from pathlib import Path
from subprocess import CompletedProcess
from subprocess import run as run_process

import numpy as np
import pandas as pd
import pytest

import durations
import hydra_cache
from thermocomp.base.lifetime import collect_less

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
# tests/ and its folders: a subprocess that unpickles or builds a test class (``_target_=
# test_deploy.ARStub``) finds it wherever that test module lives
TEST_PATH = os.pathsep.join(str(d) for d in (ROOT / "tests", *sorted((ROOT / "tests").glob("*/")))
                            if d.name != "__pycache__")
# the test-local estimators a config may build (thermocomp.shell.build): an environment setting
os.environ.setdefault("THERMOCOMP_TARGETS", "test_deploy.,test_tracking.")

# Hydra's defaults list and merged config per (conf files, root, group overrides), value overrides
# applied afresh: an in-process command composes in ~0.03 s of CPU instead of ~0.2 (tests/hydra_cache.py;
# off for a Hydra release other than the one it was written against).
hydra_cache.install()

# The collector's thresholds of a command's process (thermocomp.base.lifetime.GC_THRESHOLDS), before
# the test modules import the stack: a worker's collection of the suite spent 3.4 s of CPU in the
# collector at Python's (1.05 s at these), a test module 5-8 % of its CPU (test_hostile: 2.0 s).
collect_less()

# The fast overrides, one home: what a CLI call in a test switches off when none of its
# assertions is about it.  UNTRACKED: no MLflow run; LIGHT: the report extras (figures, one
# refit per campaign for mutual prediction, the ATI baselines, the ISO 10791-10 A.3 test);
# FAST: both and no validation folds.
UNTRACKED = ("track=false",)
LIGHT = ("plots=none", "eval.mutual_prediction=false", "eval.ati_baselines=false",
         "eval.iso10791_a3=false")
FAST = (*UNTRACKED, *LIGHT, "eval.validation=false")
# diagnose's before/after figures streamed through the plain deployed stream, not the adaptive
# compensator around it (its sensor monitor and guard step every test sample: ~60 % of a
# diagnosis's CPU on test_diagnose_pde66's record): for a diagnose call none of whose assertions
# is about the adaptive stream (test_diagnose_deployed60 and test_deployed_guarded are).  On a
# healthy record, where neither acts, the figures are the same to the last digit.
PLAIN_DIAGNOSE = ("monitor.adaptive=false",)


def thermocomp(*args: str, cwd=None, env=None, check=True,
               subprocess: bool = False) -> CompletedProcess:
    """``thermocomp <args>`` run from ``cwd`` (the project root) with ``env`` added to the
    environment: its exit status, stdout and stderr.

    In this process (:func:`thermocomp.shell.cli.main`, what the console script calls), without
    a new interpreter's ~2.5 s of CPU for the imports: for a test about what a command does
    (scores, files, messages, exit statuses).  ``subprocess=True`` runs the installed console
    script, for a test about the process boundary itself: signals, servers, stdin, concurrent
    processes (a command another one runs while it works)."""
    run = _console if subprocess else _in_process
    proc = run(args, Path(cwd or ROOT), env or {})
    if check and proc.returncode != 0:
        raise AssertionError(f"thermocomp {' '.join(args)} -> {proc.returncode}\n"
                             f"stdout:\n{proc.stdout}\nstderr:\n{proc.stderr}")
    return proc


cli = thermocomp     # the name the first in-process callers use


def _console(args, cwd: Path, env: dict) -> CompletedProcess:
    return run_process([str(BIN / "thermocomp"), *args], cwd=cwd, env={**os.environ, **env},
                       capture_output=True, text=True, timeout=600)


def _in_process(args, cwd: Path, env: dict) -> CompletedProcess:
    from thermocomp.shell.cli import main

    out, err = io.StringIO(), io.StringIO()
    with process_state(cwd, env), contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(list(args))
    return CompletedProcess(["thermocomp", *args], code, out.getvalue(), err.getvalue())


@contextlib.contextmanager
def process_state(cwd: Path, env: dict):
    """Run a block in ``cwd`` with ``env`` added, and put back after it what a command changes
    in its process, so that the next test finds the process as it was: the current folder,
    ``sys.argv``, the environment (``THERMOCOMP_LOG_LEVEL``, ...), the loggers' handlers and
    levels (Hydra's job logging replaces the root's, pytest's capture among them), the
    warning filters, Hydra's global state and MLflow's (its tracking URI, a run left active)."""
    import logging
    import warnings

    from hydra.core.global_hydra import GlobalHydra
    from hydra.core.hydra_config import HydraConfig

    argv, environ, folder = sys.argv[:], dict(os.environ), os.getcwd()
    # MLflow's load_model (a served model, in process) puts the model's code folder first on
    # sys.path for good; an in-process sweep's joblib workers start with this process's sys.path
    # and then import thermocomp from that copy, not from the code under test (seen in CI's
    # tracebacks): a command runs without such folders, and leaves none behind.
    sys.path[:] = _without_model_code(sys.path)
    loggers = [logging.getLogger(), *(lg for lg in logging.Logger.manager.loggerDict.values()
                                      if isinstance(lg, logging.Logger))]
    logs = [(lg, lg.handlers[:], lg.level, lg.propagate, lg.disabled) for lg in loggers]
    hydra_was_up, hydra_config = GlobalHydra.instance().is_initialized(), HydraConfig.instance().cfg
    os.environ.update(env)
    os.chdir(cwd)
    try:
        with warnings.catch_warnings():
            yield
    finally:
        os.chdir(folder)
        sys.argv[:] = argv
        sys.path[:] = _without_model_code(sys.path)
        os.environ.clear()
        os.environ.update(environ)
        for lg, handlers, level, propagate, disabled in logs:
            lg.handlers[:] = handlers
            lg.setLevel(level)
            lg.propagate, lg.disabled = propagate, disabled
        if not hydra_was_up:
            GlobalHydra.instance().clear()
        HydraConfig.instance().cfg = hydra_config
        _restore_mlflow()


def _without_model_code(paths: list[str]) -> list[str]:
    """``paths`` without the code folders of MLflow models (``<model>/code`` beside ``MLmodel``)."""
    return [p for p in paths if not (Path(p).name == "code" and (Path(p).parent / "MLmodel").is_file())]


def _restore_mlflow() -> None:
    """MLflow's tracking URI as the environment just put back says (``set_tracking_uri``
    mirrors it there), no run left active by a command that failed inside it."""
    if "mlflow" not in sys.modules:
        return
    import mlflow

    while mlflow.active_run() is not None:
        mlflow.end_run("FAILED")
    mlflow.set_tracking_uri(os.environ.get("MLFLOW_TRACKING_URI"))


def influence(comp, test: dict) -> dict[str, float]:
    """Per input of the fitted ``comp``: the largest change of its test predictions when that
    reading is raised by 1 °C after the first sample (a constant offset is removed by the
    reference sample, so it would move nothing)."""
    base = comp.predict(test)

    def moved(sensor: str) -> float:
        shifted = comp.predict({c: df.assign(**{sensor: df[sensor] + (np.arange(len(df)) > 0)})
                                for c, df in test.items()})
        return max(float(np.abs(shifted[c] - base[c]).to_numpy().max()) for c in test)

    return {s: moved(s) for s in comp.inputs_}


def refused(args: list[str], capsys, *says: str) -> str:
    """``thermocomp <args>`` (in process) exits 2 with one error line holding every one of
    ``says``; returns that line."""
    from thermocomp.shell.cli import main

    code = main(args)
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if ln.startswith("thermocomp: error")]
    assert code == 2, err
    assert len(lines) == 1, err
    for words in says:
        assert words in lines[0], lines[0]
    return lines[0]


def free_port() -> int:
    """A TCP port on 127.0.0.1 that nothing listens on now."""
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class ZeroStream:
    """A deployed stream of one input whose correction is always 0 (an OPC UA client's test)."""

    columns_ = ["T_a"]

    def reset(self):
        pass

    def step(self, x, t):
        return np.zeros(1)


class NoLimiter:
    """An offset limiter that only hears of a new campaign."""

    started = False          # no offset of its own yet

    def new_campaign(self, held=None):
        pass


def offline_connection(stream=None, **options):
    """A :class:`~thermocomp.apps.machine.client.Connection` to no server, stepped by hand
    (``conn._step``): ``stream`` (default :class:`ZeroStream`) behind a :class:`NoLimiter`."""
    from thermocomp.apps.machine.client import Connection

    return Connection(stream or ZeroStream(), None, "opc.tcp://127.0.0.1:1", NoLimiter(), **options)


def wait_until_up(port: int, server: subprocess.Popen, log_path: Path, timeout_s: float = 120):
    """Wait until the MLflow scoring server on ``port`` answers ``/ping``; fail with its log if
    it exits or is not up after ``timeout_s``."""
    import time

    import requests

    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if server.poll() is not None:
            pytest.fail(f"the server exited {server.returncode}:\n{log_path.read_text()}")
        try:
            if requests.get(f"http://127.0.0.1:{port}/ping", timeout=2).status_code == 200:
                return
        except requests.RequestException:
            pass
        time.sleep(0.5)
    pytest.fail(f"the server is not up after {timeout_s} s:\n{log_path.read_text()}")


def stop_process_group(proc: subprocess.Popen, timeout: float = 20) -> None:
    """Stop a server started with ``start_new_session=True``: SIGTERM its group, SIGKILL if it
    lingers."""
    import signal

    os.killpg(proc.pid, signal.SIGTERM)
    try:
        proc.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait(timeout=timeout)


def ctx(groups=None, **columns) -> pd.DataFrame:
    """A side-input context (thermocomp.core.context): ``campaign`` per row plus any other columns."""
    data = {"campaign": np.asarray(groups, dtype=object)} if groups is not None else {}
    data.update({k: np.asarray(v) for k, v in columns.items()})
    return pd.DataFrame(data)


def stream_context(est, X, context: pd.DataFrame) -> np.ndarray:
    """Feed ``X`` sample by sample through the streaming protocol with each row's context,
    restarting (``stream_init``) at each campaign."""
    out, state = [], None
    records = context.to_dict("records")
    for t, row in enumerate(records):
        if t == 0 or row["campaign"] != records[t - 1]["campaign"]:
            state = est.stream_init(row)
        y, state = est.stream_step(X[t], state, row)
        out.append(y)
    return np.array(out)


def stream_predictions(est, X, groups) -> list[float]:
    """:func:`stream_context` with only the campaign of each row."""
    return stream_context(est, X, ctx(groups)).tolist()


def monitored(mon, record: np.ndarray) -> tuple[np.ndarray, list[dict]]:
    """``record``'s rows (absolute °C, the row's index its time) through the sensor monitor
    ``mon`` one by one: the field it gives the model at each row, and every event."""
    fields, events = [], []
    for i, row in enumerate(record):
        field, ev = mon.update(row, float(i))
        fields.append(field)
        events += ev
    return np.array(fields), events


def simulated(generator, path: Path) -> Path:
    """``path`` written as ``thermocomp simulate`` writes it: the dataset and its truth."""
    from thermocomp.apps.sim.scenario import write_scenario
    from thermocomp.base.files import write_json

    truth, _, _ = write_scenario(generator, path)
    write_json(f"{path}.truth.json", truth)
    return path


def poisoned_copy(src: Path, dest: Path, scale: float = -50.0, offset: float = 1e3) -> Path:
    """A copy of dataset ``src`` whose test campaigns' ``E_`` columns are garbage
    (``E * scale + offset``): whatever a model chooses must not change with it."""
    shutil.copytree(src, dest)
    index = pd.read_csv(src / "campaigns.csv")
    for _, row in index[index["split"] == "test"].iterrows():
        df = pd.read_csv(dest / row["file"])
        errors = [c for c in df.columns if c.startswith("E_")]
        df[errors] = df[errors] * scale + offset
        df.to_csv(dest / row["file"], index=False)
    return dest


@pytest.hookimpl(wrapper=True)
def pytest_collection(session):
    """Collection with byte code written: pytest caches each test module with its asserts
    rewritten (tests/**/__pycache__) only where Python may write byte code, and
    PYTHONDONTWRITEBYTECODE (set on these machines) forbade it, so every worker parsed and
    rewrote every module again (~6 s of a worker's ~13 s of CPU).  This process and this phase
    only: the imports of collection come from tests/, src/ and the venv; a command's process
    (its environment unchanged) writes none, nor does a test in a folder it digests."""
    writes, sys.dont_write_bytecode = sys.dont_write_bytecode, False
    try:
        return (yield)
    finally:
        sys.dont_write_bytecode = writes


def pytest_collection_finish(session):
    """What collection imported (the whole stack: pandas, sklearn, MLflow, torch, ...) lives as
    long as the process: frozen out of the collector, the full collections of the tests that
    follow do not walk it again (test_calibrate.py: 6.7 -> 4.1 s of CPU in the collector, as
    ``thermocomp.shell.cli.main`` freezes a command line's objects at its end)."""
    import gc

    gc.collect()
    gc.freeze()


def pytest_addoption(parser):
    parser.addoption("--store-durations", action="store_true",
                     help="write each scheduling unit's seconds into tests/durations.json "
                          "(the order `make test` starts them in: tests/durations.py)")


def pytest_configure(config):
    # here, not in pyproject.toml's markers: the Makefile reinstalls the package when that changes
    config.addinivalue_line("markers", "full: what tests in `make test` cover (named in its reason or "
                                       "docstring; tests/covering.py): `make test-all`, not `make test` (CI)")
    if config.getoption("store_durations"):
        config.pluginmanager.register(durations.Recorder(_unit), "store-durations")


# -- how `make test`'s xdist workers (`--dist loadfile`) share the tests --------------------
# A module's tests go to one worker (its module fixtures are built once), except these: long
# tests that share nothing costly, each a unit of its own (the README test, one per page).
# Longest first, by measured seconds (tests/durations.py; `pytest --store-durations` updates them).
ALONE = ("tests/test_readme.py::test_page_commands_as_written",)


def _unit(nodeid: str) -> str:
    return nodeid if nodeid.startswith(ALONE) else nodeid.split("::")[0]


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config, log):
    """``--dist loadfile`` with the :data:`ALONE` tests as units of their own, handed out in
    the order of :func:`pytest_collection_modifyitems` (not by number of tests)."""
    if config.getvalue("dist") != "loadfile":
        return None
    from xdist.scheduler import LoadFileScheduling

    class ModulesLongFirst(LoadFileScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return _unit(nodeid)

    config.option.loadscopereorder = False
    return ModulesLongFirst(config, log)


def pytest_collection_modifyitems(items):
    """The longest units first, so that none starts when the other worker is nearly done: by the
    seconds tests/durations.json holds (:func:`durations.longest_first`; a module's own order
    is kept)."""
    units = list(dict.fromkeys(_unit(item.nodeid) for item in items))
    rank = {u: i for i, u in enumerate(durations.longest_first(units, durations.load()))}
    items.sort(key=lambda item: rank[_unit(item.nodeid)])


@pytest.fixture
def plain_hydra():
    """Hydra without the suite's composition cache (tests/hydra_cache.py), for a test of what a
    compose does itself (which files it parses, which overrides): the cache would skip that work."""
    hydra_cache.uninstall()
    yield
    hydra_cache.install()


@pytest.fixture
def paths(tmp_path):
    """The hostile matrix's small dataset (``test_hostile.make_dataset``) and where a run writes
    (``out``, ``interim``, ``model``), with the command-line arguments naming them (``args``)."""
    from test_hostile import make_dataset

    ds = make_dataset(tmp_path / "ds")
    p = {"ds": ds, "out": tmp_path / "reports" / "out", "interim": tmp_path / "interim",
         "model": tmp_path / "models" / "model.pkl"}
    p["args"] = [f"data.path={ds}", f"out={p['out']}", f"data.interim={p['interim']}",
                 f"model_path={p['model']}", *FAST]
    return p


# -- the catalogue of simulated datasets: each built once per test process (an xdist worker)
# and shared by every module that asks for it.  Read-only for the tests: copy one to change it.
SHORT = ("sim.generator.n_campaigns=9", "sim.generator.duration_h=[2.0,3.0]")  # 6 train, 3 test


def _simulate(tmp_path_factory, name: str, *overrides: str) -> Path:
    path = tmp_path_factory.mktemp("catalogue") / name
    cli("simulate", f"data.path={path}", *UNTRACKED, *overrides)
    return path


@pytest.fixture(scope="session")
def default_dataset(tmp_path_factory) -> Path:
    """The default year-round scenario at its default size."""
    return _simulate(tmp_path_factory, "yearround_spindle")


@pytest.fixture(scope="session")
def door_dataset(tmp_path_factory) -> Path:
    """The default scenario with an undeclared door signal ``S_door`` (default size)."""
    return _simulate(tmp_path_factory, "door", "sim.generator.effects=[door]")


@pytest.fixture(scope="session")
def short_dataset(tmp_path_factory) -> Path:
    """9 short year-round campaigns (6 train, 3 test)."""
    return _simulate(tmp_path_factory, "clean", *SHORT)


@pytest.fixture(scope="session")
def short_door_dataset(tmp_path_factory) -> Path:
    """9 short year-round campaigns (6 train, 3 test) with an undeclared door signal ``S_door``."""
    return _simulate(tmp_path_factory, "door", *SHORT, "sim.generator.effects=[door]")


@pytest.fixture(scope="session")
def parsed_block(tmp_path_factory) -> str:
    """The Structured Text block test_export's ``test_the_structured_text_parses_as_iec_61131_3``
    parses with blark, built once per test process: a module's export held to it
    (``test_export.parses_as_the_parsed_block``) need not be parsed again."""
    from test_export import PARSED_BLOCK, _deployed, _make_dataset
    from thermocomp.apps.deploy.export import exported_files

    data = _make_dataset(tmp_path_factory.mktemp("parsed_block") / "data")
    return exported_files(_deployed(data, *PARSED_BLOCK)[0], "st")["compensator.st"]


def copied_once(make):
    """``make`` run once per its arguments (their values, defaults filled in) for the tests of a
    worker, each call answered with a deep copy of that result: a module's tests share one fit
    and may step, reset or change what they get.  A ``tmp_path_factory`` argument says where the
    first call writes, not what it makes: no part of the key (so modules share a record they each
    pass their factory for)."""
    made, signature = {}, inspect.signature(make)

    @functools.wraps(make)
    def copy_of(*args, **kwargs):
        bound = signature.bind(*args, **kwargs)
        bound.apply_defaults()
        key = repr({name: value for name, value in bound.arguments.items()
                    if not isinstance(value, pytest.TempPathFactory)})
        if key not in made:
            made[key] = make(*args, **kwargs)
        return copy.deepcopy(made[key])
    return copy_of


def deployed_as_replay(cfg) -> tuple:
    """``(the model cfg configures, fitted on its train split and deployed as replay deploys it,
    the dataset, its test campaign ids)``: the plain stream with ``promote.envelope``
    (``builders.deploy_stream``) made deployable (``builders.deployable``: the adaptive
    compensator around it under ``monitor.adaptive``).  One home: the served monitor's and the
    exported code's tests each wrote these lines out again (review95: 13 modules)."""
    from thermocomp.shell.builders import build_compensator, deploy_stream, deployable
    from thermocomp.shell.source import read_streamed

    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    stream = deploy_stream(cfg, build_compensator(cfg, ds=ds).fit(train), train)
    return deployable(cfg, stream, train, ds), ds, test_ids


# the measured spindle (datasets/fl_thermal, its last 10 % the test campaign), adaptive MLR
FL_THERMAL_MLR = ("data=fl_thermal", "track=false", "monitor.adaptive=true", "model=mlr")


def fl_thermal_served() -> tuple:
    """``(adaptive MLR fitted on fl_thermal's train part and deployed as replay deploys it, its
    system with the monitor, the test campaign)``: a new fit and frame at each call (a module's
    fixture changes its frame)."""
    from test_export import _compose
    from thermocomp.apps.deploy.export import state_space

    deployed, ds, test_ids = deployed_as_replay(_compose(*FL_THERMAL_MLR))
    # a copy of its own: the reader's columns are Arrow's read-only buffers, and once ``ds`` is
    # collected pandas (copy on write) sees no other user and writes into them in place
    return (deployed, state_space(deployed, monitor=True),
            ds.campaigns[test_ids[-1]].reset_index(drop=True).copy())


def set_keys(path: Path, **values) -> None:
    """Set ``key: value`` on the first line of the YAML file ``path`` that holds ``key:`` (its
    indent and any other line kept): a scratch copy's config made smaller, as a user edits it."""
    text = path.read_text()
    for key, value in values.items():
        old = next(line for line in text.splitlines() if line.strip().startswith(f"{key}:"))
        indent = old[:len(old) - len(old.lstrip())]
        text = text.replace(old, f"{indent}{key}: {value}")
    path.write_text(text)


# SHORT as keys of conf/sim/<scenario>.yaml's generator, for a scratch copy of the project whose
# pipeline simulates the default study: a test of which stages DVC runs and what it shows.
SHORT_KEYS = dict(o.removeprefix("sim.generator.").split("=") for o in SHORT)


def dvc(*args: str, cwd, env) -> subprocess.CompletedProcess:
    """The venv's ``dvc <args>`` in ``cwd``; it must succeed."""
    proc = subprocess.run([str(Path(sys.executable).parent / "dvc"), *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return proc


def copy_project(dest: Path) -> tuple[Path, dict]:
    """A scratch copy of the project (its `.venv` a link to this one) and an environment whose
    PATH does NOT hold the venv: `dvc repro` must work as a new user types it."""
    dest.mkdir()
    for item in ("conf", "src", "dvc.yaml", ".dvc", "pipelines"):
        src = ROOT / item
        if src.is_dir():
            # src's byte code as `make install` leaves it (times kept: a stale file is compiled
            # anew): under PYTHONDONTWRITEBYTECODE every stage process compiled the package again
            # (0.2-0.3 s of CPU each; test_dvc_metrics starts ten)
            skip = ("tmp",) if item == "src" else ("__pycache__", "tmp")
            shutil.copytree(src, dest / item, ignore=shutil.ignore_patterns(*skip))
        else:
            shutil.copy2(src, dest / item)
    os.symlink(Path(sys.executable).parent.parent, dest / ".venv")
    git = dict(GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@t", GIT_COMMITTER_NAME="t",
               GIT_COMMITTER_EMAIL="t@t")
    venv_bin = str(Path(sys.executable).parent)
    path = os.pathsep.join(p for p in os.environ["PATH"].split(os.pathsep)
                           if p and Path(p).resolve() != Path(venv_bin).resolve())
    env = {**os.environ, **git, "THERMOCOMP_ROOT": str(dest), "PATH": path}
    env.pop("VIRTUAL_ENV", None)
    # The study as committed, minus the report extras that refit one model per campaign:
    # this test is about what DVC reruns, not about the report (tested elsewhere).
    eval_conf = dest / "conf/eval/default.yaml"
    eval_conf.write_text(eval_conf.read_text().replace("mutual_prediction: true",
                                                       "mutual_prediction: false"))
    subprocess.run(["git", "init", "-q"], cwd=dest, check=True)
    return dest, env
