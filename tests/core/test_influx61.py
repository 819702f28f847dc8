"""InfluxDB 2.x annotated CSV (``influx query --raw``, the UI's download) read as a historian's long
file (influx61): its tables (annotation rows, a header, blank lines between blocks, a series
split into two tables after a type change) are each a series, named by what tells it from the
others (a ``unit`` tag its unit), held onto the grid of ``data.resample_s``; the pivoted form
(one column per field) is read to the same grid; what cannot be read is refused naming the file,
the column and the file's own line.  Before influx61 such a file was read as a wide CSV: "no
column reads as a measured error ... the numeric columns: none".

Also the historian's shared path: a long file with a blank line among its rows had its stamps
aligned by label, each sample after the blank line given the time of the sample below it."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from thermocomp.core.io import ContractError, read_dataset

START = pd.Timestamp("2026-11-02 06:00:00")
CFG = {"resample_s": 30, "test_fraction": 0.5, "max_gap_samples": 0,
       "roles": {"state": ["rpm", "door"]}}
ERROR_DZ = {**CFG, "roles": {**CFG["roles"], "error": ["dZ*"]}}
CHANGE_S = 3600.0          # the rpm field written as a double before, a long after (two blocks)


def rfc(seconds) -> list[str]:
    text = (START + pd.to_timedelta(np.asarray(seconds, float), unit="s")).strftime(
        "%Y-%m-%dT%H:%M:%S.%f")
    return [t.rstrip("0").rstrip(".") + "Z" for t in text]


def series(seed: int = 61) -> list[tuple]:
    """``(measurement, tags, field, type, seconds, values)`` of a small machine, 2 h: a spindle
    every 30 s, a bed every 60 s from 10 s, a probe every 30 s 0-300 ms late, the spindle's
    speed on change (a float, then an integer), a door (boolean) and a program (string)."""
    rng = np.random.default_rng(seed)
    t30 = np.arange(0, 7200, 30.0)
    probe_t = t30 + np.round(rng.uniform(0, 0.3, t30.size), 3)
    rpm_t = np.array([0.2, 900.1, 2400.05, 3000.0, 4500.3, 6000.7])
    door_t = np.array([0.1, 1800.0, 2100.0, 5400.0])
    common = {"machine": "M1"}
    return [
        ("temperature", {**common, "sensor": "Spindle", "unit": "degC"}, "value", "double", t30,
         np.round(20 + t30 / 2000 + rng.normal(0, 0.02, t30.size), 2)),
        ("temperature", {**common, "sensor": "Bed", "unit": "degC"}, "value", "double",
         np.arange(10, 7200, 60.0), np.round(19 + np.arange(10, 7200, 60.0) / 9000, 2)),
        ("tracker", {**common, "sensor": "dZ", "unit": "um"}, "value", "double", probe_t,
         np.round(3 * np.sin(probe_t / 1500) + rng.normal(0, 0.1, t30.size), 1)),
        ("cnc", common, "rpm", "double", rpm_t, np.array([0, 8000, 12000, 0, 16000, 4000.0])),
        ("cnc", common, "door", "boolean", door_t, np.array([0, 1, 0, 1.0])),
        ("cnc", common, "program", "string", door_t, np.array([11, 12, 13, 14.0])),
    ]


def cell(kind, v) -> str:
    return {"boolean": "true" if v else "false", "long": str(int(v)),
            "string": f"O{int(v)}"}.get(kind, f"{v:g}")


def tables(points) -> list[tuple]:
    """One table per series; the rpm split at :data:`CHANGE_S`, a long after."""
    out = []
    for m, tags, f, kind, t, v in points:
        if f == "rpm":
            out += [(m, tags, f, "double", t[t < CHANGE_S], v[t < CHANGE_S]),
                    (m, tags, f, "long", t[t >= CHANGE_S], v[t >= CHANGE_S])]
        else:
            out.append((m, tags, f, kind, t, v))
    return out


def annotated(points, eol: str = "\r\n") -> str:
    """``influx query --raw``: a block per schema (columns and types), a table per series."""
    blocks, schema = [], None
    for number, (m, tags, f, kind, t, v) in enumerate(tables(points)):
        keys = sorted(tags)
        columns = ["result", "table", "_start", "_stop", "_time", "_value", "_field",
                   "_measurement", *keys]
        types = ["string", "long", *["dateTime:RFC3339"] * 3, kind, "string", "string",
                 *["string"] * len(keys)]
        if (columns, types) != schema:
            group = ["false", "false", "true", "true", "false", "false", "true", "true",
                     *["true"] * len(keys)]
            blocks.append(["#group," + ",".join(group), "#datatype," + ",".join(types),
                           "#default,_result" + "," * (len(columns) - 1), "," + ",".join(columns)])
            schema = (columns, types)
        rng_ = ",".join(rfc([0, 7200]))
        tail = f",{f},{m}" + "".join(f",{tags[k]}" for k in keys)
        blocks[-1] += [f",,{number},{rng_},{s},{cell(kind, x)}{tail}" for s, x in zip(rfc(t), v)]
    return eol.join(eol.join(b) + eol for b in blocks)


def pivoted(points) -> str:
    """The UI's download of ``|> pivot(rowKey: ["_time"], columnKey: ["_field"], ...)`` of the
    same samples, each series a field of its own: one table, a column per field."""
    names = {"Spindle": "spindle_degC", "Bed": "bed_degC", "dZ": "dz_um"}
    columns = {names.get(tags.get("sensor"), f): (kind, pd.Series(
        [cell(kind, x) for x in v], index=np.round(t, 3))) for _, tags, f, kind, t, v in points}
    order = sorted(columns)
    frame = pd.DataFrame({n: columns[n][1] for n in order}).sort_index().fillna("")
    head = ["result", "table", "_start", "_stop", "_time", "_measurement", "machine", *order]
    lines = ["#group,false,false,true,true,false,true,true" + ",false" * len(order),
             "#datatype,string,long," + ",".join(["dateTime:RFC3339"] * 3) + ",string,string,"
             + ",".join(columns[n][0] for n in order),
             "#default,_result" + "," * (len(head) - 1), "," + ",".join(head)]
    rng_ = ",".join(rfc([0, 7200]))
    lines += [f",,0,{rng_},{s},m1,M1," + ",".join(row)
              for s, row in zip(rfc(frame.index), frame.to_numpy(str))]
    return "\r\n".join(lines) + "\r\n\r\n"


def held(seconds, values, grid) -> np.ndarray:
    return np.asarray(values, float)[np.searchsorted(seconds, grid, side="right") - 1]


def record(path, cfg=CFG) -> tuple[pd.DataFrame, float]:
    """The record read, its campaigns joined, and its grid's first time (s after START)."""
    ds, report = read_dataset(path, cfg)
    first = report["campaigns"][ds.ids()[0]]
    origin = pd.Timestamp(first["time_origin"]).tz_convert(None)
    frames = []
    for cid in ds.ids():
        shift = (pd.Timestamp(report["campaigns"][cid]["time_origin"]).tz_convert(None)
                 - origin).total_seconds()
        frames.append(ds.campaigns[cid].assign(time=ds.campaigns[cid]["time"] + shift))
    return pd.concat(frames, ignore_index=True), (origin - START).total_seconds()


