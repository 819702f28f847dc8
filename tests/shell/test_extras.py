"""Optional dependencies (pyproject extras) and the Optuna sweeper shipped in the package.

A feature whose extra is not installed stops before any work with one line naming the extra
(exit 2): simulated here by hiding the module (a finder that says it is not installed).  The
sweeper's search space is the former plugin's syntax on Optuna's current distributions.
"""

from __future__ import annotations

import sys

import pytest
from hydra.core.override_parser.overrides_parser import OverridesParser

from conftest import refused
from test_hostile import FAST, make_dataset


class _Absent:
    """A meta-path finder for which ``modules`` are not installed."""

    def __init__(self, modules):
        self.modules = modules

    def find_spec(self, name, path=None, target=None):
        if any(name == m or name.startswith(m + ".") for m in self.modules):
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
        return None


def _hide(monkeypatch, *modules: str) -> None:
    """Imports of ``modules`` fail with ModuleNotFoundError, as without their extra (what was
    imported already is put back after the test)."""
    _unplug(monkeypatch, [m for m in modules if m.startswith("hydra_plugins.")])
    for name in list(sys.modules):
        if (any(name == m or name.startswith(m + ".") for m in modules)
                or name == "thermocomp.core.models.lstm"):
            monkeypatch.delitem(sys.modules, name)
    monkeypatch.setattr(sys, "meta_path", [_Absent(modules), *sys.meta_path])


def _unplug(monkeypatch, packages: list[str]) -> None:
    """Hydra's plugin registry as where ``packages`` are not installed, whatever ran before in
    this process: scanned now, before the finder hides them, and their classes taken out.

    The scan imports each plugin module from its file, past ``sys.meta_path``: run after the
    hiding (the first Hydra call of a fresh process: ``-n 2 --dist load`` gave the ray case a
    worker of its own), it loaded the launcher's package half, and the sweep ended in its launch
    with an ImportError of ``_core`` that names no extra (exit 1); run before it, the cached
    launcher class was what the command used (review96)."""
    if not packages:
        return
    from hydra.core.plugins import Plugins

    plugins = Plugins.instance()
    gone = [c for n, c in plugins.class_name_to_class.items() if n.startswith(tuple(packages))]
    for name in [n for n, c in plugins.class_name_to_class.items() if c in gone]:
        monkeypatch.delitem(plugins.class_name_to_class, name)
    for kind, classes in list(plugins.plugin_type_to_subclass_list.items()):
        monkeypatch.setitem(plugins.plugin_type_to_subclass_list, kind,
                            [c for c in classes if c not in gone])


def test_model_lstm_without_torch_names_the_lstm_extra(tmp_path, capsys, monkeypatch):
    data = make_dataset(tmp_path / "ds")
    _hide(monkeypatch, "torch")
    refused(["run", f"data.path={data}", "model=lstm", f"out={tmp_path / 'out'}", *FAST], capsys,
            "model=lstm needs torch", "pip install -e '.[lstm]'")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("module, override, extra", [
    ("optuna", "hydra/sweeper=optuna", "scale"),
    ("hydra_plugins.hydra_ray_launcher", "hydra/launcher=ray", "scale"),
])
def test_a_sweep_without_its_extra_names_it_before_any_job(tmp_path, capsys, monkeypatch,
                                                           module, override, extra):
    data = make_dataset(tmp_path / "ds")
    _hide(monkeypatch, module)
    refused(["run", "-m", f"data.path={data}", override, "model=mlr,pcr", *FAST,
             f"hydra.sweep.dir={tmp_path / 'sweep'}"], capsys, override, f"'.[{extra}]'")
    assert not (tmp_path / "sweep").exists()


def test_a_postgresql_store_without_psycopg2_names_the_team_extra(tmp_path, capsys, monkeypatch):
    import socket

    data = make_dataset(tmp_path / "ds")
    _hide(monkeypatch, "psycopg2")
    with socket.socket() as server:          # a port that answers, as a database server's would
        server.bind(("127.0.0.1", 0))
        server.listen()
        uri = f"postgresql+psycopg2://u@127.0.0.1:{server.getsockname()[1]}/db"
        refused(["run", f"data.path={data}", f"out={tmp_path / 'out'}", *FAST, "track=true",
                 f"tracking_uri={uri}"], capsys, "psycopg2", "'.[team]'")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("stage", ["twin", "connect"])
def test_opc_ua_without_asyncua_names_the_machine_extra(tmp_path, capsys, monkeypatch, stage):
    # audit95: `make run` installs the core; the README's twin / connect then ended in a
    # ModuleNotFoundError traceback, exit 1, not the extra's one line
    data = make_dataset(tmp_path / "ds")
    model = tmp_path / "model.pkl"
    model.write_bytes(b"")
    _hide(monkeypatch, "asyncua")
    # the stages import the OPC UA modules when run: one an earlier test imported would be found
    # again with asyncua in it, and the stage would go on to read its model
    for name in [n for n in sys.modules if n.startswith("thermocomp.apps.machine")]:
        monkeypatch.delitem(sys.modules, name)
    words = {"twin": [f"data.path={data}"], "connect": [f"connect.model={model}"]}[stage]
    refused([stage, *words, f"out={tmp_path / 'out'}"], capsys, "asyncua", "'.[machine]'")
    assert not (tmp_path / "out").exists()


def test_a_launcher_config_of_a_missing_plugin_names_its_extra():
    from hydra.errors import MissingConfigException

    from thermocomp.base.extras import MissingExtra, missing

    exc = MissingConfigException("not found", missing_cfg_file="hydra/launcher/submitit_slurm")
    assert isinstance(missing(exc), MissingExtra) and "'.[scale]'" in str(missing(exc))
    assert missing(ModuleNotFoundError("No module named 'nope'", name="nope")) is None


def _dist(override: str):
    from hydra_plugins.thermocomp_optuna.optuna_sweeper import distribution

    return distribution(OverridesParser.create().parse_override(override))


def test_the_sweepers_search_space_reads_the_former_plugins_syntax():
    from optuna.distributions import CategoricalDistribution, FloatDistribution, IntDistribution

    assert _dist("model.estimator.max_inputs=range(1,10)") == IntDistribution(1, 10)  # inclusive
    assert _dist("a=range(0,1,0.25)") == FloatDistribution(0, 1, step=0.25)
    assert _dist("a=interval(0.3,0.999)") == FloatDistribution(0.3, 0.999)
    assert _dist("a=interval(1,8)") == FloatDistribution(1.0, 8.0)                 # as Hydra reads it
    assert _dist("a=tag(log,interval(1e-4,1.0))") == FloatDistribution(1e-4, 1.0, log=True)
    assert _dist("a=choice(bic,bicc,aicc)") == CategoricalDistribution(["bic", "bicc", "aicc"])
    assert _dist("model=arx") == "arx"                                    # fixed, not searched


def test_the_grid_sampler_enumerates_each_dimension_once():
    from optuna.distributions import CategoricalDistribution, IntDistribution

    from hydra_plugins.thermocomp_optuna.optuna_sweeper import _grid_values

    assert _grid_values(IntDistribution(1, 4)) == [1, 2, 3, 4]
    assert _grid_values(CategoricalDistribution(["a", "b"])) == ["a", "b"]
