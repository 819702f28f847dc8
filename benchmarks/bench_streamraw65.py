"""The wire EDM's raw day files streamed into the compiled MLR as written (streamraw65, issue 34).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger65.py write ROOT
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger65.py once ROOT
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_streamraw65.py ROOT

``once`` leaves ``ROOT/once-edm_a`` (``init`` of ``edm_a`` as written, its MLR run).  This bench
exports that model as C with its check pack, compiles it (gcc -std=c99 -Wall -Wextra -Werror),
and feeds the eight raw day files (cp1252, ``;``, decimal commas, a unit row under the header,
``1.200,0``, ``---`` on day 2, the header written again on day 3, ``T Wasser`` from day 6) one
file after the other into ``./stream --state FILE`` (a process a day, as a logger's day files
come; the state carries the week, as replay warms the test day on the six days before it).
Its corrections are compared row by row with the pack's ``expected.csv`` (the served model's,
= replay's stream): max |diff| in µm over the rows each file gave.

No rule is chosen here: what is measured is whether the raw files reach the code as the reader
read them.  Day 2's ``---`` (T Tisch, 5 rows) is a missing value of an input the plain stream
refuses (exit 2 naming the row, as replay's plain stream refuses it); the reader interpolated
it (a train day, ``data.max_gap_samples=5``), which a causal stream cannot.  So the week is
streamed twice: as written (day 2 stops at its first mark; the state after its last good row
goes on), and with day 2's five marked cells written as the values the reader interpolated
(taken from the pack's ``rows.csv``), everything else as written.

Measured (2026-12-01, once; the pack's expected corrections are the served model's stream, as
replay streams it)
------------------------------------------------------------------------------------------
Before (stranger65's stream.c): day 1 exit 2, "the header ... lacks input column T_amb" (``T
Halle`` over its unit row ``°C``; ``T St\xe4nder`` in cp1252).  Now, as written: day 1 1,440 rows;
day 2 600 rows, then exit 2 "row 603: input T_Tisch has no finite value (a data.missing_values
mark ...)"; day 3 1,440 rows, "line 843: the header written again (a logger restarted?): left
out"; days 4-8 1,440 rows each (days 6-8 under ``T Wasser``); max |C - expected| 7.8e-14 µm on
every day's rows (7.1e-14 on day 3's), the test day's included.  Day 2's five marks filled:
11,520 rows of 11,520, the same 7.8e-14 µm.  8 processes: 0.03 s user, 2.3 s sys CPU
(``--state`` renamed after every row).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

REPO = Path(__file__).resolve().parents[1]


def export(root: Path, code: Path) -> None:
    import os

    os.environ["THERMOCOMP_ROOT"] = str(root / "tc")
    run = root / "once-edm_a"
    subprocess.run([sys.executable, "-m", "thermocomp", "export",
                    f"hydra.searchpath=[file://{run / 'conf'}]", "data=edm_a",
                    f"export.model={run / 'run' / 'model.pkl'}", "export.format=c",
                    "export.check=true", f"out={code}"], check=True, capture_output=True)
    subprocess.run(["cc", "-O2", "-std=c99", "-Wall", "-Wextra", "-Werror", "compensator.c",
                    "stream.c", "-lm", "-o", "stream"], cwd=code, check=True)


def week(code: Path, files: list[Path]) -> tuple[list, list]:
    """Each file into ``./stream --state``: (exit status and last stderr line per file, rows)."""
    state = code / "week.state"
    state.unlink(missing_ok=True)
    said, rows = [], []
    for f in files:
        p = subprocess.run(["./stream", "--state", str(state)], cwd=code, input=f.read_bytes(),
                           capture_output=True)
        out = p.stdout.decode().splitlines()[1:]
        rows.append(np.array([[float(v) for v in line.split(",")] for line in out]))
        err = p.stderr.decode().strip().splitlines()
        said.append({"file": f.name, "rc": p.returncode, "rows": len(out),
                     "said": err[-1][:160] if err else ""})
    return said, rows


def compared(code: Path, rows: list, lengths: list[int]) -> dict:
    """max |C - expected| per file, over the rows it gave (file k's rows at its place)."""
    expected = pd.read_csv(next((code / "check").glob("*/expected.csv"))).to_numpy()
    out, at = {}, 0
    for k, (got, n) in enumerate(zip(rows, lengths)):
        if len(got):
            out[k] = float(np.max(np.abs(got - expected[at:at + len(got)])))
        at += n
    return out


def main(root: Path) -> None:
    code = root / "c-streamraw65"
    export(root, code)
    files = sorted((root / "edm_a").glob("EDM_*.csv"))
    lengths = [sum(line[:1].isdigit() for line in f.read_bytes().split(b"\r\n"))
               for f in files]                  # (a data row starts with its date)
    said, rows = week(code, files)
    print(json.dumps({"as written": said, "max_abs_diff_um": compared(code, rows, lengths)},
                     indent=1))
    # day 2's marked cells as the reader interpolated them (the pack's rows.csv)
    pack = pd.read_csv(next((code / "check").glob("*/rows.csv")))
    mended = root / "edm_a-mended"
    mended.mkdir(exist_ok=True)
    for f in files:
        (mended / f.name).write_bytes(f.read_bytes())
    day = mended / files[1].name
    lines = day.read_bytes().decode("cp1252").split("\r\n")
    col = lines[0].split(";").index("T Tisch")
    filled = 0
    for i in range(2, len(lines)):
        cells = lines[i].split(";")
        if len(cells) > col and cells[col] == "---":
            v = pack["T_Tisch"].iloc[lengths[0] + i - 2]
            cells[col] = f"{v:.17g}".replace(".", ",")
            lines[i] = ";".join(cells)
            filled += 1
    day.write_bytes("\r\n".join(lines).encode("cp1252"))
    said, rows = week(code, sorted(mended.glob("EDM_*.csv")))
    diffs = compared(code, rows, lengths)
    print(json.dumps({"day 2's marks filled": filled, "files": said, "max_abs_diff_um": diffs,
                      "rows": sum(len(r) for r in rows), "pack rows": sum(lengths)}, indent=1))


if __name__ == "__main__":
    main(Path(sys.argv[1]).resolve())
