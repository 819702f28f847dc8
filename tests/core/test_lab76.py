"""Campbell Scientific's framed binary tables TOB3 / TOB2 (lab76), written here with
``struct.pack`` to the layout csiio-py and camp2ascii read (six ASCII header lines, then frames:
a header with the frame's time (TOB3: and its first record number), records at the table's
interval, a footer with flags and the validation stamp): a stale frame left out and said, a
partial (minor) frame's records read, a ring wrap put in the logger's order and said, a file
mark ending a run, a frame cut short refused naming it.  Before: refused ("no column ...")."""

from __future__ import annotations

import datetime as dt
import struct
from pathlib import Path

import numpy as np
import pytest

from conftest import thermocomp
from test_tob1_75 import fp2, spindle
from thermocomp.core.io import ContractError, read_dataset

START = dt.datetime(2025, 3, 27, 23, 30)
STAMP = 0x3A7C
ENV = '"{kind}","MZ_Halle3","CR1000X","12345","CR1000X.Std.05.02","CPU:thermo_mz.CR1X","26142",' \
      '"2025-03-27 23:29:58"'
NAMES = ['"T_spindle_Avg","T_air_Avg","dX_Avg","dZ_Avg","BattV_Min"',
         '"Deg C","Deg C","um","mm","Volts"', '"Avg","Avg","Avg","Avg","Min"',
         '"IEEE4","IEEE4","FP2","IEEE4B","FP2"']
RECORD = 16                        # bytes: IEEE4 + IEEE4 + FP2 + IEEE4B + FP2
PER_FRAME = 3
MINOR, FILE_MARK = 1 << 14, 1 << 11
ROLES = {"roles": {"error": ["d*"]}}


def frame_size(kind: str) -> int:
    return (12 if kind == "TOB3" else 8) + PER_FRAME * RECORD + 4


def rows(first: int, count: int) -> bytes:
    out = b""
    for i in range(first, first + count):
        t_spindle, t_air, dx, dz = spindle(i)
        out += struct.pack("<ff", t_spindle, t_air) + fp2(dx) + struct.pack(">f", dz) + fp2(12.61)
    return out


def frame(kind: str, first: int, count: int = PER_FRAME, flags: int = 0, stamp: int = STAMP,
          sub: int = 0) -> bytes:
    """A frame of records ``first`` ...: a major frame, or (``count`` < PER_FRAME) a minor frame
    of ``count`` records followed by the unused bytes and the frame's footer."""
    seconds = int((START - dt.datetime(1990, 1, 1)).total_seconds()) + 600 * first
    head = struct.pack("<II", seconds, sub) + (struct.pack("<I", 1000 + first) if kind == "TOB3"
                                               else b"")
    if count == PER_FRAME:
        return head + rows(first, count) + struct.pack("<HH", flags, stamp)
    part = len(head) + count * RECORD + 4
    tail = frame_size(kind) - part
    return (head + rows(first, count) + struct.pack("<HH", MINOR | part, stamp)
            + b"\0" * (tail - 4) + struct.pack("<HH", MINOR | flags | tail, stamp))


def tob3(path: Path, frames: list[bytes], kind: str = "TOB3", interval: str = "10 MIN") -> Path:
    table = (f'"Therm10min","{interval}","{frame_size(kind)}","1000","{STAMP}","Sec100Usec",'
             '"0","0","1234567"')
    head = "\r\n".join([ENV.format(kind=kind), table, *NAMES]) + "\r\n"
    path.write_bytes(head.encode() + b"".join(frames))
    return path


def card(kind: str = "TOB3") -> list[bytes]:
    """23 records: seven frames (the second's time 0.5 s late), a stale frame of an earlier
    table after the fourth, and a partial frame of the last two records."""
    out = [frame(kind, 3 * k, sub=5000 * (k == 1)) for k in range(7)]
    out.insert(4, frame(kind, 90, stamp=0x1111))
    return [*out, frame(kind, 21, count=2)]


