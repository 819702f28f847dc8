"""The typed config (issue 35 item 5): one schema (``shell/config/schema.py``) whose rules every
stage checks on the config as composed, and from which ``--help`` and the run's MLflow params
and name are derived."""

from __future__ import annotations

import ast
import functools
import os
from pathlib import Path

import pytest
from hydra import compose, initialize_config_dir
from hydra.experimental.callback import Callback
from omegaconf import OmegaConf

import thermocomp.shell.cli  # noqa: F401  (registers the resolvers conf/ uses)
import thermocomp.shell.stages
from thermocomp.base.errors import ConfigError
from thermocomp.base.paths import conf_dir
from thermocomp.shell.cli import _compose, main
from thermocomp.shell.config import rules as rule_tables
from thermocomp.shell.config.commands import COMMANDS, groups_of
from thermocomp.shell.config.naming import PARAM_KEYS, _entries, run_name, run_params
from thermocomp.shell.config.overrides import group_options as _group_options
from thermocomp.shell.config.rules import check_schema
from thermocomp.shell.config.schema import Root, fields
from thermocomp.shell.stages import STAGES
from thermocomp.shell.tracking import config_container

KEYS = [name for name, f in fields(Root) if f.metadata["rule"] is not None]
# values no config key takes: each key is set to the first its rule refuses
WRONG = ("§ not a value", {"not": "a value"}, -1.5, [-1.5], None)


@functools.cache
def _composed():
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=["track=false"])
    OmegaConf.set_struct(cfg, False)
    return cfg


def test_the_composed_defaults_hold_every_schema_key_and_pass_its_rule():
    cfg = _composed()
    absent = [k for k, _ in fields(Root) if OmegaConf.select(cfg, k, default="<absent>") == "<absent>"]
    assert not absent, f"schema keys conf/ does not have: {absent}"
    check_schema(cfg)


@pytest.mark.parametrize("key", KEYS)
def test_a_wrong_value_of_every_schema_key_is_refused_naming_the_key(key):
    cfg = _composed()
    rule = dict(fields(Root))[key].metadata["rule"]
    wrong = next(v for v in WRONG if not rule(v))
    before = OmegaConf.select(cfg, key)
    OmegaConf.update(cfg, key, wrong, merge=False)
    try:
        with pytest.raises(ConfigError, match=rf"^{key.replace('.', '[.]')}="):
            check_schema(cfg)
    finally:
        OmegaConf.update(cfg, key, before, merge=False)


def test_the_stages_rule_tables_are_the_schemas():
    # one source: a key added to the schema is in the table its stage checks
    assert set(rule_tables.MONITOR_RULES) == {k for k in KEYS if k.startswith("monitor.")}
    assert set(rule_tables.DIAGNOSE_RULES) == {k[len("diagnose."):] for k in KEYS
                                               if k.startswith("diagnose.")}
    assert rule_tables.SERVE_RULES["serve.port"] is dict(fields(Root))["serve.port"].metadata["rule"]


# -- one root config per command ---------------------------------------------------------------

def test_every_command_names_a_stage_function_and_its_root_composes_and_resolves():
    # one table: the stage a command runs is a field of its entry (imported only when it runs)
    assert STAGES == {name: c.stage for name, c in COMMANDS.items()}
    for command in COMMANDS:
        module, function = COMMANDS[command].stage.split(":")
        source = (Path(thermocomp.shell.stages.__file__).parent / f"{module}.py").read_text()
        assert function in {n.name for n in ast.parse(source).body if isinstance(n, ast.FunctionDef)}
    for command in COMMANDS:
        cfg = _compose(["track=false"], command)
        groups = {k for k in cfg if _group_options(k)}
        assert groups == set(groups_of(command)) - {"experiment"}, command
        OmegaConf.to_container(cfg, resolve=True)     # every interpolation has its group


def test_compare_composes_no_model_no_monitor():
    cfg = _compose([], "compare")
    assert not {"model", "monitor", "adapt", "serve", "select"} & set(cfg)
    assert cfg.compare.sort_by


def test_serve_composes_what_makes_a_model_pkl_deployable():
    cfg = _compose([], "serve")         # a run's model.pkl: deployed on data.path's train split
    assert {"data", "monitor", "adapt", "serve"} <= set(cfg)
    assert cfg.serve.model == "models:/thermocomp-compensator@champion"


@pytest.mark.parametrize("command, override, group", [
    ("compare", "model=arx", "model"), ("compare", "adapt.method=bias", "adapt"),
    ("compare", "monitor.window=3", "monitor"), ("calibrate", "+diagnose.alpha=0.1", "diagnose")])
