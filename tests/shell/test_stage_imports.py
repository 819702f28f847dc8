"""What a stage process imports before it does anything: every `dvc repro` stage is a fresh
`thermocomp <stage>` process, so an import the stage does not use costs every stage, every time.
The config schema (read by the Hydra callbacks of every command) needs no scikit-learn or SciPy;
`simulate` builds no model; a model.pkl exports without MLflow; a CSV dataset is read without
Parquet's reader."""

import os
import subprocess
import sys

import pytest

from conftest import FAST
from test_hostile import make_dataset

SHOW = "import sys\nprint(' '.join(sorted({*sys.modules, *(m.split('.')[0] for m in sys.modules)})))"


def _loaded(code: str, env: dict | None = None) -> set[str]:
    """Modules (``pyarrow.parquet``) and top-level packages (``sklearn``) loaded by ``code`` in a
    fresh interpreter (``env``: its environment)."""
    proc = subprocess.run([sys.executable, "-c", f"{code}\n{SHOW}"], capture_output=True, text=True,
                          env=env)
    assert proc.returncode == 0, proc.stderr
    return set(proc.stdout.split())


def _loaded_after_each(steps: dict[str, str], env: dict | None = None) -> dict[str, set[str]]:
    """What :func:`_loaded` says after each of ``steps`` (name -> code), run one after the other
    in one fresh interpreter (one start, ~1 s of CPU, instead of one each).  A step's set holds
    what the steps before it loaded too: a module it must not load is absent from its own
    imports as well; one it must load is checked where no step before loads it."""
    code = "\n".join(f"{body}\nprint('=== {name}')\n{SHOW}" for name, body in steps.items())
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert proc.returncode == 0, proc.stderr
    found = {}
    for block in proc.stdout.split("=== ")[1:]:
        name, _, modules = block.partition("\n")
        found[name] = set(modules.split())
    assert list(found) == list(steps), proc.stdout[-2000:]
    return found


@pytest.fixture(scope="module")
def chained(tmp_path_factory):
    """The steps of this module that load no MLflow in one interpreter: ``(loaded after each, a
    scratch folder)``.  The order keeps each check exact: ``--cfg job`` first (it must load the
    tracking module), simulate before anything loads scikit-learn, the MLR run before any other
    family, the model classes last (they must load what no step before loads)."""
    tmp = tmp_path_factory.mktemp("stage_imports")
    data = make_dataset(tmp / "ds")
    run = ["run", f"data.path={data}", f"out={tmp / 'run'}", "model=mlr", *FAST]
    steps = {
        "cfg job": "import contextlib, io\nfrom thermocomp.shell.cli import main\n"
                   "with contextlib.redirect_stdout(io.StringIO()):\n"
                   "    assert main(['run', '--cfg', 'job']) == 0",
        "schema": "import thermocomp.shell.config.schema, thermocomp.shell.config.checks",
        "sweep task": "from thermocomp.shell.cli import _task\nassert callable(_task('run', [], []))",
        "out of domain": "from thermocomp.shell.cli import main\n"
                         f"assert main(['run', 'track=false', 'out={tmp / 'out'}', "
                         "'eval.mode=simulaton']) == 2",
        "simulate": "from thermocomp.shell.cli import main\n"
                    f"assert main(['simulate', 'data.path={tmp / 'sim'}', 'track=false', "
                    "'sim.generator.n_campaigns=3', 'sim.generator.duration_h=[1.0,1.0]']) == 0",
        "mlr run": "import contextlib, io\nfrom thermocomp.shell.cli import main\n"
                   "with contextlib.redirect_stdout(io.StringIO()):\n"
                   f"    assert main({run!r}) == 0\n"
                   f"    assert main(['init', '{data / 'K01.csv'}', 'out={tmp / 'init'}']) == 0",
        "model classes": "from hydra.utils import get_class\nfrom thermocomp.core.models import ARXRF\n"
                         "assert get_class('thermocomp.core.models.ARX').__name__ == 'ARX'\n"
                         "import thermocomp.core.models as m\nassert {'MLR', 'LSTM'} <= set(dir(m))",
    }
    return _loaded_after_each(steps), tmp


def test_the_config_schema_imports_no_scikit_learn_nor_scipy(chained):
    loaded = chained[0]["schema"]
    assert not {"sklearn", "scipy"} & loaded


def test_printing_a_commands_config_imports_no_pandas(chained):
    """``--cfg job`` (Hydra's callbacks -> tracking -> the run name's schema) reads no data: the
    core's choices the schema names (``eval.mode``, ``data.reference``) come without pandas."""
    loaded = chained[0]["cfg job"]
    assert "thermocomp.shell.tracking" in loaded     # the edge that dragged pandas in
    assert not {"pandas", "pyarrow"} & loaded


def test_a_value_out_of_its_domain_is_refused_before_the_stage_loads_its_libraries(chained):
    """A mistyped value is exit 2 in one line without the stage's module, which for ``run``
    loads scikit-learn and SciPy (~1.5 s of CPU)."""
    loaded, tmp_path = chained[0]["out of domain"], chained[1]
    assert "thermocomp.shell.stages.modelling" not in loaded
    assert not {"sklearn", "scipy"} & loaded
    assert not (tmp_path / "out").exists()


