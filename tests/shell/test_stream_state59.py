"""``stream --state FILE`` (the exported C driver, docs/to-the-machine.md "Restarted
mid-campaign"): a stream cut in two processes goes on as one, the compensator's state, the
stream's clock and its run read back from FILE; without FILE the second process starts cold."""

from __future__ import annotations

import subprocess

import pandas as pd
import pytest

from test_export import needs_cc
from test_lab_stream52 import compiled
from test_run_column52 import _long, _runs

CUT = 12      # data rows of the first process: mid-run 3 (runs 3 and 4 of 30 rows streamed)


def _stream(binary, rows: list[str], header: str, *args) -> list[str]:
    """The corrections ``binary`` prints (one line a row) for ``header`` and ``rows``."""
    run = subprocess.run([str(binary), *args], input="\n".join([header, *rows, ""]).encode(),
                         capture_output=True, check=True)
    return run.stdout.decode().splitlines()[1:]


def _wall_clock(row: str) -> str:
    """The row with its ``Zeit [s]`` (decimal comma) as a logger's ISO 8601 time."""
    cells = row.split(";")
    cells[1] = (pd.Timestamp("2026-11-30T06:00:00") + pd.Timedelta(
        seconds=float(cells[1].replace(",", ".")))).isoformat()
    return ";".join(cells)


@pytest.fixture(scope="module")
def stream(tmp_path_factory):
    """The compiled driver of a lag bank (its lags read the time) and runs 3 and 4 of the lab's
    long file (``;``, decimal commas, a run column ``Lauf``)."""
    tmp = tmp_path_factory.mktemp("state")
    path = _long(tmp / "alle.csv", _runs())
    binary = compiled(tmp, path)
    lines = path.read_text(encoding="utf-8").splitlines()
    return binary, lines[0], [ln for ln in lines[1:] if ln.split(";")[0] in "34"]


@needs_cc
@pytest.mark.parametrize("clock", ["seconds", "wall clock"])
def test_a_stream_cut_in_two_with_its_state_file_is_the_stream_uninterrupted(stream, tmp_path,
                                                                             clock):
    binary, header, rows = stream
    if clock == "wall clock":      # the clock's origin is the run's first time: kept too
        rows = [_wall_clock(r) for r in rows]
    whole = _stream(binary, rows, header)
    assert len(whole) == len(rows) == 60
    state = tmp_path / "tc.state"
    first = _stream(binary, rows[:CUT], header, "--state", str(state))
    assert state.is_file() and not (tmp_path / "tc.state.tmp").exists()
    second = _stream(binary, rows[CUT:], header, "--state", str(state))
    assert first + second == whole                  # to the printed digit (%.17g)
    # a process restarted without it starts run 3 again from its row CUT + 1: cold
    cold = _stream(binary, rows[CUT:], header)
    assert cold[:30 - CUT] != whole[CUT:30]
    assert cold[30 - CUT:] == whole[30:]            # run 4 starts from a reset either way


@needs_cc
def test_a_state_file_this_build_did_not_write_is_refused(stream, tmp_path):
    binary, header, rows = stream
    state = tmp_path / "tc.state"
    state.write_bytes(b"tcstat1\0" + bytes(40))
    run = subprocess.run([str(binary), "--state", str(state)],
                         input="\n".join([header, *rows, ""]).encode(), capture_output=True)
    assert run.returncode == 2 and b"is no state this build wrote" in run.stderr
    assert state.read_bytes() == b"tcstat1\0" + bytes(40)        # left as it was


@needs_cc
@pytest.mark.parametrize("kind", ["time set back", "row written again", "missing value"])
def test_a_state_file_written_at_a_row_the_stream_refuses_goes_on_as_one_stream(stream, tmp_path,
                                                                                  kind):
    # dep107: the state after a row the time rule takes over (its time set back, or the row
    # written again: one period on) or that stream.c refuses (an input missing: exit 2, the
    # state of the row before kept) goes on in a fresh process as the stream of the same rows
    # uninterrupted, the refused row left out (as the served model refuses it and goes on)
    binary, header, rows = stream
    cells = rows[CUT - 1].split(";")
    time_at, input_at = header.split(";").index("Zeit [s]"), header.split(";").index("T0 [°C]")
    if kind == "time set back":
        cells[time_at] = rows[CUT - 4].split(";")[time_at]
    if kind == "missing value":
        cells[input_at] = ""
    odd = [rows[CUT - 1]] * 2 if kind == "row written again" else [";".join(cells)]
    fed = [*rows[:CUT - 1], *odd, *rows[CUT:]]
    state = tmp_path / "tc.state"
    first = subprocess.run([str(binary), "--state", str(state)], capture_output=True,
                           input="\n".join([header, *fed[:CUT - 1 + len(odd)], ""]).encode())
    assert first.returncode == (2 if kind == "missing value" else 0), first.stderr
    second = _stream(binary, rows[CUT:], header, "--state", str(state))
    taken = [*rows[:CUT - 1], *rows[CUT:]] if kind == "missing value" else fed
    assert second == _stream(binary, taken, header)[-len(rows[CUT:]):]
