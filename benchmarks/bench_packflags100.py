"""The conformance pack checks the C's printed monitor flags (issue 34; stop 100, packflags100).

Before (063630e6): ``stream --flags`` (cflags100) prints per row the code monitor's 7 flag kinds
and ``excluded_inputs``, but the pack an integrator runs on the target (``check/check.sh``:
``./stream --check <folder>/expected.csv``) compares the correction columns only: a build whose
corrections are right and whose flags are wrong (a bit of ``TC_FLAG_BITS`` swapped, a sensor
named wrong) passes it.

RULE (packflags100; export/pack.py ``FLAGS`` / ``FLAG_COLUMNS``, export/driver.py
``--check-flags``): where the code holds the sensor monitor (``ss.monitor``: ``TC_MONITOR 1``),
export writes beside each campaign's ``expected.csv`` a ``flags.csv``: per row of ``rows.csv``
the mirror's ``watch.flag_row`` (``Simulator.watch``, stepped in ``_parted`` as the pack checks the
corrections; a shared lead-in's rows once), under ``mon_<kind>`` x 7 and ``excluded_inputs``.
``./stream --check-flags FILE`` compares each row's flags as ``--flags`` prints them with FILE's
(exact): the first that differs is named on stderr (input line, row of the stream, the flag, both
values, FILE's line), exit 1; FILE's extra rows fail as ``--check`` does.  ``check.sh`` adds
``--check-flags`` to each campaign's line; check.json's ``flags`` says why.  Without the monitor
(``TC_MONITOR 0``) no flags.csv is written and check.sh is as before.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_packflags100.py pack ROOT RECORD BASE_SRC OUT   # P1, P2, P4 lines
    python benchmarks/bench_packflags100.py plain ROOT RECORD BASE_SRC OUT  # the P3 line
    python benchmarks/bench_packflags100.py write ROOT RECORD FOLDER MONITOR  # one pack (0/1)

``write``: RECORD's cell (bench_cflags100's ``_cell``: its healthy, drift and ambient frames, or
``fl``: fl_thermal's served MLR, its test campaign) exported as C with its conformance pack of
those frames as campaigns (``conformance_pack``: the planted copies it adds too) into FOLDER by
this python path's src (MONITOR 0: the model without its monitor, ``deployed.streaming``),
compiled (gcc -Werror), the pack's CPU and bytes printed.  ``pack``: ``write`` by this tree and
(a subprocess) by BASE_SRC into OUT/RECORD/{rule,base}; ``sh check/check.sh`` in each; then two
copies of the rule's build with a flag break planted in the C: ``swap`` (compensator.h's
``TC_FLAG_BITS`` of mon_excluded and mon_out swapped) and ``name`` (stream.c names the next
monitored sensor for each one out); for each, check.sh and the corrections-only check (every
campaign's ``./stream --check expected.csv``, check.sh's line without ``--check-flags``).
``plain``: the same with MONITOR 0, the rule's pack files against BASE's byte for byte.

Records (SEEN only, no fresh seed drawn): bench_cflags100's, ROOT a copy of its ROOT
(/tmp/cflags100/root): dl9878, dl9902 (healthy, drift, ambient), tr9876 (healthy, drift,
ambient) and ``fl`` (healthy).

BAR (written and committed before any bench measurement; BASE = 063630e6's src)
---
P1. dl9878, dl9902, tr9876, fl: the rule's pack passes (check.sh exit 0; every campaign's
    flags.csv rows = its expected.csv rows).
P2. dl9878 and dl9902: each planted break (``swap``, ``name``) fails the rule's check.sh (exit
    1) with a message naming the input line and the flag (``mon_excluded``/``mon_out`` for swap,
    ``excluded_inputs`` for name) and both values, while the corrections-only check passes (exit
    0 on every campaign).
P3. fl and dl9878 without the monitor (MONITOR 0): the rule's pack files (rows, expected,
    check.json, check.sh) byte-identical to BASE's, no flags.csv; check.sh exit 0.
P4. the cost said: pack CPU rule / BASE and the bytes of flags.csv against the pack's, on dl9878
    (no bound: measured and stated).
P5. a test (tests/shell/test_export_packflags100.py, < 5 s call) that fails on 063630e6 and passes
    here.
KEPT if P1-P3 and P5 hold and P4 is stated; else REFUSED (benchmarks/packflags100_rule.patch).

Scored (bar dff896bc, unchanged; the rule as committed there, test and docs after it;
2026-12-06 16:36-17:04 UTC under a load of 8-21 on 2 cores; BASE = ``git archive 063630e6 src``;
ROOT /tmp/packflags100/root, a copy of /tmp/cflags100/root).  Campaigns: the record's cases and
the planted copies the pack adds (jump, freeze, dropout, range, common step of the first case).
Wall of ``pack``: dl9878 718 s, dl9902 750 s, tr9876 817 s, fl 220 s; ``plain`` fl 85 s,
dl9878 89 s::

    record  campaigns  check.sh  corrections-only  swap: check.sh, first failure (input line)
    dl9878  8          exit 0    8 x exit 0        exit 1, mon_excluded = 1, expected 0 (3252)
    dl9902  7          exit 0    7 x exit 0        exit 1, mon_excluded = 1, expected 0 (992)
    tr9876  8          exit 0    8 x exit 0        exit 1, mon_excluded = 1, expected 0 (3346)
    fl      5          exit 0    5 x exit 0        exit 1, mon_excluded = 1, expected 0 (559)
    name: check.sh exit 1, excluded_inputs = printed vs expected (input line); corrections-only all 0:
    dl9878 'T_col_front_top' vs 'T_head_right' (3251); dl9902 'T_table' vs 'T_bed_right' (991);
    tr9876 'T_column' vs 'T_ram' (3345); fl 'T_t2' vs 'T_t1' (558)
    (every campaign's flags.csv rows = its expected.csv rows; BASE's check.sh exit 0 on each)

    P3 without the monitor: fl 4 pack files, dl9878 8: = BASE's bytes, no flags.csv, check.sh exit 0

    P4 pack CPU rule / BASE (s): dl9878 45.0 / 43.1, dl9902 36.6 / 36.5, tr9876 66.9 / 71.5,
       fl 3.7 / 4.6 (within the load's noise); bytes: flags.csv 954092 of 14813282 (6.4 %),
       861959 of 13009651 (6.6 %), 1377976 of 18050650 (7.6 %), 87344 of 2196050 (4.0 %).

P1 MET (4 records, 28 campaigns).  P2 MET (every break named with its row, flag and both values;
the corrections-only check exit 0 on every campaign; also on tr9876 and fl, outside P2's
records).  P3 MET.  P4 stated: +4.0-7.6 % bytes, CPU within noise.  P5 MET
(test_export_packflags100: 4.16 s call at load 0.9, 11.8 s under a load of 8; fails on
063630e6: KeyError 'check/K06/flags.csv').
VERDICT: KEPT.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_cflags100 import _cell  # noqa: E402

SWAP = ("mon_excluded", "mon_out")      # the two kinds whose TC_FLAG_BITS the swap break swaps
NAMED = "TC_INPUT_NAMES[TC_MONITORED[s->mon_out_set[k]]]"
MISNAMED = "TC_INPUT_NAMES[TC_MONITORED[(s->mon_out_set[k] + 1) % TC_N_MONITORED]]"


def _compile(folder: Path) -> None:
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "compensator.c",
                    "stream.c", "-lm", "-o", "stream"], cwd=folder, check=True, capture_output=True)


def write(root: str, record: str, folder: str, monitor: str) -> None:
    """RECORD's C and its pack into FOLDER (module doc), compiled; CPU and bytes printed."""
    from thermocomp.apps.deploy.export import exported_files, state_space
    from thermocomp.apps.deploy.export.pack import conformance_pack

    deployed, _ss, _names, _start, cases = _cell(root, record)
    if monitor == "0":
        deployed = deployed.streaming
    ss = state_space(deployed, monitor=monitor != "0")
    out = Path(folder)
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    for name, text in exported_files(deployed, "c").items():
        (out / name).write_text(text)
    started = time.process_time()
    files, _ = conformance_pack(deployed, ss, {case: frame.reset_index(drop=True)
                                               for case, (_, frame) in cases.items()})
    cpu = time.process_time() - started
    for name, text in files.items():
        (out / name).parent.mkdir(parents=True, exist_ok=True)
        (out / name).write_text(text)
    _compile(out)
    size = sum(len(t.encode()) for t in files.values())
    flags = sum(len(t.encode()) for n, t in files.items() if n.endswith("/flags.csv"))
    print(f"  {out.name}: pack CPU {cpu:.1f} s, {len(files)} files, {size} bytes "
          f"(flags.csv {flags} bytes, {100 * flags / size:.1f} %)", flush=True)


