"""The exported C with one, two or three sensors out at once (cmon92, issue 34): C against the served
model per row, and where they part, whether the C's monitor says so (a ``NOT_IN_CODE`` flag).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_cmon92.py trace ROOT RECORD CELLS [SIZES]
    python benchmarks/bench_cmon92.py fresh ROOT [RECORD ...]
    python benchmarks/bench_cmon92.py compiled ROOT RECORD CELL SENSORS KIND

``trace``: each cell of ``CELLS`` (comma-separated, e.g. ``mlr-none,arx-none``: a folder
``ROOT/reports/RECORD/CELL`` with its ``model.pkl``; ``ROOT/data/RECORD`` the record, as
bench_deploy89's ``sweep`` leaves them), deployed as ``export`` deploys it (bench_cmon91's
``deployed_cell``: fallbacks fitted at deploy build), its first test campaign streamed after its
lead-in through the served model and through the numpy mirror of the exported C
(:class:`Simulator`, the code's monitor in it) up to a quarter of the campaign; from there, per
case, copies of both states stepped over a copy of the next rows with a fault planted on every
sensor of a set of monitored sensors AT ONCE, from that row: ``spike`` (each read :data:`SPIKE_C`
high for :data:`SPIKE_ROWS` samples: bench_cmon91's spike) and ``freeze`` (each held at its reading
of the first planted row for :data:`FREEZE_ROWS` samples, then read again); each case :data:`AFTER`
rows past the fault's end. Sets: every single sensor, every pair, and the triples of
:func:`triples` (``SIZES``: the set sizes, default ``1,2,3``). Per (cell, size, kind) the cases
counted: ``same`` C = served on every row (the pack's tolerance: 1e-9 µm + 1e-9 x |served|);
``flagged`` they part and the code's monitor flagged ``NOT_IN_CODE`` at the first parting row or
before it in the case (the pack's cut names the rule); ``silent`` they part and nothing was flagged
before or at that row; ``fb`` cases where the served correction was a fallback's on some row;
``outs`` the most sensors the served monitor had out at once (max over the cases); after them the
rules first flagged not in the code in the cases that part, with their counts. Then each silent
case (cell, kind, sensors, first parting row, |C - served| there, the rows the served model was on
a fallback, the code's ``serving`` set there).

``fresh``: the same on fresh records (bench_cmon91's generators, seeds of :data:`FRESH`: lr / dl /
cr / lr / dl as cmon91 drew them; each simulated once under ``ROOT/data``, ``run`` of each family of
:data:`CELLS` once under ``ROOT/reports/RECORD/<family>-none``, bench_deploy88's settings: arx_rf
10 trees on ``S_spindle_rpm``), every cell traced as ``trace`` does (sizes 1, 2, 3).  Before the
faults, the healthy rows up to a quarter of the test campaign (the lead-in and the first quarter)
are checked C = served (the bench stops where they part).

``compiled``: one case of ``trace`` (``SENSORS`` joined by ``+``, ``KIND`` ``spike`` or ``freeze``)
through the compiled C (``gcc -std=c99 -Wall -Wextra -Werror -O2``, under ``ROOT/c``) fed the
whole stream (lead-in, the rows before the fault, the faulted rows): its corrections against the
mirror's on every row, the fault row where the mirror parts from served and where the mirror
flagged ``NOT_IN_CODE`` from the fault on, and ``stream.c``'s "not in the code" lines on stderr.

What the trace compares is the numpy mirror of the exported C (the pack's reference, whose
compiled C each check pack checks against it): per case a compiled C would be a build per case.

The contract asked (the brief): the C equals served, or it says that it does not (a
``NOT_IN_CODE`` flag: the check pack cuts there with the rule named, the machine's integration
sees the flag word); never a silent divergence.

The bar (written before any fresh record was simulated; seeds 9496-9500 never run before; the
contract, not a rule, is scored: the trace on the seen lr9212 found no silent case, below)::

1. Fresh 9496-9500, cells mlr, arx, lagbank, arx_rf (``-none``), sizes 1, 2 and 3, spike and
   freeze: ``silent`` = 0 in every row of the table (every case where the C parts from served is
   flagged ``NOT_IN_CODE`` at or before its first parting row), and the healthy rows before the
   faults C = served (the bench asserts it).
2. Single sensors (size 1): ``same`` = ``cases`` (the code holds one out of every kind planted,
   cmon83-cmon91, fallbacks included).
If 1 and 2 hold: TRACED-clean, the contract holds as main is (no rule: the code flags what it
does not hold; making it hold two or three sensors jumping at once is a rule of its own, below).
If a silent case appears: TRACED with the case named (the next rule: flag it, or hold it), src
as on main (no time for a rule scored on its own fresh seeds by the deadline).

Changed after the bar was committed (2be50572), measurement only: the table's last column (the
rule first flagged in the cases that part), added after the fresh tables were scored (re-run on
the same models: every count the same); and :data:`FRESH` written as bench_cmon91's generators
with the seeds put in (the dict as scored, checked equal), against a copy ``duplicates`` found.

Results (2026-12-05; src as main 2b918bfd, unchanged; 2 cores shared by 8 helpers).

Seen, lr9212 (bench_deploy89's cells, ``trace /tmp/.../seen lr9212
mlr-none,arx-none,lagbank-none,arx_rf-none``; 129.5 s CPU): fallbacks T_amb, T_spindle_front,
T_spindle_rear, T_motor, T_table, every one in the code (``fallback_set`` 1-5, also arx_rf's
forests: cmon91); 14 monitored, ``min_active`` 10; faults from test row 217 of R1b::

    cell        n kind    cases same flagged silent  the rule first flagged (cases that part)
    (all four)  1 spike     14   14     0      0
    (all four)  1 freeze    14   14     0      0
    mlr/lagbank 2 spike     91   12    79      0    several jumping in one sample 78, drift 1
    arx/arx_rf  2 spike     91   17    74      0    several jumping in one sample 73, drift 1
    (all four)  2 freeze    91   91     0      0
    (all four)  3 spike     50    0    50      0    several jumping in one sample 50
    mlr/lagbank 3 freeze    50   46     4      0    a second sensor out (here a third) 4
    arx/arx_rf  3 freeze    50   47     3      0    a second sensor out (here a third) 3

No silent case: where the C parts from served (520 cases of 1220, |C - served| at the first
parting row up to 19.4 µm, median 8.3) the code flagged ``NOT_IN_CODE`` at that row (spikes) or
one or two rows before it (a third freeze out at fault row 12, parting at 13-14).  Why they part: not
a fallback missing (every fallback is exported, and with two out both sides serve the first
out's fallback, the other read as the monitor rebuilds or holds it: freeze pairs 91 of 91 C =
served, ``outs`` 2) and not a refit on demand (served has no fallback for a set of sensors, only
one per sensor: ``fallback.sensor_fallbacks``); the served monitor's rules the code does not
hold: two or more sensors jumping in one sample that are no common step (served reads the
sample's instant faults together and takes them out: ``outs`` 3), a third sensor out (the code
holds two), and one drift with a sensor out.

The compiled C (``compiled``, lr9212, -Werror; 4.2-7.2 s CPU each): mlr T_head_left+T_head_right
spike, arx_rf T_amb+T_motor spike and freeze, arx_rf T_amb+T_spindle_front+T_col_back freeze:
compiled C = mirror to 8.5e-14 / 1.1e-13 µm on every row (3743-3793 rows), and (a driver
printing ``mon_flags`` per row, by hand under /tmp) its ``mon_flags`` equal the mirror's on every
row of those four and of arx_rf T_head_left+T_bed_left+T_zdrive spiked (``NOT_IN_CODE`` on 50 /
50 / 3 / 3 rows, first at fault row 12 / 12 / 1 / 1).  ``stream.c``'s stderr names the spikes'
rule at fault row 1 (``not in the code: several sensors jumping in one sample``), but not the
freeze pair's: at row 12 the flag word holds ``EXCLUDED | OUT | NOT_IN_CODE`` with ``mon_rule``
2 (T_amb's freeze exclusion, said), and from row 13 the not-in-code rule (9, a second sensor out)
is already flagged, so ``said_monitor`` (which says one rule per row, and a not-in-code rule only
as it sets in) never names it; there C = served on every row anyway (T_motor frozen = held).

A forest on another clock: unreachable from a deployed model's fallbacks, traced by reading and
on lr9212 / lr9496 arx_rf: a fallback's system ramps its forest over the time as read
(``switch_raw_time``) only where its stream has no clock (no lag period, no training grid);
an arx_rf keeps memory, so the model and every fallback refitted on the same record keep the
grid (60 s: clock on, ``switch_raw_time`` false, the adaptive model's false too), and the served
fallback steps on the adaptive model's clock in any case (``_step(x, t, clocked=True)``).  Were
one refused there, ``_holds`` leaves it out and the code flags ``FALLBACK`` (explicit).

Fresh 9496-9500 (``fresh /tmp/.../fresh``; 836.4 s CPU: 5 records simulated, 20 runs, 20 cells
traced): every fallback in the code (``fallback_set`` non-zero for all: 9 / 8 / 2 / 7 / 5 per
record); summed over the four cells::

    record  n  spike: cases same flagged silent   freeze: cases same flagged silent
    lr9496  1          56    56    0      0              56    56    0      0
    lr9496  2         364   150  214      0             364   356    8      0
    lr9496  3         496    88  408      0             496    88  408      0
    dl9497  1          56    56    0      0              56    56    0      0
    dl9497  2         364   138  226      0             364   230  134      0
    dl9497  3         384    26  358      0             384    60  324      0
    cr9498  1          48    48    0      0              48    48    0      0
    cr9498  2         264     0  264      0             264     0  264      0
    cr9498  3         160     0  160      0             160     0  160      0
    lr9499  1          56    56    0      0              56    56    0      0
    lr9499  2         364   194  170      0             364   356    8      0
    lr9499  3         300    80  220      0             300   236   64      0
    dl9500  1          56    56    0      0              56    56    0      0
    dl9500  2         364   150  214      0             364   360    4      0
    dl9500  3         200    32  168      0             200   132   68      0
    all               7064 cases: 3220 C = served, 3844 flagged, 0 silent

Per (record, size, kind) the families' ``same`` counts spread by 5 cases at most (mlr = lagbank and
arx = arx_rf in all 30).
The rule first flagged in the 3844 cases that part (``fresh`` again on the same models with the
last column, 788.0 s CPU, every count as scored): two or more sensors jumping in one sample (no
common step) 2740 (2382 of the 2402 spiked cases that part; and 358 frozen ones, cr9498 272,
dl9497 86: frozen sensors read again after 60 samples step in one sample), a second sensor
out (here the third, or a second where too few are left in: cr9498's, dl9497's) 1040, a drift
beyond the band with a sensor out 64.

By the bar: 1 (silent 0 in all 120 rows, the healthy rows C = served) and 2 (size 1: 544 of 544
C = served) hold: TRACED-clean.  The contract (C = served, or ``NOT_IN_CODE`` at or before the
first row they part) holds on main for one, two and three sensors spiked or frozen at once; no
src change (healthy packs, ``tc_step`` and compensator.c as main by construction).  The next
rule, by the counts: two sensors jumping in one sample (no common step) held in the code (out as
the first and second where the set of the two is solved, as served reads a sample's instant
faults together), scored by this bench's ``fresh`` on new seeds (C = served where it is held,
the rest still flagged).
"""