def test_a_group_the_command_does_not_read_is_refused_in_one_line(capsys, command, override, group):
    assert main([command, override]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"does not read the {group} group" in err[0], err
    assert ", ".join(groups_of(command)) in err[0]


@pytest.mark.parametrize("command", ["replay", "monitor", "export", "connect", "serve"])
def test_model_path_given_to_a_command_with_a_model_key_of_its_own_is_said_to_be_ignored(
        capsys, command):
    # replay model_path=<pkl> streamed a model fitted anew on the train split, without a word
    main([command, "model_path=/nowhere/model.pkl", "data.path=/nowhere"])
    err = capsys.readouterr().err
    assert f"model_path is not read by thermocomp {command}" in err
    assert f"{command}.model=<path> names the model" in err


def test_the_commands_with_a_model_key_of_their_own_are_those_named():
    from thermocomp.shell.config.commands import COMMANDS, MODEL_KEYS

    composed = {c: _compose([], c) for c in COMMANDS}
    have = {c for c, cfg in composed.items() if "model" in (cfg.get(c) or {})}
    assert have == set(MODEL_KEYS)


@pytest.mark.parametrize("command", ["train", "ingest", "run"])
def test_model_path_is_not_questioned_where_read_or_in_a_chain(capsys, command):
    main([command, "model_path=/nowhere/model.pkl", "data.path=/nowhere"])
    assert "is not read by" not in capsys.readouterr().err


def test_a_typo_in_a_key_the_command_reads_still_gets_its_hint(capsys):
    assert main(["serve", "serve.prot=5002"]) == 2
    assert "did you mean 'serve.port'?" in capsys.readouterr().err


# -- run names, MLflow params and --help from the schema ---------------------------------------

def _reporting_and_fitting_keys():
    """Schema keys marked (or under a group marked) ``reports``; the others that name no run
    by themselves (not ``names``)."""
    meta = dict(_entries())
    marked = {k for k, m in meta.items() if m["reports"]}
    keys = [k for k, _ in fields(Root)]
    reporting = [k for k in keys if any(k == r or k.startswith(f"{r}.") for r in marked)]
    fitting = [k for k in keys if k not in reporting and not meta[k]["names"] and "." in k]
    return reporting, fitting


def test_a_key_the_schema_marks_as_reporting_never_names_a_run_any_other_does():
    cfg = _compose([], "run")
    reporting, fitting = _reporting_and_fitting_keys()
    assert {"out", "data.path", "eval.validation", "promote.alias", "serve.port"} <= set(reporting)
    for key in reporting:
        assert run_name(cfg, [f"{key}=7"]) == "mlr", key
    assert {"monitor.window", "data.reference", "diagnose.alpha"} <= set(fitting)
    for key in fitting:
        assert run_name(cfg, [f"{key}=7"]) == f"mlr-{key.rsplit('.', 1)[-1]}=7", key


def test_the_logged_params_are_the_schemas():
    logged = {k for k, meta in _entries() if meta.get("logged")}
    assert set(PARAM_KEYS) == logged
    assert {"seed", "data.path", "eval.mode", "model.name", "select.name"} <= logged
    cfg = _compose(["seed=3"], "run")
    assert logged <= set(run_params(config_container(cfg)))


def test_help_keys_lists_every_key_with_its_default_type_domain_and_comment(capsys):
    assert main(["compare", "--help", "keys"]) == 0
    lines = capsys.readouterr().out.splitlines()
    cfg = _compose([], "compare")
    listed = {line.split(" = ")[0].strip(): line for line in lines}
    for key, f in fields(Root):
        if key.split(".")[0] in cfg:
            assert key in listed, key
            if f.metadata["rule"] is not None:
                assert f": {f.metadata['rule'].says})" in listed[key], listed[key]
    assert not any(k.startswith(("serve.", "model.", "monitor.")) for k in listed)
    # the default as written and the comment beside it in conf/serve/default.yaml
    assert main(["serve", "--help", "keys"]) == 0
    listed = {line.split(" = ")[0].strip(): line for line in capsys.readouterr().out.splitlines()}
    assert listed["serve.host"].startswith("  serve.host = 127.0.0.1  (str: a non-empty text)")
    assert listed["serve.host"].endswith("0.0.0.0 to listen on every interface (no authentication!)")
    assert listed["serve.model"].startswith("  serve.model = models:/${promote.model_name}@")


def test_help_keys_of_one_group_and_of_a_group_the_command_lacks(capsys):
    assert main(["run", "--help", "keys", "eval"]) == 0
    keys = [line.split(" = ")[0].strip() for line in capsys.readouterr().out.splitlines()]
    assert keys and all(k.startswith("eval.") for k in keys) and "eval.validation_folds" in keys
    assert main(["run", "--help", "keys", "monitor"]) == 2
    assert "composes no group 'monitor'" in capsys.readouterr().err


# -- a run: its config composed once, its job run by Hydra with its callbacks --------------------

class RunProbe(Callback):
    """A Hydra callback noting the jobs it saw (a run's are Hydra's, as a sweep's)."""

    seen: list = []

    def on_job_start(self, config, **kwargs):
        RunProbe.seen.append((str(config.hydra.mode), config.hydra.job.override_dirname))


@pytest.fixture
def composes(monkeypatch) -> list:
    """The configs Hydra composes from now on (their root names), counted where Hydra loads one."""
    from hydra._internal.config_loader_impl import ConfigLoaderImpl

    seen, load = [], ConfigLoaderImpl.load_configuration

    def counted(self, config_name, *args, **kwargs):
        seen.append(config_name)
        return load(self, config_name, *args, **kwargs)

    monkeypatch.setattr(ConfigLoaderImpl, "load_configuration", counted)
    return seen


def test_a_run_composes_once_and_runs_its_hydra_callbacks(tmp_path, monkeypatch, capsys, composes):
    # under hydra.main a run was composed three times (our check, Hydra's mode, Hydra's run):
    # half the CPU of a small in-process run
    from conftest import FAST
    from test_hostile import make_dataset

    monkeypatch.setenv("THERMOCOMP_TARGETS", f"{os.environ.get('THERMOCOMP_TARGETS', '')},{__name__}.")
    RunProbe.seen.clear()
    probe = f"+hydra.callbacks.probe._target_={__name__}.RunProbe"
    data, out = make_dataset(tmp_path / "data"), tmp_path / "out"
    assert main(["run", f"data.path={data}", probe, f"out={out}", f"model_path={out}/m.pkl", *FAST]) == 0
    assert composes == ["thermocomp_run"]
    assert RunProbe.seen == [("RunMode.RUN", ",".join(sorted(
        [f"data.path={data}", f"out={out}", f"model_path={out}/m.pkl", *FAST])))]
    assert (out / "metrics.json").is_file() and (out / "thermocomp.log").is_file()
    # a stage's own refusal: one line, exit 2, its job seen by the callbacks all the same
    assert main(["ingest", f"data.path={tmp_path / 'none'}", probe, "track=false"]) == 2
    assert f"{tmp_path / 'none'}: no such file or folder" in capsys.readouterr().err
    assert RunProbe.seen[1:] == [("RunMode.RUN", f"data.path={tmp_path / 'none'},track=false")]
    assert composes == ["thermocomp_run", "thermocomp_ingest"]


def test_a_typo_in_a_sweep_is_one_line_before_any_job(tmp_path, capsys, composes):
    # a key no job has: Hydra's many lines, exit 1, after the sweep folder was made
    from conftest import refused

    sweep = tmp_path / "sweep"
    line = refused(["run", "-m", "model=mlr,pcr", "eval.mdoe=one_step", "track=false",
                    f"hydra.sweep.dir={sweep}"], capsys, "unknown config key 'eval.mdoe'",
                   "did you mean 'eval.mode'?")
    assert "+eval.mdoe" not in line             # never Hydra's advice to add the key
    assert not sweep.exists()


class NestedCommand(Callback):
    """A Hydra callback running a command in-process inside a run (as a test's ``cli()`` may)."""

    codes: list = []

    def on_job_start(self, config, **kwargs):
        NestedCommand.codes.append(main(["ingest", "data.path=/nonexistent/inner", "track=false"]))


def test_a_command_runs_in_process_inside_a_run(monkeypatch, capsys):
    # hydra.main held Hydra's one global instance for the whole run: a command inside it could
    # not compose (exit 1, a traceback); a run composes before it runs, and lets go
    monkeypatch.setenv("THERMOCOMP_TARGETS", f"{os.environ.get('THERMOCOMP_TARGETS', '')},{__name__}.")
    NestedCommand.codes.clear()
    nested = f"+hydra.callbacks.nested._target_={__name__}.NestedCommand"
    assert main(["ingest", "data.path=/nonexistent/outer", nested, "track=false"]) == 2
    assert NestedCommand.codes == [2]
    err = capsys.readouterr().err
    assert "/nonexistent/inner: no such" in err and "/nonexistent/outer: no such" in err
