"""The check pack's two shortcuts of perf88 give what the long ways give: its CSV bodies formatted
without pandas' per-value formatter, and the code monitor's active set kept between the calls of
a step that ask for it (the numpy model of the code, :class:`~.watch.CodeMonitor`)."""

from __future__ import annotations

import io

import numpy as np
import pandas as pd
import pytest

from test_export import adaptive_mlr
from thermocomp.apps.deploy.export import state_space
from thermocomp.apps.deploy.export.pack import conformance_pack, csv_text
from thermocomp.apps.deploy.export.watch import CodeMonitor


def _pandas(frame: pd.DataFrame) -> str:
    buf = io.StringIO()
    frame.to_csv(buf, index=False, float_format="%.17g", na_rep="", lineterminator="\n")
    return buf.getvalue()


def _frames() -> dict[str, pd.DataFrame]:
    rng = np.random.default_rng(88)
    values = rng.normal(size=(300, 5)) * 10.0 ** rng.integers(-300, 300, size=(300, 5))
    values[rng.random(values.shape) < 0.1] = np.nan
    values[0] = [np.inf, -np.inf, -0.0, 3.0, -np.nan]
    values[1] = [1e16, 0.1, 5e-324, np.finfo(float).max, 2.0 ** 53 + 1]
    names = ["time", "T a", "b,c", 'd"e', "nan"]   # names that need quoting, and one read "nan"
    floats = pd.DataFrame(values, columns=names)
    return {"floats": floats, "one row": floats.iloc[:1], "no row": floats.iloc[:0],
            "one column": floats[["b,c"]], "with an int": floats.assign(n=np.arange(300))}


@pytest.mark.parametrize("name", list(_frames()))
def test_csv_text_is_pandas_to_the_byte_and_formats_float_bodies_itself(name, monkeypatch):
    frame = _frames()[name]
    want = _pandas(frame)
    given = []
    to_csv = pd.DataFrame.to_csv

    def counted(self, *args, **kwargs):
        given.append(len(self))
        return to_csv(self, *args, **kwargs)

    monkeypatch.setattr(pd.DataFrame, "to_csv", counted)
    assert csv_text(frame) == want
    floats_only = name in ("floats", "one row", "no row")
    # pandas writes the header (names may need quoting); the body of float columns is formatted
    # without it (a single column or another dtype: pandas' whole, as before)
    assert given == ([0] if floats_only else [len(frame)])


@pytest.fixture(scope="module")
def monitored(tmp_path_factory):
    """``(adaptive MLR, its system with the monitor, {test campaign})`` (test_export's record)."""
    deployed, ds, test_ids = adaptive_mlr(tmp_path_factory.mktemp("perf88") / "data")
    cid = test_ids[0]
    return deployed, state_space(deployed, monitor=True), {cid: ds.campaigns[cid]}


def test_the_code_monitors_set_is_kept_and_the_pack_is_the_one_made_afresh(monitored,
                                                                          monkeypatch):
    deployed, ss, campaigns = monitored
    asked, made = [], []
    kept_set, made_set = CodeMonitor._set, CodeMonitor._made_set

    def ask(self):
        asked.append(1)
        return kept_set(self)

    def make(self):
        made.append(1)
        return made_set(self)

    monkeypatch.setattr(CodeMonitor, "_set", ask)
    monkeypatch.setattr(CodeMonitor, "_made_set", make)
    files, summary = conformance_pack(deployed, ss, campaigns)
    entries = summary["campaigns"]
    assert any("planted" in e for e in entries)
    # made anew where the set changed (a planted fault takes its sensor out: more than once a
    # campaign), kept between the calls of a step otherwise
    assert len(entries) < len(made) < len(asked) / 3
    # made afresh on every call, as before: the same pack to the byte
    monkeypatch.setattr(CodeMonitor, "_set", lambda self: made_set(self))
    assert conformance_pack(deployed, ss, campaigns) == (files, summary)
