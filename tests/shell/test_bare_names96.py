"""A unit-row lab's own bare headers served, and a time refused as the file writes it (names96).

audit96's Italian lab (``bench_names96.py``): the file's units sit in a row under its header
(``Temperatura ambiente`` over ``°C``), the reader joins them (``Temperatura ambiente [°C]``) and
the deployed model knew only the joined name, so a session sending the lab's headers as its
logger writes them was refused, "input lacks column(s) ['Temperatura ambiente [°C]' ...]".  Two
columns alike but for their unit (``T`` over ``°C`` and ``T`` over ``K``) make a bare ``T`` no
column for sure: refused naming both.  A second export overlapping the first was refused naming
its times in UTC (``08:29:00+00:00``) where the file wrote ``10:29:00+02:00``.  Every case here
fails on 55f940b8 but the guard (the joined names, served as before).
"""

from __future__ import annotations

import copy

import numpy as np
import pandas as pd
import pytest

from test_data88b import _record
from thermocomp.core.io import ContractError, read_dataset

UNITS = {"Zeit": "s", "Temp a": "°C", "Temp b": "°C", "Temp c": "°C", "dX": "µm"}


def _cell(value: float) -> str:
    return f"{value:.4f}".replace(".", ",")


def _unit_rowed(rows: pd.DataFrame, headers=tuple(UNITS), units=tuple(UNITS.values()),
                kelvin: tuple = ()) -> str:
    """``rows`` as a lab's PC writes them: ``;``, decimal commas, bare headers over a unit row
    (a column in ``kelvin`` written in K)."""
    cols = ["time", "T_a", "T_b", "T_c", "E_X"]
    body = [";".join(_cell(r[c] + (273.15 if c in kelvin else 0.0)) for c in cols)
            for _, r in rows.iterrows()]
    return "".join(f"{ln}\n" for ln in [";".join(headers), ";".join(units), *body])


def _served(tmp_path, text: str, columns: dict | None = None):
    """MLR fitted on ``text``'s first 75 %, deployed as ``thermocomp serve`` deploys it
    (``columns``: data.columns, headers Hydra's override grammar does not take)."""
    from omegaconf import OmegaConf

    from test_export import _compose
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    (tmp_path / "lab.csv").write_text(text, encoding="utf-8")
    cfg = _compose(f"data.path={tmp_path / 'lab.csv'}", "data.test_fraction=0.25",
                   "data.delimiter=';'", "data.decimal=','", "data.roles.error=[dX]", "model=mlr",
                   "track=false")
    if columns:
        OmegaConf.update(cfg, "data.columns", columns, force_add=True)
    ds, train, _, _ = read_streamed(cfg, test=False)
    return deployable_model(cfg, ds, train, None, "serve.model")[0]


def _sent(deployed, frame: pd.DataFrame) -> pd.DataFrame:
    from thermocomp.apps.deploy.pyfunc import CompensatorModel

    model = CompensatorModel(copy.deepcopy(deployed))
    return pd.concat([model.predict(None, frame.iloc[a:a + 12].reset_index(drop=True),
                                    {"reset": a == 0}) for a in range(0, len(frame), 12)],
                     ignore_index=True)


def _frame(rows: pd.DataFrame, joined: bool) -> pd.DataFrame:
    """The rows a lab's client sends: the file's headers, bare or with their units joined."""
    named = {"time": "Zeit", "T_a": "Temp a", "T_b": "Temp b", "T_c": "Temp c", "E_X": "dX"}
    frame = rows.rename(columns=named)
    return frame.rename(columns={h: f"{h} [{UNITS[h]}]" for h in UNITS}) if joined else frame


def test_a_session_takes_the_lab_headers_bare_as_its_logger_writes_them(tmp_path):
    # before: refused, "input lacks column(s) ['Temp a [°C]' (read as T_Temp_a), ...]"
    from thermocomp.apps.deploy.pyfunc import signature

    rows = _record(961)
    deployed = _served(tmp_path, _unit_rowed(rows))
    assert {"Temp a", "Temp a [°C]", "Zeit", "Zeit [s]"} <= set(signature(deployed).inputs.input_names())
    test = rows.iloc[36:].drop(columns="E_X")
    bare, joined = _sent(deployed, _frame(test, False)), _sent(deployed, _frame(test, True))
    assert len(bare) == 12 and np.isfinite(bare["C_dX"]).all()
    np.testing.assert_array_equal(bare["C_dX"], joined["C_dX"])


