"""The exported C as the benches build and feed it: compiled as a control's build would
(warnings as errors), rows piped through ``stream.c``, and the pooled error after correction."""

from __future__ import annotations

import io
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd


def built(folder: Path, files: dict) -> Path:
    """``files`` (name -> text) written into ``folder`` and compiled: the ``stream`` program."""
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in files.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text)
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "compensator.c",
                    "stream.c", "-lm", "-o", "stream"], cwd=folder, check=True, capture_output=True)
    return folder / "stream"


def streamed(binary: Path, frame: pd.DataFrame) -> np.ndarray:
    """The corrections ``binary`` prints for the rows of ``frame`` (it must take them all)."""
    text = frame.to_csv(index=False, float_format="%.17g")
    run = subprocess.run([str(binary)], input=text, text=True, capture_output=True, check=True)
    return pd.read_csv(io.StringIO(run.stdout)).to_numpy(float)


def rmse(errors: list, corrections: list) -> np.ndarray:
    """Per target, the RMS of the errors after their corrections, pooled over the campaigns."""
    r = np.vstack([e + c for e, c in zip(errors, corrections)])
    return np.sqrt(np.mean(r ** 2, axis=0))
