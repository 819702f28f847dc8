"""Leftovers of the lab-file work (session 53): a model from the registry exports the lab's
names and run column as one from the run does; the compiled C stream reads a logger's
wall-clock times as the served model does."""

from __future__ import annotations

import re

from conftest import FAST
from test_export import _compose
from test_run_column52 import _long, _runs
from thermocomp.shell.builders import deploy_stream, deployable
from thermocomp.shell.cli import main
from thermocomp.shell.model_store import load_model
from thermocomp.shell.source import read_streamed

DATA = ("data.roles.error=[dX]", "data.roles.campaign=Lauf", "data.test_fraction=0.5")
_BANNER = re.compile(r"\A/\*.*?\*/\n", re.S)      # the provenance: source, run, dataset, date


def _code(folder) -> dict[str, str]:
    """The exported C files without their provenance banner."""
    return {f.name: _BANNER.sub("", f.read_text(encoding="utf-8")) for f in folder.iterdir()
            if f.suffix in (".c", ".h")}


def test_a_registered_model_exports_the_code_its_run_exports(tmp_path):
    # before: the registry's model (no dataset at export) had TC_RUN_COLUMN "": its stream ran a
    # lab's long file as one campaign, each run going on from the last one's end
    from thermocomp.apps.deploy.pyfunc import save_compensator

    path = _long(tmp_path / "alle.csv", _runs())
    common = (f"data.path={path}", *DATA)
    assert main(["run", *common, "model=lagbank", *FAST, f"out={tmp_path / 'run'}"]) == 0
    model = tmp_path / "run" / "model.pkl"
    assert main(["export", *common, "export.format=c", "track=false", f"export.model={model}",
                 f"out={tmp_path / 'from_run'}"]) == 0
    # what promote registers (builders.deployable on promote's dataset), as a pyfunc folder
    cfg = _compose(*common, "model=lagbank", "track=false")
    ds, train_ids = read_streamed(cfg)[:2]
    train = {c: ds.campaigns[c] for c in train_ids}
    folder = save_compensator(deployable(cfg, deploy_stream(cfg, load_model(model), train),
                                         train, ds), tmp_path / "registered")
    assert main(["export", f"export.model={folder}", "export.format=c", "track=false",
                 f"out={tmp_path / 'from_registry'}"]) == 0         # no data.path
    want, got = _code(tmp_path / "from_run"), _code(tmp_path / "from_registry")
    assert set(want) == {"compensator.h", "compensator.c", "stream.c"}
    assert 'TC_RUN_COLUMN = "Lauf";' in want["compensator.h"]
    assert '{"T0 [\\302\\260C]", "T_T0"}' in want["compensator.h"]
    assert got == want
