"""The exported C as the benches run it: compiled with gcc, fed a CSV text on stdin, whole and
stopped half-way then resumed with ``--state`` (the two diagnosed-to-code benches had each their
own copy of these steps)."""

from __future__ import annotations

import io
import json
import re
import subprocess
from pathlib import Path

import pandas as pd

STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-O2"]


def compile_stream(folder: Path, flags: list[str] = STRICT) -> Path:
    """``compensator.c`` + ``stream.c`` of an export folder built into ``folder/stream``."""
    subprocess.run(["cc", *flags, "compensator.c", "stream.c", "-lm", "-o", "stream"], cwd=folder,
                   check=True)
    return folder / "stream"


def streamed(binary: Path, text: str, state: Path | None = None) -> pd.DataFrame:
    """The corrections ``binary`` prints for the CSV ``text`` (``state``: ``--state FILE``)."""
    args = [str(binary)] + (["--state", str(state)] if state else [])
    p = subprocess.run(args, input=text, capture_output=True, text=True, check=True)
    return pd.read_csv(io.StringIO(p.stdout))


def whole_and_resumed(binary: Path, text: str) -> tuple[pd.DataFrame, pd.DataFrame]:
    """The stream of ``text`` whole, and stopped after half its lines and resumed in a new
    process from the state file (the header given again)."""
    lines = text.splitlines()
    half = len(lines) // 2
    state = binary.parent / "state.bin"
    state.unlink(missing_ok=True)
    first = streamed(binary, "\n".join(lines[:half]) + "\n", state)
    second = streamed(binary, "\n".join([lines[0]] + lines[half:]) + "\n", state)
    return streamed(binary, text), pd.concat([first, second], ignore_index=True)


def checked(folder: Path) -> str:
    """An export folder's C built (:data:`STRICT`) and run on its conformance pack
    (``check/check.sh``): one line, the binary's size, passed or not, rows and the largest
    |C - replay|."""
    binary = compile_stream(folder)
    check = subprocess.run(["sh", "check/check.sh"], cwd=folder, capture_output=True, text=True)
    worst = [float(w) for w in re.findall(r"largest \|difference\| (\S+) um", check.stderr)]
    rows = sum(e["rows"] for e in json.loads((folder / "check" / "check.json").read_text())["campaigns"])
    return (f"stream built {binary.stat().st_size / 1024:,.0f} KB; check "
            f"{'passed' if check.returncode == 0 else 'FAILED'}: {rows:,} rows, largest "
            f"|C - replay| {max(worst, default=float('nan')):.2g} um")