from __future__ import annotations

import copy
import itertools
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_audit86b import stage  # noqa: E402
from bench_cmon91 import FRESH as CMON91_FRESH  # noqa: E402
from bench_cmon91 import deployed_cell  # noqa: E402
from bench_deploy88 import FAMILIES, day_files, extra_of  # noqa: E402

# bench_cmon91's generators (lr / dl / cr / lr / dl) on the seeds given, chosen before any was simulated
FRESH = {f"{record[:2]}{seed}": [f"seed={seed}" if w.startswith("seed=") else w for w in words]
         for (record, words), seed in zip(CMON91_FRESH.items(), range(9496, 9501))}
CELLS = ("mlr", "arx", "lagbank", "arx_rf")

SPIKE_C, SPIKE_ROWS = 5.0, 10      # bench_cmon91's planted spike (lr9212's T_motor, +4.98 °C)
FREEZE_ROWS = 60                   # a freeze: longer than every blind_run (10) and seen_run
AFTER = 60                         # rows stepped past the fault's end: re-admission windows (10)
N_TRIPLES = 40                     # triples beyond those of the fallback sensors, drawn (seed 92)


def triples(names: list[str], falls: list[str]) -> list[tuple[str, ...]]:
    """Every triple of sensors with a fallback (``falls``), and :data:`N_TRIPLES` others drawn
    from all triples with a fixed seed (92) chosen before any was run."""
    own = list(itertools.combinations(falls, 3))
    rest = [c for c in itertools.combinations(names, 3) if c not in own]
    pick = np.random.default_rng(92).choice(len(rest), min(N_TRIPLES, len(rest)), replace=False)
    return own + [rest[k] for k in sorted(pick)]