def test_a_tob3_file_reads_its_frames_a_stale_one_left_out_and_said(tmp_path, caplog):
    ds, report = read_dataset(tob3(tmp_path / "card.dat", card()), ROLES)
    df = ds.campaigns[ds.ids()[0]]
    assert list(df.columns) == ["time", "T_spindle_Avg", "T_air_Avg", "E_dX_Avg", "E_dZ_Avg",
                                "S_BattV_Min"]
    assert report["campaigns"][ds.ids()[0]]["time_origin"] == "2025-03-27T23:30:00"
    want_time = 600.0 * np.arange(23)
    want_time[3:6] += 0.5                      # (frame 2's sub-seconds: 5000 x 100 µs)
    assert df["time"].tolist() == want_time.tolist()
    want = np.array([spindle(i) for i in range(23)])
    assert df["T_spindle_Avg"].to_numpy() == pytest.approx(want[:, 0], abs=1e-5)
    assert df["E_dX_Avg"].to_numpy() == pytest.approx(want[:, 2], abs=5e-4)       # FP2, µm
    assert df["E_dZ_Avg"].to_numpy() == pytest.approx(want[:, 3] * 1000, abs=1e-3)  # IEEE4B, mm
    assert ("1 of 9 frames (5) carry another validation stamp than the file's 14972 (frames of "
            "an earlier table left on the card): left out") in caplog.text


def test_a_ring_wrap_is_read_in_the_loggers_order_and_said(tmp_path, caplog):
    """The card full, the table went on at its start: frames 7-9 first in the file.  Read by
    record number, as unwrapped."""
    frames = card()
    plain, _ = read_dataset(tob3(tmp_path / "plain.dat", frames), ROLES)
    ring, _ = read_dataset(tob3(tmp_path / "ring.dat", frames[6:] + frames[:6]), ROLES)
    np.testing.assert_array_equal(ring.campaigns[ring.ids()[0]].to_numpy(),
                                  plain.campaigns[plain.ids()[0]].to_numpy())
    assert ("frame 4 follows frame 3 in the file but comes before it (record 1000 < 1021): the "
            "table wrapped around its ring on the card; its frames read in the logger's order, "
            "by their record numbers") in caplog.text


def test_a_tob2_file_mark_ends_a_run(tmp_path):
    """TOB2: no record number in the frame header; a file mark after frame 4 (record 12):
    two runs, each a campaign."""
    frames = [frame("TOB2", 3 * k, flags=FILE_MARK * (k == 3)) for k in range(8)]
    ds, _ = read_dataset(tob3(tmp_path / "marked.dat", frames, "TOB2"),
                         {"roles": {"error": ["d*"], "campaign": "run"}})
    assert [len(ds.campaigns[c]) for c in ds.ids()] == [12, 12]
    second = ds.campaigns[ds.ids()[1]]
    assert second["T_air_Avg"].to_numpy() == pytest.approx([spindle(i)[1] for i in range(12, 24)])


def test_a_cut_frame_a_broken_minor_frame_and_overlapping_frames_are_refused(tmp_path):
    frames = card()
    cut = tob3(tmp_path / "cut.dat", frames)
    cut.write_bytes(cut.read_bytes() + frames[0][:20])
    with pytest.raises(ContractError, match=r"cut.dat: frame 10 \(from byte \d+\) is cut short: 20 "
                                            r"of its 64 bytes.*cut the file after frame 9"):
        read_dataset(cut, ROLES)
    broken = bytearray(frames[-1])
    broken[-4:-2] = struct.pack("<H", MINOR | 20)      # the unused bytes said 20, not 16
    with pytest.raises(ContractError, match=r"frame 9 is a minor frame whose parts do not add up"):
        read_dataset(tob3(tmp_path / "broken.dat", [*frames[:-1], bytes(broken)]), ROLES)
    with pytest.raises(ContractError, match=r"frames 1 and 2 overlap in time"):
        read_dataset(tob3(tmp_path / "twice.dat", [frames[0], frame("TOB3", 1)]), ROLES)


def test_init_names_a_tob3_table_and_run_reads_its_config(tmp_path):
    tob3(tmp_path / "card.dat", card())
    said = thermocomp("init", str(tmp_path / "card.dat"), f"out={tmp_path / 'init'}").stdout
    assert ("card.dat: a Campbell Scientific TOB3 table 'Therm10min' of station 'MZ_Halle3' "
            "(CR1000X, serial 12345, program 'CPU:thermo_mz.CR1X') (its channels as columns)"
            ) in said, said
    assert "dZ_Avg [mm]            error        E_dZ_Avg" in said
    # (a binary table is no Windows export: no data.encoding written)
    assert "encoding" not in (tmp_path / "init" / "conf" / "data" / "card.yaml").read_text()
    ran = thermocomp("run", f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]",
                     "data=card", "model=mlr", "eval.validation=false", "track=false",
                     "plots=none", f"out={tmp_path / 'run'}").stdout
    assert "E_dZ_Avg" in ran


