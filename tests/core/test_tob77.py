"""Campbell Scientific's TOB3 / TOB2 marks and FP2 infinities (lab77), on test_lab76's card: a
remove mark (the card taken out, logging to it stopped) ends a run as a file mark does
(CardConvert's *Use RemoveMarks*), said; a mark on a partial frame ends its last part only; an
FP2 ``INF`` / ``-INF`` (``0x1FFF`` / ``0x9FFF``) is named as a TOA5 file's ``INF`` is (its column
and rows: a logger's overflow or an open input).  Before: the remove mark read over, the table
going on across the pause; the infinity an unnamed gap."""

from __future__ import annotations

import struct

import pytest

from test_lab76 import FILE_MARK, MINOR, RECORD, STAMP, frame, spindle, tob3
from test_tob1_75 import fp2
from thermocomp.core.io import read_dataset

REMOVE_MARK = 1 << 12
RUNS = {"roles": {"error": ["d*"], "campaign": "run"}}


@pytest.mark.parametrize("kind", ["TOB3", "TOB2"])
def test_a_remove_mark_ends_a_run_as_a_file_mark_does(tmp_path, caplog, kind):
    frames = [frame(kind, 3 * k, flags=REMOVE_MARK * (k == 2) | FILE_MARK * (k == 5))
              for k in range(8)]
    ds, _ = read_dataset(tob3(tmp_path / "card.dat", frames, kind), RUNS)
    assert [len(ds.campaigns[c]) for c in ds.ids()] == [9, 9, 6]
    second = ds.campaigns[ds.ids()[1]]
    assert second["T_air_Avg"].to_numpy() == pytest.approx([spindle(i)[1] for i in range(9, 18)])
    assert ("card.dat: a remove mark (the card taken out, logging to it stopped) in frame 3: the "
            "records after it are the next run, as after a file mark") in caplog.text


def test_a_file_mark_on_a_partial_frame_ends_its_last_part_only(tmp_path):
    """TOB2: frame 3 written as two minor frames of one record each (records 6 and 7), its
    footer a file mark: one run of 8 records, then the next.  Before, each minor frame ended a
    run (a run of 7 records, one of 1, then the next)."""
    def minor(record: int) -> bytes:
        whole = frame("TOB2", record)                  # (its header, then its first record)
        size = 8 + RECORD + 4
        return whole[:8 + RECORD] + struct.pack("<HH", MINOR | size, STAMP)

    parts = minor(6) + minor(7)
    tail = len(frame("TOB2", 0)) - len(parts)
    partial = parts + b"\0" * (tail - 4) + struct.pack("<HH", MINOR | FILE_MARK | tail, STAMP)
    frames = [frame("TOB2", 0), frame("TOB2", 3), partial, frame("TOB2", 9), frame("TOB2", 12)]
    ds, _ = read_dataset(tob3(tmp_path / "card.dat", frames, "TOB2"), RUNS)
    assert [len(ds.campaigns[c]) for c in ds.ids()] == [8, 6]


def test_an_fp2_infinity_is_named_as_a_toa5_files_inf_is(tmp_path, caplog):
    frames = [frame("TOB3", 3 * k) for k in range(6)]
    body = bytearray(frames[2])
    for record, word in ((1, 0x1FFF), (2, 0x9FFF)):        # dX_Avg of records 7 and 8
        at = 12 + record * RECORD + 8
        body[at:at + 2] = fp2(0, word)
    frames[2] = bytes(body)
    ds, _ = read_dataset(tob3(tmp_path / "card.dat", frames),
                         {"roles": {"error": ["d*"]}, "max_gap_samples": 2})
    df = ds.campaigns[ds.ids()[0]]
    assert len(df) == 18 and df["E_dX_Avg"].notna().all()          # (the gap repaired)
    assert ("column 'E_dX_Avg': 2 infinite reading(s) (row 8 (data row 8), row 9 (data row 9)): "
            "a logger's overflow or an open input, read as missing (its header in the file: "
            "'dX_Avg [um]')") in caplog.text, caplog.text
