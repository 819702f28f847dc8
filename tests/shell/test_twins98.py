"""One name written in two units is read as twins (twins98, ``bench_twins98.py``).

A lab's header holding one name in two units (``T [°C]`` and ``T [K]``: two sensors, or one
logged twice) was refused by the reader ("... both give T_T; give each ... a name
(data.columns)"), where the same header written twice in one unit is read (``T#2 [°C]``,
``T_2``; ``Temp#2 [°C]``, ``T_Temp_2``).  The second is now read ``T_2`` too, its header kept as
written: the exported ``stream.c`` reads it by that text, or joined to its unit row.  A bare
``T`` beside ``T [K]`` names neither for sure: refused by the reader and by the C as before.
Each case fails on 4b9de3c8 ("both give T_T" / "both give T_t1") before its bare refusal, which
holds there too.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from test_export import needs_cc
from test_names97b import _deployed, _fed, _text
from thermocomp.base.errors import ContractError
from thermocomp.core.io import read_dataset


@needs_cc
def test_one_name_in_two_units_is_read_and_streamed_with_no_key(tmp_path):
    # before: the reader refused the file, "'T [°C]' and 'T [K]' both give T_T"
    headers = ("Zeit", "T", "T", "Temp c", "dX")                # over s;°C;K;°C;µm
    code, model, rows = _deployed(tmp_path, headers, {})
    assert model.streaming.columns_ == ["T_T", "T_2", "T_c"]    # (as T;T in one unit)
    sent = pd.DataFrame({"Zeit [s]": rows["time"], "T [°C]": rows["a"],
                         "T_2": rows["b"] - 273.15, "Temp c [°C]": rows["c"]})
    served = model.predict(None, sent, {"reset": True})["C_dX"].to_numpy()
    joined = ("Zeit [s]", "T [°C]", "T [K]", "Temp c [°C]", "dX [µm]")
    for text in (_text(rows, headers), _text(rows, joined, units=None)):
        done = _fed(code, text)
        assert done.returncode == 0, done.stderr.decode()
        got = pd.read_csv(pd.io.common.StringIO(done.stdout.decode()))["C_dX"].to_numpy()
        assert len(got) == len(rows) and np.max(np.abs(got - served)) < 1e-9
    bare = _fed(code, _text(rows, ("Zeit [s]", "T", "T [K]", "Temp c [°C]", "dX [µm]"), units=None))
    assert bare.returncode == 2 and not bare.stdout           # (which T? refused, as names97)
    assert "'T' may be 'T [°C]' or 'T [K]'" in bare.stderr.decode()


def test_every_spelling_of_a_unit_is_read_a_bare_name_beside_it_refused(tmp_path, caplog):
    t = np.arange(30) * 60.0
    temp = 20 + t / 600
    pd.DataFrame({"time [s]": t, "t1(°C)": temp, "t1 [K]": temp + 274.15, "t1_degF": 68 + t / 300,
                  "dX [µm]": 2 * temp}).to_csv(tmp_path / "r.csv", index=False)
    ds, _ = read_dataset(tmp_path / "r.csv", {"roles": {"error": ["dX"]}})
    frame = ds.campaigns["r"]
    np.testing.assert_allclose(frame["T_t1"], temp)
    np.testing.assert_allclose(frame["T_t1_2"], temp + 1)
    np.testing.assert_allclose(frame["T_t1_3"], 20 + t / 540)
    assert "columns 2 and 3 hold one name in two units ('t1(°C)', 't1 [K]'): column 3 read as " \
           "T_t1_2" in caplog.text
    pd.DataFrame({"time [s]": t, "T": temp, "T [K]": temp + 273.15, "dX [µm]": 2 * temp}).to_csv(
        tmp_path / "bare.csv", index=False)
    with pytest.raises(ContractError, match=r"'T' and 'T \[K\]' both give T_T"):
        read_dataset(tmp_path / "bare.csv", {"roles": {"error": ["dX"]}})