def _both(root: str, record: str, base_src: str, out: str, monitor: str) -> Path:
    folder = Path(out).resolve() / f"{record}-{monitor}"
    print(f"{record} (monitor {monitor}):", flush=True)
    write(root, record, str(folder / "rule"), monitor)
    env = {**os.environ, "PYTHONPATH": f"{Path(base_src).resolve()}{os.pathsep}{HERE}"}
    subprocess.run([sys.executable, __file__, "write", root, record, str(folder / "base"), monitor],
                   env=env, check=True)
    return folder


def _script(folder: Path) -> subprocess.CompletedProcess:
    return subprocess.run(["sh", "check/check.sh"], cwd=folder, capture_output=True, text=True)


def _said(run: subprocess.CompletedProcess) -> str:
    lines = [s for s in run.stderr.splitlines() if "check failed" in s or "check:" in s]
    return (lines[-1] if lines else run.stdout.strip())[:240]


def _corrections_only(folder: Path) -> list[int]:
    """Each campaign's ``./stream --check expected.csv`` exit (check.sh's lines, no flags)."""
    codes = []
    for line in (folder / "check" / "check.sh").read_text().splitlines():
        if line.startswith("./stream"):
            plain = line.split(" --check-flags ")[0] + " <" + line.split(" <", 1)[1]
            codes.append(subprocess.run(["sh", "-c", plain], cwd=folder,
                                        capture_output=True).returncode)
    return codes