def test_init_converts_a_lab_file_once_and_says_an_infinity_once(tmp_path, monkeypatch):
    """A TOB1 table: converted once for init's looks and its read (before: five times, for the
    period, the head, the cells, the runs and the read).  A TOA5 file's ``INF``: said once, by
    the read with its rows (before: init's line too, ``'INF' in 2 cell(s) of ...``)."""
    import contextlib

    from test_lab75 import HALLE
    from test_tob1_75 import tob1
    from thermocomp.core.io import plain

    converted = []
    convert = plain.records_as_csv

    @contextlib.contextmanager
    def counted(records, path):
        converted.append(path)
        with convert(records, path) as text:
            yield text

    monkeypatch.setattr(plain, "records_as_csv", counted)
    thermocomp("init", str(tob1(tmp_path / "therm.dat")), f"out={tmp_path / 'tob1'}")
    assert len(converted) == 1, converted
    done = thermocomp("init", str(HALLE), f"out={tmp_path / 'toa5'}")
    said = [line for line in (done.stdout + done.stderr).splitlines() if "T_spindle_Avg" in line
            and "infinite reading" in line]
    assert len(said) == 1 and "line 9 (data row 5), line 10 (data row 6)" in said[0], said


def test_a_relative_humidity_is_proposed_ignored_a_load_in_percent_a_state():
    """``%`` under a humidity's name (RH, rel. hum., Luftfeuchte, humidity): no thermal input,
    proposed ``ignore`` and said with the key that reads it as a state; a spindle's load in
    ``%`` stays a state.  Before: every ``%`` column proposed a state."""
    from thermocomp.core.io.detect import foreign_said, proposed_roles
    from thermocomp.core.io.options import ReadOptions

    header = ["time", "T1 [°C]", "E_X [µm]", "RH_hall [%]", "rel. hum. [%]", "Luftfeuchte [%]",
              "Humidity [%]", "Spindle load [%]"]
    first = dict.fromkeys(header, "1.5")
    opts = ReadOptions.from_cfg({})
    roles = proposed_roles(header, first, opts)
    assert roles["ignore"] == ["RH_hall", "rel. hum.", "Luftfeuchte", "Humidity"]
    assert roles["state"] == ["Spindle load"]
    said = foreign_said(header, roles, opts, stated=False)
    assert said[0] == ("'RH_hall [%]': a relative humidity (its name, unit '%'), no temperature "
                       "nor machine state: it drives no thermal error, and what it says of the "
                       "machine the air's temperature says; proposed data.roles.ignore "
                       "(data.roles.state=[RH_hall] reads it as a machine state)")


def test_a_tob1_tables_int4_and_uint2_are_big_endian(tmp_path):
    """``INT4`` / ``UINT2`` as csiio-py and camp2ascii read them, big-endian (before: read
    little-endian, -3 µm as -33554433 µm)."""
    head = ['"TOB1","MZ_Halle3","CR1000X","12345","CR1000X.Std.05.02","CPU:t.CR1X","26142","Fast"',
            '"SECONDS","NANOSECONDS","T_Avg","dX_Avg","N_Avg"', '"","","Deg C","um","rpm"',
            '"","","Avg","Avg","Avg"', '"ULONG","ULONG","IEEE4","INT4","UINT2"']
    seconds = int((START - dt.datetime(1990, 1, 1)).total_seconds())
    body = b"".join(struct.pack("<IIf", seconds + 60 * i, 0, 20 + i) + struct.pack(">iH", i - 3,
                                                                                   1000 * i)
                    for i in range(6))
    path = tmp_path / "fast.dat"
    path.write_bytes(("\r\n".join(head) + "\r\n").encode() + body)
    ds, _ = read_dataset(path, ROLES)
    df = ds.campaigns[ds.ids()[0]]
    assert df["E_dX_Avg"].tolist() == [-3.0, -2.0, -1.0, 0.0, 1.0, 2.0]
    assert df["S_N_Avg"].tolist() == [0.0, 1000.0, 2000.0, 3000.0, 4000.0, 5000.0]