def test_simulate_imports_no_scikit_learn(chained):
    loaded, tmp_path = chained[0]["simulate"], chained[1]
    assert (tmp_path / "sim").is_dir()
    assert "sklearn" not in loaded
    assert "scipy.signal" not in loaded      # its sensor lags: SciPy's linear algebra (~0.6 s less)


def test_an_mlr_run_imports_no_other_familys_library(chained):
    """``thermocomp.core.models`` imports a family on first use: an MLR run (and ``init``, which
    builds the configured MLR to check it) loads neither arx_rf's forest (``sklearn.ensemble``,
    ~0.2 s of CPU) nor SciPy's ``signal`` (the dynamic families' filter); the names of the
    package resolve all the same (the next test)."""
    loaded, tmp_path = chained[0]["mlr run"], chained[1]
    assert (tmp_path / "run" / "metrics.json").is_file() and (tmp_path / "init" / "conf").is_dir()
    assert "sklearn.linear_model" in loaded           # it did fit the MLR
    assert not {"sklearn.ensemble", "scipy.signal", "thermocomp.core.models.arx_rf",
                "thermocomp.core.models.arx", "thermocomp.core.models.lstm"} & loaded


def test_the_model_classes_resolve_by_name_and_load_their_family_then(chained):
    """The names of ``thermocomp.core.models`` (a package import, Hydra's targets) load a
    family's module when asked for it, not before."""
    before, loaded = chained[0]["mlr run"], chained[0]["model classes"]
    assert not {"sklearn.ensemble", "thermocomp.core.models.arx"} & before
    assert {"sklearn.ensemble", "thermocomp.core.models.arx"} <= loaded


def test_a_sweep_parent_imports_no_model_library(chained):
    """The task a launcher hands its jobs (joblib, Ray, SLURM: other processes) imports the
    stage when a job calls it, not when the parent makes it."""
    loaded = chained[0]["sweep task"]
    assert not {"sklearn", "scipy"} & loaded


def _user_env(config_home) -> dict:
    """A user's environment (no PYTEST_CURRENT_TEST: it would switch MLflow's telemetry off by
    itself), MLflow's installation id kept under ``config_home``."""
    env = {k: v for k, v in os.environ.items() if k in ("PATH", "PYTHONPATH", "HOME", "LANG")}
    return {**env, "XDG_CONFIG_HOME": str(config_home)}


@pytest.fixture(scope="module")
def exported(chained):
    """An export of a model.pkl, then ``--version`` and MLflow's telemetry client, in one
    interpreter of a user's environment: ``(loaded after each, a scratch folder)``.  The model.pkl
    is the one ``chained``'s MLR run wrote (the default model, FAST, on make_dataset's data; ci104e:
    this fixture made the same run again, in this process)."""
    tmp = chained[1]
    data = tmp / "ds"
    steps = {
        "export": "from thermocomp.shell.cli import main\n"
                  f"assert main(['export', 'data.path={data}', 'track=false', "
                  f"'export.model={tmp / 'run' / 'model.pkl'}', 'out={tmp / 'c'}']) == 0",
        "telemetry": "from thermocomp.shell.cli import main\nassert main(['--version']) == 0\n"
                     "from mlflow.telemetry import get_telemetry_client\n"
                     "assert get_telemetry_client() is None, 'telemetry on'",
    }
    from thermocomp.base.signing import KEY_ENV, _key

    # the key that signed the model.pkl (the user's config folder is a fresh one here)
    env = {**_user_env(tmp / "config"), KEY_ENV: _key().decode()}
    return _loaded_after_each(steps, env), tmp


def test_exporting_a_model_pkl_imports_no_mlflow_no_parquet_no_simulator(exported):
    """MLflow (~1.8 s of CPU) is for a pyfunc folder or a registered model, not a model.pkl made
    deployable on a CSV dataset's train split; Parquet's reader (and the ``ssl`` it pulls in) is
    for Parquet files; the simulator's package (``open_source``'s BLAS helper) for a volumetric
    dataset."""
    loaded, tmp_path = exported[0]["export"], exported[1]
    assert (tmp_path / "c" / "compensator.json").is_file()
    assert "mlflow" not in loaded
    assert "pyarrow.parquet" not in loaded
    assert "thermocomp.apps.sim" not in loaded


def test_mlflow_telemetry_is_off_in_a_thermocomp_process_unless_the_user_turns_it_on(exported,
                                                                                   tmp_path):
    """MLflow 3 sends usage events from any process that imports it outside a CI or a test and
    keeps an installation id in the user's config folder (the interpreter of ``exported``
    checked its telemetry client is None)."""
    assert "mlflow.telemetry" in exported[0]["telemetry"]
    assert not (exported[1] / "config" / "mlflow").exists()      # nothing written for it either
    # a user's own setting stands (false: MLflow's telemetry on)
    code = ("import os\nfrom thermocomp.shell.cli import main\nassert main(['--version']) == 0\n"
            "assert os.environ['MLFLOW_DISABLE_TELEMETRY'] == 'false'")
    _loaded(code, {**_user_env(tmp_path), "MLFLOW_DISABLE_TELEMETRY": "false"})
