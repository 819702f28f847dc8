"""A lab's raw export, round 4 (session 47, a stranger's pass): Excel's 'Unicode Text' export
(UTF-16, tab-separated), a tab typed on the command line, a temperature headed ``T [°C]``."""

from __future__ import annotations

import codecs
from io import BytesIO, TextIOWrapper

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, refused
from test_raw_exports44 import _read, _record, _write
from thermocomp.core.io import ContractError
from thermocomp.core.io.stdin import stdin_text, stream_seconds
from thermocomp.shell.cli import main

HEADER = ["time [s]", "T [°C]", "T2 [°C]", "dX [µm]"]


def _table(sep: str) -> str:
    t, t1, t2, e = _record()
    rows = [sep.join(f"{v:.6g}" for v in row) for row in zip(t, t1, t2, e)]
    return "\r\n".join([sep.join(HEADER), *rows]) + "\r\n"


@pytest.mark.parametrize("command", ["init", "run"])
# (UTF-16, refused here before session 49, is read: tests/core/test_utf16_exports49.py)
@pytest.mark.parametrize("bom, codec, said", [(codecs.BOM_UTF32_LE, "utf-32-le", "UTF-32"),
                                              (codecs.BOM_UTF32_BE, "utf-32-be", "UTF-32")])
def test_excels_unicode_text_export_is_refused_saying_how_to_save_it(tmp_path, capsys, command,
                                                                    bom, codec, said):
    # before: 'file looks '\t'-separated (one column 'ÿþt\x00i\x00m...'): set data.delimiter='\t''
    # (init), or a column named by the NUL-riddled header (run): no setting reads it
    path = tmp_path / "Messung.txt"
    path.write_bytes(bom + _table("\t").encode(codec))
    args = ([str(path)] if command == "init" else
            [f"data.path={path}", "data.roles.error=[dX]", "data.test_fraction=0.2", *FAST])
    line = refused([command, *args, f"out={tmp_path / 'out'}"], capsys,
                   f"file {path}:", f"{said} text", "CSV UTF-8", f"iconv -f {said} -t UTF-8")
    assert "\\x00" not in line, line
    assert not (tmp_path / "out").exists()


def test_excels_unicode_text_export_on_stdin_is_refused_saying_how_to_convert_it():
    # before: 'byte 0xff is not utf-8 text (set data.encoding to the stream's character set,
    # e.g. cp1252)': cp1252 reads it as NUL-riddled text
    stream = TextIOWrapper(BytesIO(codecs.BOM_UTF32_LE + _table("\t").encode("utf-32-le")))
    with pytest.raises(ContractError, match="stream is UTF-32 text.*pipe it through iconv -f "
                                            "UTF-32 -t UTF-8"):
        stdin_text(stream)


@pytest.mark.parametrize("typed", ["\\t", "tab"])
def test_a_tab_separator_is_typed_as_the_refusal_says_it(tmp_path, capsys, typed):
    # a tab-separated file that auto detection cannot settle is refused with "set
    # data.delimiter='\t'"; the shell passes that as a backslash and a 't' (no command line
    # passes a tab): before, 'data.delimiter must be one character or 'auto', got '\\t''
    t, t1, t2, e = _record()
    path = _write(tmp_path / "log.tsv", ["time", "T1", "T2", "dX [um]"], [t, t1, t2, e], sep="\t")
    frame = _read(path, delimiter=typed, roles={"error": ["dX*"]})
    np.testing.assert_allclose(frame[["time", "T_T1", "E_dX"]], np.c_[t, t1, e], atol=1e-3)
    assert main(["run", f"data.path={path}", f"data.delimiter={typed}", "data.roles.error=[dX]",
                 "data.test_fraction=0.2", *FAST, f"out={tmp_path / 'out'}"]) == 0, \
        capsys.readouterr().err


def test_a_temperature_headed_t_with_its_unit_is_no_time(tmp_path, capsys):
    # 'T [°C]' beside 'time [s]': before, "'time [s]' and 'T [°C]' both look like the time (set
    # data.roles.time)", refused by init and run; a header 'T' in °C is a temperature
    path = tmp_path / "spindel.csv"
    path.write_text(_table(","), encoding="utf-8")
    t, t1, t2, e = _record()
    frame = _read(path, roles={"error": ["dX"]})
    assert list(frame.columns) == ["time", "T_T", "T_T2", "E_dX"]
    np.testing.assert_allclose(frame.to_numpy(), np.c_[t, t1, t2, e], atol=1e-3)
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0, capsys.readouterr().err
    out = capsys.readouterr().out
    assert "time: 'time [s]', in s" in out and "T_T\n" in out, out