def test_each_table_is_a_series_held_onto_the_grid(tmp_path):
    points = series()
    (tmp_path / "m1.csv").write_text(annotated(points), newline="")
    got, origin = record(tmp_path / "m1.csv", ERROR_DZ)
    # every series has a sample from the bed's first (10 s); the door's and rpm's 0.1 / 0.2 s
    assert origin == 10.0
    grid = origin + got["time"].to_numpy()
    assert np.allclose(np.diff(grid), 30.0) and grid[-1] <= 7200
    expected = {"T_Spindle": points[0], "T_Bed": points[1], "E_dZ": points[2],
                "S_rpm": points[3], "S_door": points[4]}
    assert sorted(expected) == sorted(c for c in got.columns if c != "time")
    for name, (_, _, _, _, t, v) in expected.items():
        want = held(t, v, grid)
        have = got[name].to_numpy()
        if name.startswith(("T_", "E_")):    # (as referenced, or not: compared as rises)
            want, have = want - want[0], have - have[0]
        assert np.allclose(have, want, atol=1e-9), name
    # the rpm's two tables (a double, a long) one series: its values after the change held
    assert got.loc[grid >= 4500.3, "S_rpm"].iloc[0] == 16000


def test_the_pivoted_download_reads_to_the_same_grid(tmp_path):
    points = series()
    (tmp_path / "long.csv").write_text(annotated(points), newline="")
    (tmp_path / "wide.csv").write_text(pivoted(points), newline="")
    cfg = {**CFG, "roles": {"state": ["rpm", "door"], "error": ["dZ*", "dz*"]}}
    long, origin_long = record(tmp_path / "long.csv", cfg)
    wide, origin_wide = record(tmp_path / "wide.csv", cfg)
    assert origin_long == origin_wide
    wide = wide.rename(columns={"T_spindle": "T_Spindle", "T_bed": "T_Bed", "E_dz": "E_dZ"})
    assert sorted(wide.columns) == sorted(long.columns)
    pd.testing.assert_frame_equal(wide[long.columns], long)