def faulted_cell(root: Path, record: str, cell: str):
    """A cell as ``trace`` faults it (module doc): ``(deployed, state space, its first test
    campaign's frame after its lead-in, the lead-in's rows, the first faulted row, the campaign)``."""
    from thermocomp.apps.deploy.export import state_space
    from thermocomp.apps.deploy.export.pack import fed
    from thermocomp.apps.deploy.report import plain
    from thermocomp.shell.stages.export import lead_ins

    deployed, ds, _, test_ids = deployed_cell(root, record, root / "reports" / record / cell / "model.pkl")
    cid = test_ids[0]
    frame = fed(ds.campaigns[cid], lead_ins(plain(deployed).compensator, ds, [cid]).get(cid))
    lead = len(frame) - len(ds.campaigns[cid])
    return deployed, state_space(deployed, monitor=True), frame, lead, lead + (len(frame) - lead) // 4, cid


def fault_sets(deployed) -> dict[int, list[tuple[str, ...]]]:
    """The cases per set size (module doc): every single sensor, every pair, :func:`triples`."""
    names = list(deployed.monitor.names)
    return {1: [(s,) for s in names], 2: list(itertools.combinations(names, 2)),
            3: triples(names, list(deployed.fallbacks_))}


def planted(frame, start: int, sensors: tuple[str, ...], kind: str):
    """``frame``'s rows from ``start`` with ``sensors`` spiked or frozen at once (module doc)."""
    rows = SPIKE_ROWS if kind == "spike" else FREEZE_ROWS
    part = frame.iloc[start:start + rows + AFTER].copy()
    for s in sensors:
        col = part.columns.get_loc(s)
        if kind == "spike":
            part.iloc[:rows, col] += SPIKE_C
        else:
            part.iloc[:rows, col] = part.iloc[0, col]
    return part


