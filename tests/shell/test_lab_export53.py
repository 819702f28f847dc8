"""Leftovers of the lab-file work (session 53): a model from the registry exports the lab's
names and run column as one from the run does; the compiled C stream reads a logger's
wall-clock times as the served model does."""

from __future__ import annotations

import io
import re
import subprocess

import numpy as np
import pandas as pd

from conftest import FAST
from test_export import _compose, needs_cc
from test_lab_stream52 import DATA, compiled
from test_run_column52 import _long, _runs
from thermocomp.apps.deploy.streaming import replay
from thermocomp.shell.builders import deploy_stream, deployable
from thermocomp.shell.cli import main
from thermocomp.shell.model_store import load_model
from thermocomp.shell.source import read_streamed

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


def _streamed(binary, text: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(binary)], input=text.encode("utf-8"), capture_output=True)


@needs_cc
def test_the_compiled_c_reads_a_loggers_wall_clock_times_as_replay_does(tmp_path):
    # before: "row 2: the time is no number (seconds; a clock time or date is not read here)":
    # the lab converted its logger's clock to seconds first, which serve and replay do not need
    path = _clock_file(tmp_path / "alle.csv")
    binary = compiled(tmp_path, path)
    cfg = _compose(f"data.path={path}", *DATA, "model=lagbank", "monitor.adaptive=false",
                   "track=false")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    assert test_ids == ["Lauf_3", "Lauf_4"]
    stream = deploy_stream(cfg, load_model(tmp_path / "run" / "model.pkl"),
                           {c: ds.campaigns[c] for c in train_ids})
    assert stream.time_required_ or "time" in stream.columns_
    want = np.vstack([-replay(stream, ds.campaigns[c])[stream.targets_].to_numpy(float)
                      for c in test_ids])
    lines = path.read_text(encoding="utf-8-sig").splitlines()
    rows = [ln for ln in lines[1:] if ln.split(";")[0] in "34"]
    assert rows[0].split(";")[1] == "15.03.2023 08:00:00"
    raw = "\ufeff" + "\n".join([lines[0], *rows]) + "\n"       # the lab's file, its BOM too
    run = _streamed(binary, raw)
    assert run.returncode == 0, run.stderr
    got = pd.read_csv(io.BytesIO(run.stdout)).to_numpy(float)
    assert got.shape == want.shape == (60, 1)
    assert np.abs(got - want).max() <= 1e-9
    # the same clock as ISO 8601: local, with a zone offset (+01:00, a fraction after a comma)
    for form in ("%Y-%m-%dT%H:%M:%S", "%Y-%m-%d %H:%M:%S,000+01:00"):
        iso = _reclocked(raw, form)
        assert iso != raw
        run = _streamed(binary, iso)
        assert run.returncode == 0, run.stderr
        assert np.abs(pd.read_csv(io.BytesIO(run.stdout)).to_numpy(float) - want).max() <= 1e-9
    # refused with the row: an impossible date, a time of day alone, two forms in one stream
    cases = {rows[4].split(";")[1]: ("30.02.2023 08:04:00", 6, "no number of seconds nor a date"),
             rows[0].split(";")[1]: ("08:00:00", 2, "a time of day alone"),
             rows[9].split(";")[1]: ("540,0", 11, "is seconds, the stream's first a date")}
    for old, (new, row, said) in cases.items():
        bad = _streamed(binary, raw.replace(old, new, 1))
        assert bad.returncode == 2 and f"line {row}: the time ".encode() in bad.stderr, bad.stderr
        assert said.encode() in bad.stderr


def _clock_file(path):
    """Four runs in one ``;`` file, decimal commas, a BOM, ``Lauf`` numbering them and the
    logger's wall-clock time (day-first), a week apart."""
    runs = _runs()
    for k, run in enumerate(runs):
        start = pd.Timestamp("2023-03-01 08:00") + pd.Timedelta(days=7 * k)
        run.insert(0, "Zeit", (start + pd.to_timedelta(run.pop("Zeit [s]"), unit="s"))
                   .dt.strftime("%d.%m.%Y %H:%M:%S"))
    _long(path, runs)
    path.write_text(path.read_text(encoding="utf-8"), encoding="utf-8-sig")
    return path


def _reclocked(text: str, form: str) -> str:
    """``text`` (the lab's rows) with its day-first times rewritten in ``form``."""
    def stamp(match):
        return pd.Timestamp(pd.to_datetime(match.group(0), format="%d.%m.%Y %H:%M:%S")
                            ).strftime(form)
    return re.sub(r"\d\d\.\d\d\.\d{4} \d\d:\d\d:\d\d", stamp, text)
