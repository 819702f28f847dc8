"""The suite's cache of Hydra's composition (tests/hydra_cache.py): the configs and errors plain
Hydra gives, a config file or a ConfigStore node changed is read again, and Hydra is left as it is
for a release the cache was not written against."""

from __future__ import annotations

import dataclasses
import os
import shutil

import hydra
import pytest
from hydra import compose, initialize_config_dir
from hydra.core.config_store import ConfigStore
from hydra.core.global_hydra import GlobalHydra
from hydra.types import RunMode
from omegaconf import OmegaConf

import hydra_cache
from thermocomp.base.paths import conf_dir
from thermocomp.shell.config import commands, overrides

# (command, overrides): roots, group and value overrides together, Hydra's own, and errors
CASES = [
    *[(command, []) for command in ("simulate", "run", "compare", "replay", "design", "calibrate")],
    ("run", ["model=arx", "data.path=/x", "model.estimator.fit_intercept=false"]),
    ("run", ["data.path=/y", "model=arx"]),                         # same groups, other values
    ("run", ["model=arx_rf", "ati=cmeans", "denoise=emd", "select=pearson"]),
    ("run", ["hydra/launcher=joblib", "hydra.sweep.dir=/tmp/s", "hydra.job.chdir=false"]),
    ("run", ["data.columns={a: b}", "~model.estimator.fit_intercept", "+extra=1"]),
    ("simulate", ["sim=swiss_lathe_door", "sim.generator.seed=3"]),
    ("run", ["model=no_such_model"]),                               # errors: a group option,
    ("run", ["model.estimator.no_such_key=1"]),                     # a key,
    ("run", ["model=arx", "data.path=[1,2"]),                       # a parse error
    ("run", ["+model=mlr"]),
]


def _outcome(command: str, args: list[str]):
    """The composed config as yaml with its flags, or the error Hydra raised (type and text)."""
    try:
        cfg = overrides.compose(args, command)
    except Exception as exc:                      # noqa: BLE001 - the error is the outcome
        return type(exc).__name__, str(exc)
    return (OmegaConf.to_yaml(cfg), OmegaConf.is_struct(cfg), OmegaConf.is_readonly(cfg.hydra),
            OmegaConf.to_yaml(cfg.hydra.runtime.choices))


def test_the_cache_is_on_in_this_suite():
    assert hydra_cache.supported() and hydra_cache.install()


def _plain(outcomes):
    """``outcomes()`` with plain Hydra; the cache is on (and empty) again after it."""
    hydra_cache.uninstall()
    try:
        return outcomes()
    finally:
        assert hydra_cache.install()


def test_cached_compositions_are_plain_hydras_configs_and_errors():
    expected = _plain(lambda: [_outcome(c, a) for c, a in CASES])
    first = [_outcome(c, a) for c, a in CASES]          # misses, kept
    kept = len(hydra_cache._entries)
    again = [_outcome(c, a) for c, a in CASES]          # from the cache
    assert kept >= 6                                    # it did keep them
    for case, want, miss, hit in zip(CASES, expected, first, again):
        assert miss == want, case
        assert hit == want, case


def test_a_sweeps_master_config_is_plain_hydras():
    """A multirun composes with skip_missing and its sweep overrides (``model=mlr,pcr``)."""
    def master():
        commands.register("run")
        with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
            cfg = GlobalHydra.instance().hydra.compose_config(
                commands.root_name("run"), ["model=mlr,pcr", "data.path=/z", "seed=1,2"],
                run_mode=RunMode.MULTIRUN)
        return OmegaConf.to_yaml(cfg)

    want = _plain(master)
    assert master() == want and master() == want


def _config_value(conf, key: str):
    with initialize_config_dir(config_dir=str(conf), version_base="1.3"):
        return OmegaConf.select(compose(config_name="config", overrides=["track=false"]), key)


def test_an_edited_conf_file_is_read_again_even_with_its_size_and_time_kept(tmp_path):
    """A test edits a copy of conf/ (conftest.set_keys) within a clock tick of composing it."""
    conf = tmp_path / "conf"
    shutil.copytree(conf_dir(), conf)
    mlr = conf / "model" / "mlr.yaml"
    text = mlr.read_text()
    assert "fit_intercept: true" in text
    assert _config_value(conf, "model.estimator.fit_intercept") is True
    stat = mlr.stat()
    mlr.write_text(text.replace("fit_intercept: true", "fit_intercept: null"))   # 4 letters each
    os.utime(mlr, ns=(stat.st_atime_ns, stat.st_mtime_ns))
    assert mlr.stat().st_size == stat.st_size and mlr.stat().st_mtime_ns == stat.st_mtime_ns
    assert _config_value(conf, "model.estimator.fit_intercept") is None


