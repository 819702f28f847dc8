"""A vertical turning lathe's DIAdem script saving a TDM/TDX pair a day (stranger78): the XML
header (NI's USI schema: channel groups, channels with ``unit_string`` and ``datatype``, local
columns pointing to sequences) and the binary values beside it (``usi:include``'s blocks), the
time a ``DT_DATE`` channel (seconds since 0000-01-01), an operator's text channel inline; a
loose plug's NaN in one day (``benchmarks/bench_stranger78.py`` writes the lab's full record;
these are a few rows of test_stranger68's linear runs)."""

from __future__ import annotations

import datetime as dt
from pathlib import Path
from xml.sax.saxutils import escape

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, refused
from test_stranger68 import ROWS, linear_run
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

NAMES = ["Halle", "Ständer", "Stößel", "Laser dX", "Laser dZ"]
UNITS = ["°C", "°C", "°C", "µm", "µm"]
START = dt.datetime(2027, 4, 5, 6)
DIADEM_EPOCH = 62167132800.0        # s from DIAdem's 0000-01-01 to 1970-01-01 (tdm.DIADEM_EPOCH_S)


def _pair(folder: Path, day: int, nan_rows: int = 0, implicit: bool = False) -> Path:
    """``KV_<day>.tdm`` + ``.tdx``: ``Zeit`` (DT_DATE, float64; ``implicit``: its start and step
    inline, ``implicit_linear``), the channels float32 but the probe dZ stored raw (int32 in
    0.001 µm, ``raw_linear``); ``nan_rows`` NaN in Ständer."""
    folder.mkdir(parents=True, exist_ok=True)
    start = (START + dt.timedelta(days=day - 1) - dt.datetime(1970, 1, 1)).total_seconds()
    values = linear_run(7846, day)
    values[40:40 + nan_rows, 1] = np.nan
    chans = [("Zeit", "s", "DT_DATE", DIADEM_EPOCH + start + 60.0 * np.arange(ROWS), "<f8")]
    chans += [(n, u, "DT_FLOAT", values[:, j], "<f4") for j, (n, u) in enumerate(zip(NAMES, UNITS))]
    chans[-1] = ("Laser dZ", "µm", "DT_DOUBLE", np.round(values[:, 4] * 1e3), "<i4")
    blocks, seqs, body, offset = [], [], [], 0
    with open(folder / f"KV_{day}.tdx", "wb") as f:
        for k, (name, unit, dtype, v, kind) in enumerate(chans):
            f.write(np.asarray(v, dtype=kind).tobytes())
            vtype = {"<f8": "eFloat64Usi", "<f4": "eFloat32Usi", "<i4": "eInt32Usi"}[kind]
            blocks.append(f'<block byteOffset="{offset}" id="inc{k}" length="{ROWS}" valueType="{vtype}"/>')
            offset += np.dtype(kind).itemsize * ROWS
            seqs.append(f'<double_sequence id="s{k}"><values external="inc{k}"/></double_sequence>')
            raw, how = kind == "<i4", "raw_linear" if kind == "<i4" else "explicit"
            if implicit and k == 0:
                seqs[-1] = (f'<double_sequence id="s0"><values><A>{float(v[0])!r}</A><A>60</A>'
                            '</values></double_sequence>')
                how = "implicit_linear"
            body.append(f'<tdm_channel id="c{k}"><name>{escape(name)}</name><unit_string>{unit}'
                        f'</unit_string><datatype>{dtype}</datatype><local_columns>'
                        f'#xpointer(id("l{k}"))</local_columns></tdm_channel>'
                        f'<localcolumn id="l{k}"><submatrix>#xpointer(id("m"))</submatrix>'
                        f'<sequence_representation>{how}</sequence_representation>'
                        + ('<generation_parameters>0 0.001</generation_parameters>' if raw else "")
                        + f'<values>#xpointer(id("s{k}"))</values></localcolumn>')
    body.append('<tdm_channel id="n"><name>Bediener</name><datatype>DT_STRING</datatype>'
                '<local_columns>#xpointer(id("ln"))</local_columns></tdm_channel><localcolumn '
                'id="ln"><values>#xpointer(id("sn"))</values></localcolumn><string_sequence '
                'id="sn"><values><s>Schicht A</s></values></string_sequence>')
    ids = " ".join(f'id("c{k}")' for k in range(len(chans))) + ' id("n")'
    (folder / f"KV_{day}.tdm").write_text(
        '<?xml version="1.0" encoding="UTF-8"?><usi:tdm xmlns:usi="http://www.ni.com/Schemas/'
        f'USI/1_0" version="1.0"><usi:include><file byteOrder="littleEndian" url="KV_{day}.tdx">'
        + "".join(blocks) + '</file></usi:include><usi:data>' + "".join(seqs)
        + f'<tdm_channelgroup id="g"><name>Messung</name><channels>#xpointer({ids})</channels>'
        f'</tdm_channelgroup><submatrix id="m"><number_of_rows>{ROWS}</number_of_rows></submatrix>'
        + "".join(body) + "</usi:data></usi:tdm>", encoding="utf-8")
    return folder / f"KV_{day}.tdm"


