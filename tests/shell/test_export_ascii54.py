"""The exported C is ASCII whatever letters a lab's headers hold (session 54): a contract name
takes them (`Säule [°C]` -> `T_Säule`), and was written raw beside the lab's name escaped, in the
banner and in the C string literals, so that a source meant to be read as ASCII was not."""

from __future__ import annotations

import io
import subprocess

import numpy as np
import pandas as pd

from test_export import needs_cc
from test_lab_stream52 import compiled
from test_run_column52 import _long, _runs


@needs_cc
def test_the_exported_c_is_ascii_and_reads_a_labs_header_with_umlauts(tmp_path):
    runs = [r.rename(columns={"T0 [°C]": "Säule [°C]", "T1 [°C]": "Stößel [°C]"}) for r in _runs()]
    path = _long(tmp_path / "alle.csv", runs)
    code = compiled(tmp_path, path).parent
    for name in ("compensator.h", "compensator.c", "stream.c"):
        text = (code / name).read_text(encoding="utf-8")
        assert text.isascii(), [ln for ln in text.splitlines() if not ln.isascii()][:3]
    header = (code / "compensator.h").read_text()
    assert "T_S\\xe4ule* degC" in header and "(the lab's 'S\\xe4ule [\\xb0C]')" in header
    # the literals hold the same UTF-8 bytes: the compiled stream still finds both names
    raw = path.read_bytes()
    got = subprocess.run([str(code / "stream")], input=raw, capture_output=True, check=True)
    named = raw.replace("Säule [°C]".encode(), "T_Säule".encode(), 1)
    again = subprocess.run([str(code / "stream")], input=named, capture_output=True, check=True)
    out = pd.read_csv(io.BytesIO(got.stdout)).to_numpy(float)
    assert out.shape == (120, 1) and np.isfinite(out).all()
    assert np.array_equal(out, pd.read_csv(io.BytesIO(again.stdout)).to_numpy(float))