def test_a_new_option_file_is_found_and_a_removed_one_is_gone(tmp_path):
    conf = tmp_path / "conf"
    shutil.copytree(conf_dir(), conf)

    def model(option: str):
        with initialize_config_dir(config_dir=str(conf), version_base="1.3"):
            return compose(config_name="config", overrides=[f"model={option}"]).model

    shutil.copy2(conf / "model" / "mlr.yaml", conf / "model" / "mlr2.yaml")
    assert model("mlr2") == model("mlr")
    (conf / "model" / "mlr2.yaml").unlink()
    with pytest.raises(hydra.errors.MissingConfigException):
        model("mlr2")


def test_a_configstore_node_stored_again_is_read_again():
    store = ConfigStore.instance()

    def value():
        with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
            return compose(config_name="hydra_cache_probe").probe

    try:
        store.store(name="hydra_cache_probe", node={"probe": 1})
        assert value() == 1
        store.store(name="hydra_cache_probe", node={"probe": 2})
        assert value() == 2
    finally:
        del store.repo["hydra_cache_probe.yaml"]


def test_a_hit_is_unpickled_not_deep_copied_and_owns_its_config(monkeypatch):
    """A hit copies the pristine config from its pickle (a deep copy cost ~3x the CPU on every
    in-process command); what one command changes in its config is not seen by the next."""
    import copy
    import types

    def once():
        return overrides.compose(["model=arx", "data.path=/x"], "run")

    want = _plain(once)
    first = once()                               # a miss: kept
    deep_copied = []
    monkeypatch.setattr(hydra_cache, "copy", types.SimpleNamespace(
        copy=copy.copy, deepcopy=lambda obj, *args: deep_copied.append(obj) or copy.deepcopy(obj, *args)))
    first.data.path = "/changed"                 # what a command does to its own config
    hit, again = once(), once()
    assert deep_copied == []
    flags = (OmegaConf.is_struct(want), OmegaConf.is_readonly(want.hydra))
    for cfg in (hit, again):
        assert OmegaConf.to_yaml(cfg) == OmegaConf.to_yaml(want) and cfg.data.path == "/x"
        assert (OmegaConf.is_struct(cfg), OmegaConf.is_readonly(cfg.hydra)) == flags
    hit.data.path = "/changed too"
    assert again.data.path == "/x"


def test_a_config_that_does_not_pickle_is_deep_copied_on_a_hit():
    store = ConfigStore.instance()
    local = dataclasses.make_dataclass("Unpicklable", [("probe", int, 3)])  # no module attribute

    def value():
        with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
            return compose(config_name="hydra_cache_local", overrides=["probe=4"]).probe, \
                compose(config_name="hydra_cache_local").probe

    try:
        store.store(name="hydra_cache_local", node=local)
        assert value() == (4, 3) and value() == (4, 3)       # a miss, then hits
        entry = next(e for e in hydra_cache._entries.values()
                     if e.config is not None and "probe" in e.config and "model" not in e.config)
        assert entry.pickled == b""
    finally:
        del store.repo["hydra_cache_local.yaml"]


def test_a_composition_copies_the_repository_not_the_config_store(monkeypatch, tmp_path):
    """Each composition copied Hydra's whole config repository, the ConfigStore in it (half a
    cached composition's CPU); a search path one composition adds is still not seen by the next."""
    import copy
    import types

    from hydra._internal import config_repository

    deep_copied = []
    monkeypatch.setattr(config_repository, "copy", types.SimpleNamespace(
        deepcopy=lambda obj, *args: deep_copied.append(type(obj).__name__) or copy.deepcopy(obj, *args)))
    extra = tmp_path / "extra" / "model"
    extra.mkdir(parents=True)
    shutil.copy2(conf_dir() / "model" / "mlr.yaml", extra / "mlr_extra.yaml")
    searched = f"hydra.searchpath=[file://{extra.parent}]"
    assert overrides.compose([searched, "model=mlr_extra"], "run").model == \
        overrides.compose(["model=mlr"], "run").model
    assert deep_copied == []
    with pytest.raises(hydra.errors.MissingConfigException):
        overrides.compose(["model=mlr_extra"], "run")


@pytest.mark.parametrize("change", ["version", "source"])
def test_another_hydra_release_is_left_as_it_is(monkeypatch, change):
    from hydra._internal import config_loader_impl

    hydra_cache.uninstall()
    try:
        plain = config_loader_impl.create_defaults_list
        if change == "version":
            monkeypatch.setattr(hydra, "__version__", "1.4.0")
        else:
            monkeypatch.setitem(hydra_cache.SOURCES, "create_defaults_list", "0" * 64)
        assert not hydra_cache.supported()
        assert not hydra_cache.install()
        assert config_loader_impl.create_defaults_list is plain
        assert overrides.compose(["model=arx"], "run").model.name == "arx"
    finally:
        monkeypatch.undo()
        assert hydra_cache.install()
