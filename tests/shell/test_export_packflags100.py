"""The conformance pack checks the C's monitor flags (packflags100, issue 34;
benchmarks/bench_packflags100.py): where the code holds the sensor monitor, export writes beside
each campaign's ``expected.csv`` a ``flags.csv`` (the mirror's flags per row, as ``stream --flags``
prints them) and ``check.sh`` runs ``stream --check-flags`` on it, so a build whose corrections
are right and whose flags are wrong fails on the target, the row, the flag and both values named.

On test_export's three-sensor record (MLR deployed adaptive, test_export_monitor76's fixture): a
+3 degC jump of ``T_b`` in a test campaign (excluded, rebuilt, re-admitted), and the planted
faults the pack adds.  Fails on 063630e6: no flags.csv, and check.sh passes a build with two flag
bits swapped."""

from __future__ import annotations

import subprocess

from test_export import built_stream, needs_cc
from test_export_monitor76 import _stepped, served  # noqa: F401  (the module's fixture)
from thermocomp.apps.deploy.export import exported_files, state_space
from thermocomp.apps.deploy.export.pack import conformance_pack


def _swapped_bits(header: str) -> str:
    """compensator.h with TC_FLAG_BITS' first (mon_excluded) and third (mon_out) swapped."""
    line = next(s for s in header.splitlines() if s.startswith("static const int TC_FLAG_BITS"))
    bits = line.split("{")[1].split("}")[0].split(", ")
    bits[0], bits[2] = bits[2], bits[0]
    return header.replace(line, line.split("{")[0] + "{" + ", ".join(bits) + "};")


@needs_cc
def test_the_pack_fails_a_build_whose_flags_are_wrong(served, tmp_path):  # noqa: F811
    deployed, healthy, other = served
    ss = state_space(deployed, monitor=True)
    files, summary = conformance_pack(deployed, ss, {"K05": healthy, "K06": _stepped(other, 3.0)})
    flags = files["check/K06/flags.csv"].splitlines()
    assert flags[0] == ("mon_excluded,mon_readmitted,mon_out,mon_band,mon_not_in_code,"
                        "mon_rereferenced,mon_new_state,excluded_inputs")
    assert flags[21] == "1,0,1,0,0,0,0,T_b"         # the jump's row: excluded and out
    assert len(flags) == files["check/K06/expected.csv"].count("\n")     # a row per row
    assert "--check-flags" in summary["command"] and "flags" in summary
    code = exported_files(deployed, "c")
    good = tmp_path / "good"
    built_stream(good, {**code, **files})
    script = subprocess.run(["sh", "check/check.sh"], cwd=good, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr
    assert "flag check passed: 40 rows' monitor flags as check/K06/flags.csv" in script.stderr
    # the same build with mon_excluded's and mon_out's bits swapped: the corrections are right...
    bad = tmp_path / "bad"
    built_stream(bad, {**code, **files, "compensator.h": _swapped_bits(code["compensator.h"])})
    with open(bad / "check" / "K06" / "rows.csv") as rows:
        alone = subprocess.run(["./stream", "--check", "check/K06/expected.csv"], cwd=bad,
                               stdin=rows, capture_output=True, text=True)
    assert alone.returncode == 0, alone.stderr
    # ...and the pack fails it, naming the row, the flag and both values
    script = subprocess.run(["sh", "check/check.sh"], cwd=bad, capture_output=True, text=True)
    assert script.returncode == 1
    # (the jump's row sets both bits; the row after it, out alone, is read as excluded)
    assert ("stream: flag check failed at input line 23 (row 22 of the stream): mon_excluded = 1, "
            "expected 0 (check/K06/flags.csv line 23)") in script.stderr


def test_a_pack_without_the_monitor_has_no_flags(served):  # noqa: F811
    deployed, healthy, _ = served
    files, summary = conformance_pack(deployed.streaming, state_space(deployed.streaming),
                                      {"K05": healthy})
    assert not [n for n in files if n.endswith("flags.csv")] and "flags" not in summary
    assert "--check-flags" not in files["check/check.sh"]
