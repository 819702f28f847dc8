"""A lab's ISO 230-3 thermal tests (iso67, ``benchmarks/bench_iso67.py``): the sensor nest's
tilts (``Tilt A [µrad]``, ``Tilt B [″]``) read as angular errors in µm/m and named so in every
table, the nest software's elapsed ``hh:mm:ss.s`` read by the compiled stream, and a refusal
naming ``data.split_overrides`` where a folder has no ``campaigns.csv``."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import FAST, refused
from test_export import needs_cc
from test_stranger65 import _compiled_stream_equals_its_pack
from thermocomp.core import io
from thermocomp.core.io.contract import ContractError
from thermocomp.core.io.roles import naming
from thermocomp.shell.cli import main

ARCSEC = np.pi / 648000 * 1e6          # µrad


def clock(t: float) -> str:
    tenths = int(round(t * 10))
    h, rest = divmod(tenths, 36000)
    return f"{h:02d}:{rest // 600:02d}:{rest % 600 // 10:02d}.{rest % 10}"


def nest_file(path, seed: int, hours: float, period: float = 60.0):
    """One test as a sensor nest's software writes it: an INI-like ``[Header]`` block, then
    ``[Data]`` and a TAB table, the time ``hh:mm:ss.s`` since the start (past 24 h as it is), a
    tilt in µrad and one in arcsec (″); returns the tilts as written (µrad, arcsec)."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, hours * 3600.0, period)
    rpm = np.where((t > 600) & (t < hours * 1800), 1000.0 * (2 + seed % 5), 0.0)
    spindle = 20 + np.cumsum(rpm / 1e6 - 0.0005 * np.cumsum(rpm > 0) / 3e3
                             + rng.normal(0, 0.01, t.size))
    air = 20 + 0.5 * np.sin(t / 20000.0 + seed) + rng.normal(0, 0.01, t.size)
    tilt_a = 6 * (spindle - spindle[0]) - 3 * (air - air[0]) + rng.normal(0, 0.1, t.size)
    tilt_b = (4 * (spindle - spindle[0]) + rng.normal(0, 0.1, t.size)) / ARCSEC
    dx = 2 * (spindle - spindle[0]) + rng.normal(0, 0.1, t.size)
    head = ["[Header]", "Software\tNestLog 3.2", "Standard\tISO 230-3:2020", "Test\tSPINDLE",
            "Sample rate\t60 s", "[Data]",
            "Time\tX1 [µm]\tTilt A [µrad]\tTilt B [″]\tT1 Spindle [°C]\tT2 Air [°C]\tSpindle speed [rpm]"]
    rows = [f"{clock(a)}\t{b:.3f}\t{c:.3f}\t{d:.4f}\t{e:.3f}\t{f:.3f}\t{g:.0f}"
            for a, b, c, d, e, f, g in zip(t, dx, tilt_a, tilt_b, spindle, air, rpm)]
    path.write_bytes(("\r\n".join(head + rows) + "\r\n").encode("utf-8"))
    return tilt_a, tilt_b


def nest_folder(folder):
    folder.mkdir()
    return {name: nest_file(folder / f"{name}.txt", seed, hours)
            for name, seed, hours in (("01_ETVE", 1, 26.0), ("02_SPINDLE", 2, 6.0),
                                      ("03_SPINDLE", 3, 6.0), ("04_SPINDLE", 4, 6.0))}


def test_a_nests_tilts_are_angular_errors_in_um_per_m(tmp_path, capsys):
    # before: "2 column(s) not read: 'Tilt A [µrad]': unit 'µrad' is not a temperature's (°C, K,
    # °F), 'Tilt B [″]': ..." -- an angle had no role, and no unit but µm for an error
    written = nest_folder(tmp_path / "nest")
    assert main(["init", str(tmp_path / "nest"), f"out={tmp_path / 'init'}"]) in (0, None)
    out = capsys.readouterr().out
    assert "E_Tilt_A (an angle, in µm/m = µrad)" in out
    assert f"E_Tilt_B (an angle, in µm/m = µrad: ″ x {ARCSEC:.6g})" in out
    ds = io.read_dataset(tmp_path / "nest", {"time": "elapsed", "roles": {
        "error": ["X1", "Tilt A", "Tilt B"], "state": ["Spindle speed"]}})[0]
    frame = ds.campaigns["02_SPINDLE"]
    a, b = written["02_SPINDLE"]
    assert np.abs(frame["E_Tilt_A"].to_numpy() - np.round(a, 3)).max() < 1e-9
    # arcsec converted to µrad (the contract's µm/m for an angular error), as written to 4 places
    assert np.abs(frame["E_Tilt_B"].to_numpy() - np.round(b, 4) * ARCSEC).max() < 1e-9
    assert main(["run", f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=nest",
                 *FAST, "model=mlr", "plots=none", f"out={tmp_path / 'run'}"]) == 0
    assert "(µm; E_Tilt_A, E_Tilt_B in µm/m)" in capsys.readouterr().out