def test_a_folder_of_pairs_reads_as_campaigns_timed_by_their_dt_date_channel(tmp_path):
    """(Before: "manifest not found ...; its files, .tdm (2), .tdx (2), are no kind read as a
    run".)  Each pair a campaign, its time DIAdem's dates (the lab PC's clock; the second's
    implicit), the float32, float64 and raw int32 blocks as numbers, the text channel left out."""
    for day in (1, 2):
        _pair(tmp_path / "vtl", day, implicit=day == 2)
    ds, _ = read_dataset(tmp_path / "vtl", {"roles": {"error": ["Laser*"]}, "test_fraction": 0.5})
    assert list(ds.campaigns) == ["KV_1", "KV_2"]
    frame = ds.campaigns["KV_2"]
    names = ["T_Halle", "T_Ständer", "T_Stößel", "E_Laser_dX", "E_Laser_dZ"]
    assert sorted(frame.columns) == sorted(["time", *names])
    np.testing.assert_array_equal(frame["time"], np.arange(ROWS) * 60.0)
    np.testing.assert_allclose(frame[names], linear_run(7846, 2), rtol=1e-5, atol=1e-3)
    assert str(ds.manifest["start"].iloc[1]) == "2027-04-06 06:00:00"      # (no zone said)
    # the dates are the PC's clock: data.timezone says its zone (they were read as UTC, unsaid)
    ds, _ = read_dataset(tmp_path / "vtl", {"roles": {"error": ["Laser*"]}, "test_fraction": 0.5,
                                            "timezone": "Europe/Berlin"})
    assert ds.manifest["start"].iloc[1] == pd.Timestamp("2027-04-06 04:00", tz="UTC")