def test_series_are_named_by_what_tells_them_apart():
    from thermocomp.core.io.influx import series_names

    keys = [("temperature", (("machine", "M1"), ("sensor", "Spindle"), ("unit", "degC")), "value"),
            ("tracker", (("machine", "M1"), ("sensor", "dZ"), ("unit", "um")), "value"),
            ("cnc", (("machine", "M1"),), "rpm"),
            ("cnc", (("machine", "M1"),), "door"),
            ("power", (("machine", "M1"), ("sensor", "Spindle")), "kw")]
    assert list(series_names(keys).values()) == [
        "Spindle.value [degC]", "dZ [um]", "rpm", "door", "Spindle.kw"]


def test_a_string_series_is_left_out_and_said(tmp_path, caplog):
    (tmp_path / "m1.csv").write_text(annotated(series()), newline="")
    got, _ = record(tmp_path / "m1.csv", ERROR_DZ)
    assert not any("program" in c for c in got.columns)
    assert "program (string)" in caplog.text


@pytest.mark.parametrize("spoil, column, says", [
    ("text", "_value", "is not a number"),
    ("repeat", "_value", "two samples at"),
    ("time", "_time", "2026-13-02"),
])
def test_a_bad_sample_is_refused_naming_file_column_and_line(tmp_path, spoil, column, says):
    lines = annotated(series()).split("\r\n")
    k = next(k for k, ln in enumerate(lines)
             if ln.endswith(",Spindle,degC") and f",{rfc([600])[0]}," in ln)
    cells = lines[k].split(",")             # ,,table,_start,_stop,_time,_value,...
    if spoil == "text":
        cells[6], at = "abc", k + 1
    elif spoil == "time":
        cells[5], at = cells[5].replace("2026-11-02", "2026-13-02"), k + 1
    else:                                   # the sample again at its stamp, another value
        cells[6], at = str(float(cells[6]) + 1), k + 2
        lines.insert(k + 1, lines[k])
    lines[at - 1] = ",".join(cells)
    (tmp_path / "m1.csv").write_text("\r\n".join(lines), newline="")
    with pytest.raises(ContractError) as exc:
        read_dataset(tmp_path / "m1.csv", ERROR_DZ)
    assert exc.value.line == at and exc.value.column == column, str(exc.value)
    assert says in str(exc.value) and f"line {at}" in str(exc.value)
    assert str(tmp_path / "m1.csv") in str(exc.value)


def test_an_error_table_and_a_table_without_time_are_refused_with_their_line(tmp_path):
    failed = ("#datatype,string,string\r\n#group,true,true\r\n#default,,\r\n,error,reference\r\n"
              ',"unauthorized access: bucket \'lab\' not found",\r\n\r\n')
    (tmp_path / "failed.csv").write_text(failed, newline="")
    with pytest.raises(ContractError) as exc:
        read_dataset(tmp_path / "failed.csv", CFG)
    assert exc.value.line == 5 and "unauthorized access" in str(exc.value)
    no_time = annotated(series()).replace(",_time,", ",_when,", 1)
    (tmp_path / "no_time.csv").write_text(no_time, newline="")
    with pytest.raises(ContractError) as exc:
        read_dataset(tmp_path / "no_time.csv", CFG)
    assert exc.value.line == 4 and "a table without '_time'" in str(exc.value)


def test_a_historian_file_with_a_blank_line_keeps_each_samples_time(tmp_path):
    """The shared long path (historian60): the stamps were put back by label, the rows'
    labels skipping the blank line, so each sample after it took its successor's time."""
    from test_historian60 import CFG as HCFG
    from test_historian60 import samples, write

    frame = samples()
    write(frame, tmp_path / "pi.csv")
    lines = (tmp_path / "pi.csv").read_text().splitlines()
    (tmp_path / "gap.csv").write_text("\n".join([*lines[:200], "", *lines[200:]]) + "\n")
    plain, _ = read_dataset(tmp_path / "pi.csv", HCFG)
    blank, _ = read_dataset(tmp_path / "gap.csv", HCFG)
    assert len(blank.ids()) == len(plain.ids())
    for gap, cid in zip(blank.ids(), plain.ids()):
        pd.testing.assert_frame_equal(blank.campaigns[gap], plain.campaigns[cid])