def test_an_angle_under_a_lengths_contract_name_is_refused_naming_the_fix():
    # a lab's own contract name for a tilt, 'E_tiltA' would read as µm: refused, the fix named
    # (before: "unit 'µrad' is not an error's (µm, mm, m, nm)", no way given)
    with pytest.raises(ContractError, match=r"an angle, its name a length's \(µm\): name it as a "
                       r"tilt, data.columns=\{'E_A1 \[µrad\]': E_tilt_A1\}"):
        naming(["time", "E_A1 [µrad]", "T_1"], {"roles": {}}, {}, {"E_A1 [µrad]": "1.0"})
    # a header in an angle whose name says no rotation: its contract name says it, converted
    got = naming(["time", "Kanal 4 [arcsec]", "T1 [°C]"], {"error": ["Kanal 4"]}, {},
                 {"Kanal 4 [arcsec]": "1.0", "T1 [°C]": "20.0"})
    assert got.names["Kanal 4 [arcsec]"] == "E_tilt_Kanal_4"
    assert got.scales["E_tilt_Kanal_4"][0] == pytest.approx(ARCSEC)
    # ISO 230-1's names are angular already: converted, kept
    got = naming(["time", "E_AX [arcsec]", "T_1"], {"roles": {}}, {}, {"E_AX [arcsec]": "1.0"})
    assert got.names["E_AX [arcsec]"] == "E_AX" and got.scales["E_AX"][0] == pytest.approx(ARCSEC)


@needs_cc
def test_the_compiled_stream_reads_the_nests_elapsed_time(tmp_path):
    # before: export.format=c refused: "the time column 'Time' is read as data.time=elapsed,
    # which stream.c cannot convert"; now the raw export piped in gives the pack's corrections
    path = tmp_path / "etve.txt"
    nest_file(path, 7, 30.0)
    common = [f"data.path={path}", "data.roles.error=[X1]", "data.roles.ignore=[Tilt A,Tilt B]",
              "data.roles.state=[Spindle speed]", "data.time=elapsed", "data.test_fraction=0.3"]
    _compiled_stream_equals_its_pack(tmp_path, path, common)


def test_a_fraction_beside_split_overrides_names_them_not_a_manifest(tmp_path, capsys):
    # before: "file .../nest/campaigns.csv, column 'split': data.test_fraction is set but the
    # manifest has test campaigns already" -- a folder without campaigns.csv, the test given
    # by data.split_overrides (the ETVE scored alone)
    nest_folder(tmp_path / "nest")
    line = refused(["run", f"data.path={tmp_path / 'nest'}", "data.time=elapsed",
                    "data.roles.error=[X1,Tilt A,Tilt B]", "data.roles.state=[Spindle speed]",
                    "data.split_overrides={01_ETVE: test}", "data.test_fraction=0.25", *FAST,
                    "model=mlr", "plots=none", f"out={tmp_path / 'run'}"], capsys,
                   "data.split_overrides makes 01_ETVE test already", "data.test_fraction=null")
    assert "campaigns.csv" not in line


def test_the_diagnosis_report_gives_a_tilt_its_unit(tmp_path, capsys):
    # before: every figure of the report said µm, an angular error's (E_AX, ISO 230-1's tilt
    # about X, in µm/m = µrad) too
    nest_folder(tmp_path / "nest")
    for path in (tmp_path / "nest").glob("*.txt"):      # the tilt about X under ISO 230-1's name
        path.write_bytes(path.read_bytes().replace("Tilt A [µrad]".encode(), b"E_AX"))
    assert main(["diagnose", f"data.path={tmp_path / 'nest'}", "data.time=elapsed",
                 "data.roles.error=[X1]", "data.roles.ignore=[Tilt B]",
                 "data.roles.state=[Spindle speed]",
                 "data.test_fraction=0.25", "model=mlr", "plots=none", "track=false",
                 f"out={tmp_path / 'diag'}"]) == 0
    md = (tmp_path / "diag" / "diagnosis" / "report.md").read_text(encoding="utf-8")
    tilt = md[md.index("\n## E_AX"):]
    tilt = tilt[:tilt.index("\n## ", 1)] if "\n## " in tilt[1:] else tilt
    assert "| test RMSE (µm/m) |" in tilt and "CV RMSE at the start of this round:" in tilt
    assert "(µm)" not in tilt and " µm." not in tilt and " µm;" not in tilt
    assert "(µm; E_AX in µm/m)" in md
    other = md[md.index("\n## E_X1"):]
    assert "| test RMSE (µm) |" in other


def test_the_generated_codes_banner_gives_a_tilt_its_unit(tmp_path):
    # before: "outputs: C_X1, C_AX in um" and its guard's bound and rate in um, um/s: an
    # integrator reading the banner would apply a tilt's µrad as µm
    nest_folder(tmp_path / "nest")
    for path in (tmp_path / "nest").glob("*.txt"):
        path.write_bytes(path.read_bytes().replace("Tilt A [µrad]".encode(), b"E_AX"))
    common = [f"data.path={tmp_path / 'nest'}", "data.time=elapsed", "data.roles.error=[X1]",
              "data.roles.ignore=[Tilt B]", "data.roles.state=[Spindle speed]",
              "data.test_fraction=0.25"]
    assert main(["run", *common, *FAST, "model=mlr", "plots=none", f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, "track=false", "export.format=st", "export.check=false",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'st'}"]) == 0
    text = "\n".join(p.read_text(encoding="utf-8", errors="replace")
                     for p in (tmp_path / "st").iterdir() if p.is_file())
    assert "outputs: C_X1, C_AX in um (C_AX in um/m = urad, angular errors)" in text
    assert "guard E_AX: bound [" in text
    guard = text[text.index("guard E_AX: bound ["):].splitlines()[0]
    assert "] um/m, rate limit" in guard and guard.endswith("um/m/s")
    assert "] um, rate limit" in text[text.index("guard E_X1: bound ["):].splitlines()[0]
