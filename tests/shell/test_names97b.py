"""stream.c finds a header whose unit row tells two alike columns apart (names97b,
``bench_names97b.py``).

The reader joins a unit row's units to the header, then numbers a name still written twice
(``T;T`` over ``°C;K``: ``T [°C]``, ``T [K]``; ``Temp;Temp`` over ``°C;°C``: ``Temp [°C]``,
``Temp#2 [°C]``).  The exported ``stream.c`` took a line for the header only where its bare names
named every input (the bare twin ``T#2`` names none), so it read past the header and its unit
row and refused the file ("lacks input column T_b") that ``run`` read.  Each case fails on
c9c1d35c but the bare header with no unit row, refused there as here.
"""

from __future__ import annotations

import copy
import subprocess

import numpy as np
import pandas as pd

from cbuild import compiled
from test_export import _compose, needs_cc

UNITS = ("s", "°C", "K", "°C", "µm")


def _rows(n: int = 40, seed: int = 972) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    temp = 20 + np.cumsum(rng.normal(0, 0.05, (n, 3)), axis=0)
    return pd.DataFrame({"time": np.arange(n) * 60.0, "a": temp[:, 0], "b": temp[:, 1] + 273.15,
                         "c": temp[:, 2], "e": 2 * temp[:, 0] - temp[:, 1] + 0.5 * temp[:, 2]
                         }).round(4)


def _text(rows: pd.DataFrame, headers, units=UNITS, above=()) -> str:
    body = [";".join(f"{v:.4f}".replace(".", ",") for v in r) for r in rows.to_numpy(float)]
    lines = [*above, ";".join(headers), *([";".join(units)] if units else []), *body]
    return "".join(f"{ln}\n" for ln in lines)


def _deployed(tmp_path, headers, columns: dict):
    """The lab's file (``headers`` over :data:`UNITS`), MLR on its first 75 % made deployable as
    serve makes it, exported as C and built: (the code's folder, the served model, the rows)."""
    from omegaconf import OmegaConf

    from thermocomp.apps.deploy.pyfunc import CompensatorModel
    from thermocomp.apps.deploy.report import plain
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.model_store import save_model
    from thermocomp.shell.source import read_streamed
    from thermocomp.shell.stages.export import export

    rows = _rows()
    (tmp_path / "lab.csv").write_text(_text(rows, headers), encoding="utf-8")
    cfg = _compose(f"data.path={tmp_path / 'lab.csv'}", "data.test_fraction=0.25",
                   "data.delimiter=';'", "data.decimal=','", "data.roles.error=[dX*]", "model=mlr",
                   "track=false", "export.format=c", "export.check=false",
                   f"export.model={tmp_path / 'model.pkl'}", f"out={tmp_path / 'code'}")
    OmegaConf.update(cfg, "data.columns", columns, force_add=True)
    ds, train, _, _ = read_streamed(cfg, test=False)
    deployed = deployable_model(cfg, ds, train, None, "serve.model")[0]
    save_model(plain(deployed).compensator, tmp_path / "model.pkl")
    export(cfg)
    compiled(tmp_path / "code")
    return tmp_path / "code", CompensatorModel(copy.deepcopy(deployed)), rows


def _fed(code, text: str):
    return subprocess.run(["./stream"], cwd=code, capture_output=True, input=text.encode())


@needs_cc
def test_a_header_written_twice_over_a_unit_row_that_tells_them_apart(tmp_path):
    # before: exit 2 "the header (line 1 ...) lacks input column T_b (the lab's header 'T [K]')"
    code, model, rows = _deployed(tmp_path, ("Zeit", "T", "T", "Temp c", "dX"),
                                  {"T [°C]": "T_a", "T [K]": "T_b"})
    sent = pd.DataFrame({"Zeit [s]": rows["time"], "T [°C]": rows["a"], "T_b": rows["b"] - 273.15,
                         "Temp c [°C]": rows["c"]})
    served = model.predict(None, sent, {"reset": True})["C_dX"].to_numpy()
    for above in ((), ("Maschine;PM-12",)):        # (a logger's preamble line above it too)
        done = _fed(code, _text(rows, ("Zeit", "T", "T", "Temp c", "dX"), above=above))
        assert done.returncode == 0, done.stderr.decode()
        got = pd.read_csv(pd.io.common.StringIO(done.stdout.decode()))["C_dX"].to_numpy()
        assert len(got) == len(rows) and np.max(np.abs(got - served)) < 1e-9
    bare = _fed(code, _text(rows, ("Zeit [s]", "T", "T", "Temp c [°C]", "dX [µm]"), units=None))
    assert bare.returncode == 2 and not bare.stdout          # (no unit row: which T? refused)
    assert "lacks input column T_b (the lab's header 'T [K]')" in bare.stderr.decode()


@needs_cc
def test_one_name_three_times_over_a_unit_row_is_read_as_the_reader_numbers_it(tmp_path):
    # the reader: 'Temp [°C]', 'Temp [K]', 'Temp#2 [°C]'; before: refused at its header
    headers = ("Zeit", "Temp", "Temp", "Temp", "dX")
    code, model, rows = _deployed(tmp_path, headers, {"Temp [°C]": "T_a", "Temp [K]": "T_b",
                                                      "Temp#2 [°C]": "T_c"})
    sent = pd.DataFrame({"Zeit [s]": rows["time"], "Temp [°C]": rows["a"],
                         "T_b": rows["b"] - 273.15, "Temp#2 [°C]": rows["c"]})
    served = model.predict(None, sent, {"reset": True})["C_dX"].to_numpy()
    done = _fed(code, _text(rows, headers))
    assert done.returncode == 0, done.stderr.decode()
    got = pd.read_csv(pd.io.common.StringIO(done.stdout.decode()))["C_dX"].to_numpy()
    assert len(got) == len(rows) and np.max(np.abs(got - served)) < 1e-9