def test_quoted_decimal_commas_in_a_comma_separated_file_read_as_the_refusal_says(tmp_path,
                                                                                 capsys):
    # "0,38" quoted in a ','-separated export: refused 'a decimal comma? set data.decimal=','',
    # and that setting was refused in turn ('the field separator too'): no setting read it
    t, t1, t2, e = _record()
    rows = [",".join(f'"{v:.6g}"'.replace(".", ",") for v in row) for row in zip(t, t1, t2, e)]
    path = tmp_path / "export.csv"
    path.write_text("\n".join(['"time","T1","T2","dX [um]"', *rows]) + "\n", encoding="utf-8")
    refused(["init", str(path), f"out={tmp_path / 'init'}"], capsys, "set data.decimal=','")
    frame = _read(path, decimal=",", roles={"error": ["dX*"]})
    np.testing.assert_allclose(frame[["time", "T_T1", "T_T2", "E_dX"]], np.c_[t, t1, t2, e],
                               rtol=1e-5)
    assert main(["init", str(path), "data.decimal=,", f"out={tmp_path / 'init'}"]) == 0, \
        capsys.readouterr().err


@pytest.mark.parametrize("celsius, fahrenheit", [("ºC", "ºF"), ("˚C", "˚F")])
def test_a_degree_sign_typed_as_the_ordinal_or_the_ring_is_the_degree(tmp_path, celsius,
                                                                      fahrenheit):
    # 'T1 [ºC]' (U+00BA, a Spanish or Italian keyboard's º) was refused "unit 'ºC' is not a
    # temperature's (°C, K, °F)": two signs that look alike in the header and in the message
    t, t1, t2, e = _record()
    path = _write(tmp_path / "ensayo.csv", ["time", f"T1 [{celsius}]", f"T2 [{fahrenheit}]",
                                             "dX [µm]"], [t, t1, t2 * 1.8 + 32, e])
    frame = _read(path, roles={"error": ["dX"]})
    np.testing.assert_allclose(frame[["T_T1", "T_T2"]], np.c_[t1, t2], atol=1e-3)
    unit_row = tmp_path / "unit_row.csv"
    unit_row.write_text(path.read_text(encoding="utf-8").replace(
        f"T1 [{celsius}],T2 [{fahrenheit}]", "T1,T2").replace(
        "\n", f"\ns,{celsius},{fahrenheit},µm\n", 1), encoding="utf-8")
    frame = _read(unit_row, roles={"error": ["dX"]})
    np.testing.assert_allclose(frame[["T_T1", "T_T2"]], np.c_[t1, t2], atol=1e-3)


@pytest.mark.parametrize("written", ["%Y-%m-%d %H:%M:%S,%f", "%d.%m.%Y %H:%M:%S,%f"])
def test_a_timestamp_with_a_seconds_fraction_after_a_comma_reads_in_a_file_and_a_stream(
        tmp_path, written):
    # '2026-03-29 00:59:59,500' (ISO 8601 allows the comma; a European logger writes it) was
    # refused "is not an ISO 8601 timestamp without zone offset (like the first row ...)", and
    # a day-first '29.03.2026 00:59:59,500' too, also with data.time='%d.%m.%Y %H:%M:%S,%f'
    t, t1, t2, e = _record()
    stamps = pd.Timestamp("2026-03-29 00:59:59.5") + pd.to_timedelta(t + 0.25, unit="s")
    cells = [s.strftime(written)[:-3] for s in stamps]
    rows = [f"{c};" + f"{a:.6g};{b:.6g}".replace(".", ",") for c, a, b in zip(cells, t1, e)]
    path = tmp_path / "logger.csv"
    path.write_text("\n".join(["Zeitstempel;T1 [°C];dX [µm]", *rows]) + "\n", encoding="utf-8")
    for time in ("auto", written):
        frame = _read(path, roles={"error": ["dX"]}, time=time)
        np.testing.assert_allclose(frame["time"], t, atol=1e-9)
        np.testing.assert_allclose(frame[["T_T1", "E_dX"]], np.c_[t1, e], atol=1e-3)
        np.testing.assert_allclose(stream_seconds(pd.Series(cells), time), t, atol=1e-9)
    path.write_text(path.read_text(encoding="utf-8").replace(cells[20], "2026-03-29 nachts"),
                    encoding="utf-8")
    with pytest.raises(ContractError, match="line 22 \\(data row 21\\).*'2026-03-29 nachts' is "
                                            "not an? (ISO 8601 timestamp|time in data.time)"):
        _read(path, roles={"error": ["dX"]})