class Stepped:
    """The served model and the code's arithmetic stepped together over a frame's rows."""

    def __init__(self, deployed, ss):
        from thermocomp.apps.deploy.export import Simulator

        self.served, self.sim, self.ss = deployed, Simulator(ss), ss
        self.sim.reset()
        deployed.reset()

    def rows(self, part):
        """Per row ``(C, served C, code's flags, rule missed, served fallback, served out count,
        code's serving set)`` of ``part``'s rows from the states they are in."""
        from thermocomp.apps.deploy.export.pack import corrections

        served, sim, ss = self.served, self.sim, self.ss
        X = part[served.columns_].to_numpy(float)
        U, t = part[ss.inputs].to_numpy(float), part["time"].to_numpy(float)
        mon = served.monitor
        for i in range(len(part)):
            read = X[i] if served._mon_all else X[i, served._mon]
            y = served._step(X[i], t[i])[0]
            fell = served._fallen_back(read)
            c = sim.step(U[i], t[i])
            w = sim.watch
            yield (c, corrections(ss, y[None, :])[0], w.flags, w.missed, fell,
                   int((~mon._active).sum()), sim.serving)


def trace_cell(root: Path, record: str, cell: str, sizes: list[int], out: list) -> None:
    """One cell's table rows (module doc) appended to ``out``; its silent cases printed."""
    from thermocomp.apps.deploy.export.pack import beyond
    from thermocomp.apps.deploy.export.watch import NOT_IN_CODE, REASONS

    deployed, ss, frame, lead, start, cid = faulted_cell(root, record, cell)
    names, falls = list(deployed.monitor.names), list(deployed.fallbacks_)
    base = Stepped(deployed, ss)
    for c, want, *_ in base.rows(frame.iloc[:start]):
        assert not beyond(c, want).any(), f"{cell}: C and served part before the faults"
    sets = fault_sets(deployed)
    print(f"{cell}: fallbacks {falls}, fallback_set "
          f"{[k for k, f in zip(ss.monitor['fallback_set'], ss.monitor['fallback']) if f]}, "
          f"{len(names)} monitored, min_active {ss.monitor['min_active']}; faults from test row "
          f"{start - lead + 1} of {cid}", flush=True)
    for size in sizes:
        for kind in ("spike", "freeze"):
            tally = {"same": 0, "flagged": 0, "silent": 0, "fb": 0, "outs": 0}
            why: dict = {}      # the first rule flagged not in the code, of the cases that part
            for sensors in sets[size]:
                run = copy.deepcopy(base)
                part = planted(frame, start, sensors, kind)
                first_flag = parted = None
                fb = False
                for i, (c, want, flags, missed, fell, outs, serving) in enumerate(run.rows(part)):
                    fb = fb or fell is not None
                    tally["outs"] = max(tally["outs"], outs)
                    if first_flag is None and flags & NOT_IN_CODE:
                        first_flag = (i, REASONS[missed].split(": ", 1)[-1][:44])
                    if parted is None and beyond(c, want).any():
                        parted = (i, float(np.max(np.abs(c - want))), fell, serving)
                tally["fb"] += fb
                if parted is None:
                    tally["same"] += 1
                elif first_flag is not None and first_flag[0] <= parted[0]:
                    tally["flagged"] += 1
                else:
                    tally["silent"] += 1
                    print(f"  SILENT {cell} {kind} {'+'.join(sensors)}: parts at fault row "
                          f"{parted[0] + 1} by {parted[1]:.3g} µm, served fallback {parted[2]}, "
                          f"code serving set {parted[3]}, first flag {first_flag}", flush=True)
                if parted is not None and first_flag is not None:
                    why[first_flag[1]] = why.get(first_flag[1], 0) + 1
            out.append((cell, size, kind, len(sets[size]), tally))
            print(f"{cell:<14}{size:>3}{kind:>8}{len(sets[size]):>6}" + "".join(
                f"{tally[k]:>9}" for k in tally) + "  " + ", ".join(
                f"{k} {n}" for k, n in sorted(why.items(), key=lambda kv: -kv[1])), flush=True)


