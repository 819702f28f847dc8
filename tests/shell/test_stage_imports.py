"""What a stage process imports before it does anything: every `dvc repro` stage is a fresh
`thermocomp <stage>` process, so an import the stage does not use costs every stage, every time.
The config schema (read by the Hydra callbacks of every command) needs no scikit-learn or SciPy;
`simulate` builds no model."""

import subprocess
import sys


def _loaded(code: str) -> set[str]:
    """Top-level packages loaded by ``code`` in a fresh interpreter."""
    code += "\nimport sys\nprint(' '.join(sorted({m.split('.')[0] for m in sys.modules})))"
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return set(proc.stdout.split())


def test_the_config_schema_imports_no_scikit_learn_nor_scipy():
    loaded = _loaded("import thermocomp.shell.config.schema, thermocomp.shell.config.checks")
    assert not {"sklearn", "scipy"} & loaded


def test_simulate_imports_no_scikit_learn(tmp_path):
    loaded = _loaded("from thermocomp.shell.cli import main\n"
                     f"assert main(['simulate', 'data.path={tmp_path / 'ds'}', 'track=false', "
                     "'sim.generator.n_campaigns=3', 'sim.generator.duration_h=[1.0,1.0]']) == 0")
    assert (tmp_path / "ds").is_dir()
    assert "sklearn" not in loaded


def test_a_sweep_parent_imports_no_model_library():
    """The task a launcher hands its jobs (joblib, Ray, SLURM: other processes) imports the
    stage when a job calls it, not when the parent makes it."""
    loaded = _loaded("from thermocomp.shell.cli import _task\nassert callable(_task('run', [], []))")
    assert not {"sklearn", "scipy"} & loaded
