"""A Windows export with a preamble line above its header, read as UTF-8: the refusal names the
column that holds the byte, or none where the byte is in the preamble (audit98: a
``# Sample period: 60 s`` line above ``T_amb [°C];...`` was named as the column)."""

from __future__ import annotations

from pathlib import Path

import pytest

from thermocomp.core.io import ContractError, read_dataset


def _export(path: Path, preamble: str) -> Path:
    """cp1252 bytes (° is 0xB0): ``preamble``, then ``T1 [°C];dX [µm]`` and three rows."""
    rows = [f"{20 + k / 10:.1f};{k / 2:.1f}".replace(".", ",") for k in range(3)]
    path.write_bytes("\r\n".join([preamble, "T1 [°C];dX [µm]", *rows, ""]).encode("cp1252"))
    return path


def _refusal(path: Path) -> ContractError:
    with pytest.raises(ContractError) as refusal:
        read_dataset(path, {"roles": {"error": ["dX"]}, "sample_period_s": 60.0})
    return refusal.value


def test_a_byte_in_the_header_under_a_preamble_names_its_column(tmp_path):
    said = _refusal(_export(tmp_path / "lab.csv", "# Sample period: 60 s"))
    assert "byte 0xb0" in str(said) and "data.encoding=cp1252" in str(said)
    assert said.column.startswith("T1 [") and "line 2" in str(said)   # before: '# Sample period: 60 s'


def test_a_byte_in_the_preamble_names_no_column(tmp_path):
    said = _refusal(_export(tmp_path / "lab.csv", "# Halle 20 °C, sample period: 60 s"))
    assert "byte 0xb0" in str(said) and "line 1" in str(said)
    assert said.column is None                    # before: the preamble line named as a column