def test_the_joined_names_are_served_as_before(tmp_path):
    # a guard: the reader's names (the unit row's units joined) as on 55f940b8
    rows = _record(962)
    deployed = _served(tmp_path, _unit_rowed(rows))
    joined = _sent(deployed, _frame(rows.iloc[36:].drop(columns="E_X"), True))
    assert np.isfinite(joined["C_dX"]).all()


def test_a_lacking_or_doubled_bare_column_is_refused_by_the_lab_name(tmp_path):
    rows = _record(963)
    deployed = _served(tmp_path, _unit_rowed(rows))
    test = _frame(rows.iloc[36:].drop(columns="E_X"), False)
    with pytest.raises(Exception, match=r"lacks column\(s\) \['Temp b \[°C\]' \(read as T_b\)\]"):
        _sent(deployed, test.drop(columns="Temp b"))
    with pytest.raises(Exception, match=r"names one column twice.*'Temp b \[°C\]' and 'Temp b'"):
        _sent(deployed, test.assign(**{"Temp b [°C]": test["Temp b"]}))


def test_a_bare_name_two_columns_share_but_for_their_unit_is_refused_naming_both(tmp_path):
    # 'T' over °C and 'T' over K: a bare T is neither for sure (before: "lacks column(s)")
    rows = _record(964)
    deployed = _served(tmp_path, _unit_rowed(rows, ("Zeit", "T", "T", "Temp c", "dX"),
                                             kelvin=("T_b",)).replace(
        ";°C;°C;°C;", ";°C;K;°C;"), {"T [°C]": "T_a", "T [K]": "T_b"})
    sent = rows.iloc[36:].drop(columns="E_X").rename(columns={
        "time": "Zeit", "T_a": "T", "T_b": "T [K]", "T_c": "Temp c"})
    with pytest.raises(Exception, match=r"'T' may be 'T \[°C\]' or 'T \[K\]': two columns "
                                        r"alike but for their unit"):
        _sent(deployed, sent.assign(**{"T [K]": sent["T [K]"] + 273.15}))


def _overlapping(rows: pd.DataFrame, zone_start: str) -> str:
    """A second export repeating the first's last 3 rows, times with their offsets across the
    start of daylight saving time (``+01:00`` then ``+02:00``)."""
    start = pd.Timestamp(zone_start, tz="Europe/Rome")
    stamps = [(start + pd.Timedelta(seconds=float(t))).isoformat(sep=" ") for t in rows["time"]]
    lines = [f"{s},{a:.3f},{b:.3f},{c:.3f},{e:.3f}" for s, a, b, c, e in
             zip(stamps, rows["T_a"], rows["T_b"], rows["T_c"], rows["E_X"])]
    return "".join(f"{ln}\n" for ln in ["time,T_a,T_b,T_c,E_X", *lines[:30], *lines[27:]])


def test_a_time_going_back_is_refused_as_the_file_writes_it(tmp_path):
    # before: "time decreases from 2027-03-28T02:30:00+00:00 (row 30) to ..." (UTC)
    (tmp_path / "over.csv").write_text(_overlapping(_record(965), "2027-03-28 01:05:00"))
    with pytest.raises(ContractError) as refused:
        read_dataset(tmp_path / "over.csv")
    assert refused.value.row == 31 and refused.value.column == "time"
    assert ("time decreases from 2027-03-28 04:30:00+02:00 = 2027-03-28 02:30:00 UTC (row 30) "
            "to 2027-03-28 04:20:00+02:00 = 2027-03-28 02:20:00 UTC") in refused.value.reason


def test_a_time_without_an_offset_is_said_as_written_without_utc(tmp_path):
    # a local clock's time, no offset: the cell as written, no UTC beside it (before: the
    # same instant in ISO 8601's form, 2027-01-10T10:25:00, which the file does not write)
    text = _overlapping(_record(966), "2027-01-10 08:00:00").replace("+01:00", "")
    (tmp_path / "over.csv").write_text(text)
    with pytest.raises(ContractError) as refused:
        read_dataset(tmp_path / "over.csv")
    assert "time decreases from 2027-01-10 10:25:00 (row 30) to 2027-01-10 10:15:00" \
        in refused.value.reason