def trace(root: str, record: str, cells: str, sizes: str = "1,2,3") -> None:
    """The ``trace`` table (module doc)."""
    out: list = []
    print(f"{'cell':<14}{'n':>3}{'kind':>8}{'cases':>6}" + "".join(
        f"{k:>9}" for k in ("same", "flagged", "silent", "fb", "outs")), flush=True)
    for cell in cells.split(","):
        trace_cell(Path(root).resolve(), record, cell, [int(s) for s in sizes.split(",")], out)


def compiled(root: str, record: str, cell: str, sensors: str, kind: str) -> None:
    """The ``compiled`` rows (module doc)."""
    import subprocess

    import pandas as pd

    from thermocomp.apps.deploy.export import exported_files
    from thermocomp.apps.deploy.export.pack import beyond
    from thermocomp.apps.deploy.export.watch import NOT_IN_CODE

    root = Path(root).resolve()
    deployed, ss, frame, _, start, _ = faulted_cell(root, record, cell)
    folder = root / "c" / record / cell
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in exported_files(deployed, "c").items():
        (folder / name).write_text(text)
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "compensator.c",
                    "stream.c", "-lm", "-o", "stream"], cwd=folder, check=True, capture_output=True)
    frame = pd.concat([frame.iloc[:start], planted(frame, start, tuple(sensors.split("+")), kind)])
    run = subprocess.run([str(folder / "stream")], capture_output=True, text=True, check=True,
                         input=frame[["time", *ss.inputs]].to_csv(index=False, float_format="%.17g"))
    got = pd.read_csv(pd.io.common.StringIO(run.stdout)).to_numpy(float)
    mirror, parted, flagged = [], None, None
    for i, (c, want, flags, *_) in enumerate(Stepped(deployed, ss).rows(frame)):
        mirror.append(c)
        if parted is None and beyond(c, want).any():
            parted = i - start + 1
        if flagged is None and flags & NOT_IN_CODE and i >= start:
            flagged = i - start + 1
    mirror = np.asarray(mirror)
    print(f"{cell} {kind} {sensors}: compiled C = mirror to {np.max(np.abs(got - mirror)):.2g} µm "
          f"over {len(frame)} rows; mirror parts from served at fault row {parted}, flagged at "
          f"{flagged}; stream.c's stderr on it:")
    print("\n".join(line for line in run.stderr.splitlines() if "not in the code" in line))


def made(root: Path, record: str, family: str, generators: dict | None = None) -> None:
    """``root/data/record`` simulated (its words in ``generators``, default :data:`FRESH`) and
    ``run model=family`` on it into ``root/reports/record/<family>-none``, each once."""
    data, out = root / "data" / record, root / "reports" / record / f"{family}-none"
    if not data.exists():
        rc, said = stage("simulate", *(generators or FRESH)[record], f"data.path={data}")
        assert rc == 0, said
        if record.startswith("dl"):
            day_files(data)
    if not (out / "model.pkl").exists():
        rc, said = stage("run", f"data.path={data}", f"out={out}", "plots=none", f"model={family}",
                         *FAMILIES[family], "track=false", *extra_of(record))
        assert rc == 0, said


def fresh(root: str, *chosen: str) -> None:
    """The ``fresh`` tables (module doc)."""
    root = Path(root).resolve()
    for record in [r for r in FRESH if r in chosen] or list(FRESH):
        for family in CELLS:
            made(root, record, family)
        print(f"== {record}", flush=True)
        trace(str(root), record, ",".join(f"{f}-none" for f in CELLS))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "fresh": fresh, "compiled": compiled}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