def test_init_proposes_the_gap_of_a_folder_of_lab_files_and_its_config_reads(tmp_path, capsys):
    """A loose plug's 6 NaN in one day's pair: init read the folder's cells of text files only,
    so no ``data.max_gap_samples`` was proposed and its own read refused the gap (exit 2)."""
    for day in (1, 2, 3):
        _pair(tmp_path / "vtl", day, nan_rows=6 * (day == 2))
    assert main(["init", str(tmp_path / "vtl"), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "inside a file is 6 samples" in said and "data.max_gap_samples=6" in said, said
    conf = (tmp_path / "init" / "conf" / "data" / "vtl.yaml").read_text()
    assert "max_gap_samples: 6" in conf and "error:\n  - Laser dX\n  - Laser dZ" in conf, conf
    # (init's own read is run's: the repaired cells counted in its report)
    ds, report = read_dataset(tmp_path / "vtl", {"roles": {"error": ["Laser*"]},
                                                 "max_gap_samples": 6, "test_fraction": 0.34})
    assert not ds.campaigns["KV_2"]["T_Ständer"].isna().any()


def test_the_tdx_given_for_the_pair_is_refused_naming_its_header(tmp_path, capsys):
    _pair(tmp_path, 1)
    refused(["init", str(tmp_path / "KV_1.tdx"), f"out={tmp_path / 'init'}"], capsys,
            f"file {tmp_path / 'KV_1.tdx'}: a DIAdem TDX file holds the values its TDM header "
            "describes: give the header, KV_1.tdm")
    assert not (tmp_path / "init").exists()


@pytest.mark.parametrize("damage, says", [
    ("missing", "its values' file KV_1.tdx is not beside it: keep the .tdx with the .tdm"),
    ("short", "group 'Messung', channel 'Laser dZ': block 'inc5' (120 values from byte 2880) "
              "ends past the end of KV_1.tdx (3000 bytes)")])
def test_a_pair_without_its_values_is_refused_naming_file_and_channel(tmp_path, capsys, damage, says):
    path = _pair(tmp_path, 1)
    tdx = path.with_suffix(".tdx")
    if damage == "missing":
        tdx.unlink()
    else:
        tdx.write_bytes(tdx.read_bytes()[:3000])
    refused(["run", f"data.path={path}", "data.roles.error=[Laser*]", *FAST,
             f"out={tmp_path / 'out'}"], capsys, f"file {path}: {says}")
    assert not (tmp_path / "out").exists()


def test_the_header_piped_into_monitor_is_refused_as_a_tdm_header(tmp_path, monkeypatch, capsys):
    """(Before: "stdin is not a CSV table with a header, data.delimiter=','", a wrong way out:
    no delimiter reads XML.)"""
    import io as _io

    path = _pair(tmp_path / "vtl", 1)
    rows = pd.concat([pd.DataFrame(linear_run(7846, day), columns=NAMES).assign(
        run=f"day{day}", time=60.0 * np.arange(ROWS)) for day in (1, 2)])
    rows.to_csv(table := tmp_path / "KV.csv", index=False)      # (the record as CSV rows)
    monkeypatch.setattr("sys.stdin", _io.TextIOWrapper(_io.BytesIO(path.read_bytes())))
    said = refused(["monitor", f"data.path={table}", "data.roles.error=[Laser*]",
                    "data.roles.campaign=run", "data.test_fraction=0.5", *FAST,
                    "monitor.input=-", f"out={tmp_path / 'out'}"],
                   capsys, "stdin holds a DIAdem TDM header, the XML of a TDM/TDX pair (its "
                   "signature), no rows of text: give the file as data.path=<file>")
    assert "delimiter" not in said


def test_init_proposes_the_gap_of_a_folder_of_hdf5_files_too(tmp_path, capsys):
    """The gap look is the folder's lab files', whatever their kind (before: an HDF5 file a day
    with 6 NaN, "gap of 6 missing values ... longer than data.max_gap_samples=0", exit 2)."""
    h5py = pytest.importorskip("h5py")
    (tmp_path / "h5").mkdir()
    for day in (1, 2):
        with h5py.File(tmp_path / "h5" / f"day{day}.h5", "w") as f:
            start = (START + dt.timedelta(days=day - 1)).replace(tzinfo=dt.timezone.utc)
            f.create_dataset("time", data=start.timestamp() + 60.0 * np.arange(ROWS)).attrs[
                "units"] = "seconds since 1970-01-01 00:00:00"
            values = linear_run(7846, day)
            values[40:46, 1] = np.nan if day == 2 else values[40:46, 1]
            for j, (name, unit) in enumerate(zip(NAMES, ["degC", "degC", "degC", "um", "um"])):
                f.create_dataset(name, data=values[:, j]).attrs["units"] = unit
    assert main(["init", str(tmp_path / "h5"), f"out={tmp_path / 'init'}"]) == 0
    assert "data.max_gap_samples=6" in capsys.readouterr().out