def _broken(rule: Path, name: str) -> Path:
    """A copy of the rule's build with flag break ``name`` planted in its C (module doc)."""
    copy = rule.parent / name
    shutil.rmtree(copy, ignore_errors=True)
    shutil.copytree(rule, copy)
    if name == "swap":
        header = (copy / "compensator.h").read_text()
        line = next(s for s in header.splitlines() if s.startswith("static const int TC_FLAG_BITS"))
        names = next(s for s in header.splitlines() if "TC_FLAG_NAMES[" in s and "=" in s)
        kinds = [k.strip(' "') for k in names.split("{")[1].split("}")[0].split(",")]
        bits = [b.strip() for b in line.split("{")[1].split("}")[0].split(",")]
        a, b = (kinds.index(k) for k in SWAP)
        bits[a], bits[b] = bits[b], bits[a]
        swapped = line.split("{")[0] + "{" + ", ".join(bits) + "};"
        (copy / "compensator.h").write_text(header.replace(line, swapped))
    else:
        stream = (copy / "stream.c").read_text()
        assert NAMED in stream
        (copy / "stream.c").write_text(stream.replace(NAMED, MISNAMED))
    _compile(copy)
    return copy


def pack(root: str, record: str, base_src: str, out: str) -> None:
    """The P1, P2 and P4 lines of RECORD (module doc)."""
    folder = _both(root, record, base_src, out, "1")
    rule = folder / "rule"
    rows = {p.parent.name: p.read_text().count("\n") for p in (rule / "check").glob("*/expected.csv")}
    flagged = {p.parent.name: p.read_text().count("\n") for p in (rule / "check").glob("*/flags.csv")}
    ran = _script(rule)
    print(f"P1 {record}: check.sh exit {ran.returncode}; {len(rows)} campaigns, flags.csv rows = "
          f"expected.csv rows: {rows == flagged}; {_said(ran)}", flush=True)
    print(f"   BASE's check.sh exit {_script(folder / 'base').returncode}", flush=True)
    for name in ("swap", "name"):
        broken = _broken(rule, name)
        ran = _script(broken)
        print(f"P2 {record} {name}: check.sh exit {ran.returncode}: {_said(ran)}", flush=True)
        print(f"   corrections-only exits {_corrections_only(broken)}", flush=True)


def plain(root: str, record: str, base_src: str, out: str) -> None:
    """The P3 line of RECORD (module doc)."""
    folder = _both(root, record, base_src, out, "0")
    listed = lambda f: sorted(p.relative_to(f) for p in (f / "check").rglob("*") if p.is_file())  # noqa: E731
    rule, base = listed(folder / "rule"), listed(folder / "base")
    same = rule == base and all((folder / "rule" / p).read_bytes() == (folder / "base" / p).read_bytes()
                                for p in rule)
    print(f"P3 {record}: {len(rule)} pack files, = BASE's bytes: {same}; flags.csv: "
          f"{sum(p.name == 'flags.csv' for p in rule)}; check.sh exit "
          f"{_script(folder / 'rule').returncode}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"pack": pack, "plain": plain, "write": write}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
