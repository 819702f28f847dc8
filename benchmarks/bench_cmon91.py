"""The exported C serves an arx_rf model's fallback forests (cmon91, issue 34): deploy89's
lr9212/arx_rf cell, whose check pack was cut at R1b row 765.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_cmon91.py trace ROOT RECORD CELL [FIRST [LAST]]
    python benchmarks/bench_cmon91.py fresh ROOT LABEL [RECORD ...]
    python benchmarks/bench_cmon91.py timing ROWS FOLDER [FOLDER ...]

``trace``: a cell that ``python benchmarks/bench_deploy89.py sweep ROOT lr9212 arx_rf`` built
(``RECORD`` ``lr9212``, ``CELL`` ``arx_rf-none``), deployed as ``export`` deploys it (its
``model.pkl``, fallbacks fitted at deploy build), its test campaign streamed after its lead-in
through the served model and through the numpy mirror of the exported C (:class:`Simulator`,
its monitor in it): per row FIRST-LAST of the test campaign (default 760-772) the two
corrections, the law set the code serves and the rule it flags as not in the code; then the
first row where they part (none: C = served on every row).

``fresh``: per record of :data:`FRESH` (all where none is named; made once under ``ROOT``, the
``run`` of ``model=arx_rf`` too, bench_deploy88's settings: 10 trees on ``S_spindle_rpm``, so both
trees score the same fitted model), deployed as ``export`` deploys it, then the healthy test
campaigns and a copy of them with the sensors that have a fallback model (sensors no other predicts:
``deployed.fallbacks_``, the monitor's order) each read 5 °C high for 10 samples, one after another
:data:`GAP` rows apart from a quarter of the campaign on, as many as fit before three quarters of it
(a spike read as a jump: excluded, its fallback served, re-admitted: lr9212's T_motor): the C and
its check pack written under ``ROOT/LABEL/<record>/<case>`` (``gcc -std=c99 -Wall -Wextra -Werror
-O2``), ``check.sh`` run, and the compiled ``stream`` fed every row (lead-in first) against the
served corrections. Columns: ``fb`` the rows the served correction is a fallback's; ``rows`` test
rows; ``same`` the test rows where |C - served| <= the pack's tolerance; ``first`` the first row (of
the test campaign) where they part (``-``: none); ``cut`` the pack's first cut row of that campaign
(``-``: whole) and ``pack`` ``check.sh``'s exit; ``maxd`` max |C - served| (µm).

``timing``: ``tc_step``'s time per sample (ns, best of 5 passes over ``ROWS``, a pack's
``rows.csv``: lr9212's ``check/R1b/rows.csv`` as the branch writes it, the lead-in and the whole
test campaign; each pass from ``tc_init``) of each exported C folder named (``-O2``): main's
and the branch's export of the same cell, fed the same rows.

The rule (src of fix/cmon91 at 968d83cd): an arx_rf fallback's forest is merged into the
exported system (``fallbacks._merge_forests``: its states, features and trees appended, each
forest counting by its ARX's law of the fallback's set); the C walks a forest only while its
law's set is served (``forests(..., serving)``: the numpy mirror's ``_beside`` already gated
it), as the fallback's laws.  No new compensator.json key: a fallback's forest is held where
the monitor's ``fallback_set`` names its set (an export before this has 0 there and flags
``FALLBACK`` as it did); a model without forests exports the same system.

Trace (before the rule, 277a181d; lr9212, bench_deploy89's generator; 3457 lead-in rows):
rows 760-764 C = served (|d| <= 2e-14 µm); row 765 ``T_motor`` jumps +4.98 °C (the largest
training step 0.43 °C), no other sensor predicts it: served excludes it and serves its fallback,
the arx_rf refitted without T_motor (``fallbacks_``: T_amb, T_spindle_front, T_spindle_rear,
T_motor, T_table; ``fallback_set`` all 0: ``fallbacks._holds`` refused any forest).  The code's
monitor excludes it too and holds its last reading (serving 0, ``fell``: flagged
``FALLBACK``): C 1.37647 against served 2.10316 µm at 765 (0.28-0.73 µm on the next rows),
the pack cut there.  The served branch the C lacked: ``AdaptiveCompensator._step``'s
``y = falls[out]`` for an arx_rf fallback (its ARX laws and its forest on S_door's ramp).  With
the rule: ``fallback_set`` 1-5, rows 765-772 served by set 4 (T_motor's), |d| <= 3e-14 µm,
no parting row.

The bar (written before any fresh record was simulated; the fresh seeds 9376-9380 were never
run before)::

1. Seen, lr9212/arx_rf (none and ati, ``bench_deploy89.py sweep ROOT lr9212 arx_rf`` under the
   branch): ``C`` = ``replay`` = ``promo`` and ``Craw`` = ``cold`` to 7 digits, both pack
   entries whole (``cut`` 0) and ``check.sh`` exit 0.
2. Fresh 9376-9380 (:data:`FRESH`, bench_deploy89's generators; ``fresh``): on every healthy
   case and every planted case, ``same`` = ``rows`` (C = served on every row), no pack cut
   (``cut`` ``-``), ``check.sh`` exit 0, every build with -Werror.  Main's column beside it
   (the same fitted models) shows where main was cut.
3. Every other deploy89 cell unchanged: bench_deploy89's ``sweep`` under the branch on lr9212
   (all families and wrappers), and arx_rf / auto on dl9307, lr9306, cr9308: every column as
   bench_deploy89's table (C = replay to 7 digits).
4. ``tc_step`` time of lr9212/arx_rf's C, branch / main (the ratio reported; no bar: the code
   steps 5 fallback ARX laws more per sample, their forests walked only while served).
5. The export tests (tests/shell/test_export*.py, in parts, -n 2) pass.
KEPT when 1-3 and 5 hold and the new tests fail on 277a181d; else REFUSED (the rule's diff kept
as benchmarks/cmon91_rule.patch).

Changed after the bar was committed (288c3904), before any fresh record was simulated, both to
the measurement: ``run`` takes bench_deploy88's arx_rf settings (dev seed 4242 has no
``S_door``: the default state column refused); and one planted copy with every fallback
sensor spiked in turn (``GAP``) instead of one copy per sensor: on dev seed lr4242 (9 sensors
with a fallback) the ten copies took 4.7 CPU min for one record, the machine shared by 7
helpers (there C = served on all 864 rows of every copy, no cut, ``check.sh`` 0).

Results (2026-12-05; fix/cmon91's src at 968d83cd = as scored; main 277a181d, the same fitted
models; 2 cores shared by 7 helpers):

1. Seen, lr9212/arx_rf (``bench_deploy89.py sweep ROOT lr9212 arx_rf``), none and ati alike:
   main ``C`` 1.035993 / ``Craw`` 1.039593 against ``replay`` = ``promo`` 1.037863 / ``cold``
   1.041456, R1b and R1b.cold cut at 765 (99 of 864 rows unchecked); branch ``C`` = ``replay``
   = ``promo`` = 1.037863, ``Craw`` = ``cold`` = ``Pcold`` = 1.041456, ``cut`` 0, ``check.sh`` 0
   (every other column as main's).  ``trace`` above: no parting row.
2. Fresh (``fresh ROOT branch`` then ``fresh ROOT main`` with main's src, the same models; every
   build -Werror, every ``check.sh`` exit 0 in both trees)::

     record/case      campaign   fb   rows   branch: same first cut maxd   main: same first cut maxd
     lr9376/healthy   R1b         0    864   864  -   -   5.7e-14           864  -   -   5.7e-14
     lr9376/spikes    R1b        80    864   864  -   -   1.1e-13           804  257 257 5.15
     dl9377/healthy   R1b        12   1440   1440 -   -   9.9e-14           1440 -   -   3.6e-13
     dl9377/spikes    R1b       101   1440   1440 -   -   9.9e-14           1359 361 361 3.62
     cr9378/healthy   C10/11/12   0    213/224/236 all, none cut           all, none cut
     cr9378/spikes    C10        41    213   213  -   -   1.4e-14           172  54  54  1.77
     cr9378/spikes    C11        40    224   224  -   -   1.5e-14           184  57  57  2.01
     cr9378/spikes    C12        40    236   236  -   -   1.8e-14           196  60  60  2.49
     lr9379/healthy   R1b         0    864   864  -   -   5.0e-14           864  -   -   5.0e-14
     lr9379/spikes    R1b        80    864   864  -   -   5.0e-14           804  217 217 4.31
     dl9380/healthy   R1b         0   1440   1440 -   -   5.0e-14           1440 -   -   5.0e-14
     dl9380/spikes    R1b       121   1440   1440 -   -   6.4e-14           1340 361 361 3.50

   Branch: C = served on every row of all 16 campaign cases, no pack cut.  Main: every spiked
   copy cut at the first spike whose sensor's fallback served (the C held the reading, up to
   5.15 µm off).  dl9377 healthy: 12 rows served by a fallback in the test campaign and C =
   served on main too (3.6e-13 µm): that fallback's corrections equal the model's there (its
   ARX chose the same terms without the sensor).  CPU: branch 186.6 s, main 167.2 s (the five
   records, the fits shared).
3. Other deploy89 cells, ``bench_deploy89.py sweep ROOT dl9307 lr9306 cr9308 arx_rf`` under the
   branch (the cells whose system holds a forest: the only ones the rule can move; auto's
   candidates there hold none): every column of all six cells = bench_deploy89's table to the
   digits printed (lr9306 1.191719 / cold 1.18705; dl9307 replay = promo = C 0.8598465, cold =
   Craw = Pcold 0.8604102; cr9308 none 0.8595478, ati 0.7623871), packs whole, ``check.sh`` 0;
   CPU 213.9 s.  lr9212's other families (no forest: ``_holds`` and the C's walk unchanged for
   them, ``TC_N_FORESTS`` 0): ``bench_deploy89.py sweep ROOT
   lr9212 mlr pcr arx lagbank hammerstein lstm auto``: all 13 cells that run = bench_deploy89's
   table in every column (e.g. mlr replay = promo = C 0.9531205, lagbank cold = Craw = Pcold
   1.187391, auto-none 0.8100009 / 0.6924982), packs whole, ``check.sh`` 0; auto-ati exit 2 as
   designed; CPU 235.4 s.  So item 3 holds on the 21 cells run: lr9212's 15 and the
   arx_rf cells of dl9307, lr9306 and cr9308 (the other non-forest cells of dl9307 / lr9306 / cr9308 not
   re-run: nothing of them changed).
4. ``tc_step`` on lr9212/arx_rf-none's C (``timing``, the branch's R1b rows, 4321 rows, two
   runs each): main 1012 / 1003 ns, branch 1084 / 1115 ns per sample: x1.07-1.11 (five
   fallback ARX laws stepped per sample; their forests walked only while served);
   compensator.c 206 -> 362 KB.
5. The export tests (tests/*/test_export*.py, 51 files in three parts, -n 2): 116, 85 and 76
   passed (277, none failed), the new test file among them.

Verdict by the bar: 1, 2, 3 (as run), 5 hold and the three tests of
tests/shell/test_export_cmon91.py fail on 277a181d (3 failed) and pass on the branch: KEPT.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_audit86b import stage  # noqa: E402
from bench_deploy88 import FAMILIES, LONG, day_files, extra_of  # noqa: E402

FRESH = {      # bench_deploy89's generators, chosen before any was simulated
    "lr9376": [*LONG, "seed=9376", "sim.generator.duration_days=3.0"],
    "dl9377": [*LONG, "seed=9377", "sim.generator.duration_days=5.0"],
    "cr9378": ["sim=climate_room", "seed=9378", "sim.generator.n_runs=12",
               "sim.generator.duration_h=[3.0,4.0]", "sim.generator.test_fraction=0.25"],
    "lr9379": [*LONG, "seed=9379", "sim.generator.duration_days=3.0"],
    "dl9380": [*LONG, "seed=9380", "sim.generator.duration_days=5.0"],
}
SPIKE_C, SPIKE_ROWS = 5.0, 10      # the planted spike: lr9212's T_motor (+4.98 °C, re-admitted)
GAP = 40       # rows from one planted spike to the next: re-admitted (10 calm samples) between
CC = ["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-O2"]


def deployed_cell(root: Path, record: str, model: Path):
    """``(deployed, dataset, train ids, test ids)``: ``model`` deployed as ``export`` deploys it
    (its fallbacks fitted at deploy build) on ``root/data/record``."""
    from hydra import compose, initialize_config_dir

    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.model_store import load_model
    from thermocomp.shell.source import read_streamed

    with initialize_config_dir(config_dir=str(REPO / "conf"), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[f"data.path={root / 'data' / record}",
                                                       "track=false", *extra_of(record)])
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    deployed = deployable_model(cfg, ds, train_ids, str(model), "export.model",
                                load_model(model))[0]
    return deployed, ds, train_ids, test_ids


def streamed(deployed, ds, campaigns: dict) -> dict:
    """Per test campaign ``(fed frame, lead-in rows, served corrections as exported, rows the
    served correction is a fallback's)``."""
    from thermocomp.apps.deploy.export import state_space
    from thermocomp.apps.deploy.export.pack import corrections, fed
    from thermocomp.apps.deploy.report import plain, stream_rows
    from thermocomp.shell.stages.export import lead_ins

    ss = state_space(deployed, monitor=True)
    leads = lead_ins(plain(deployed).compensator, ds, list(campaigns))
    out = {}
    for cid, campaign in campaigns.items():
        frame = fed(campaign, leads.get(cid))
        fallen, own = [], deployed._fallen_back
        deployed._fallen_back = lambda read: fallen.append(own(read)) or fallen[-1]  # noqa: B023
        try:
            y = stream_rows(deployed, frame, cid).y
        finally:
            del deployed._fallen_back
        lead = len(frame) - len(campaign)
        out[cid] = (frame, lead, corrections(ss, y), sum(f is not None for f in fallen[lead:]))
    return out


def planted(campaigns: dict, sensors: list[str]) -> dict:
    """``campaigns`` with each of ``sensors`` in turn read :data:`SPIKE_C` high for
    :data:`SPIKE_ROWS` samples, :data:`GAP` rows apart from a quarter of each campaign on, as many
    as fit before three quarters of it."""
    out = {}
    for cid, frame in campaigns.items():
        frame = frame.copy()
        n = len(frame)
        for k, start in enumerate(range(n // 4, 3 * n // 4 - SPIKE_ROWS, GAP)[:len(sensors)]):
            frame.iloc[start:start + SPIKE_ROWS, frame.columns.get_loc(sensors[k])] += SPIKE_C
        out[cid] = frame
    return out


def case(folder: Path, deployed, ds, campaigns: dict) -> list[dict]:
    """The C and its check pack of ``campaigns`` in ``folder``, built, checked and fed (module
    doc's columns), per campaign."""
    from thermocomp.apps.deploy.export import exported_files, state_space
    from thermocomp.apps.deploy.export.pack import beyond, conformance_pack
    from thermocomp.apps.deploy.report import plain
    from thermocomp.shell.stages.export import lead_ins

    ss = state_space(deployed, monitor=True)
    files, summary = conformance_pack(deployed, ss, campaigns,
                                      lead_ins(plain(deployed).compensator, ds, list(campaigns)))
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in {**exported_files(deployed, "c"), **files}.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text)
    subprocess.run([*CC, "compensator.c", "stream.c", "-lm", "-o", "stream"], cwd=folder,
                   check=True, capture_output=True)
    pack = subprocess.run(["sh", "check/check.sh"], cwd=folder, capture_output=True, text=True)
    cuts = {e["campaign"]: e["cut"]["row"] - e["lead_in_rows"] for e in summary["campaigns"]
            if e["cut"] and "planted" not in e}
    rows = []
    for cid, (frame, lead, want, fb) in streamed(deployed, ds, campaigns).items():
        run = subprocess.run([str(folder / "stream")], capture_output=True, text=True, check=True,
                             input=frame[["time", *ss.inputs]].to_csv(index=False,
                                                                      float_format="%.17g"))
        got = pd.read_csv(pd.io.common.StringIO(run.stdout)).to_numpy(float)[lead:]
        parts = beyond(got, want[lead:]).any(axis=1)
        rows.append({"campaign": cid, "fb": fb, "rows": len(parts), "same": int((~parts).sum()),
                     "first": int(np.argmax(parts)) + 1 if parts.any() else "-",
                     "cut": cuts.get(cid, "-"), "pack": pack.returncode,
                     "maxd": float(np.max(np.abs(got - want[lead:])))})
    return rows


def made(root: Path, record: str) -> Path:
    """``root/reports/record/model.pkl``: the record simulated and ``run model=arx_rf`` on it,
    once (both trees then score the same fitted model)."""
    model = root / "reports" / record / "model.pkl"
    if model.exists():
        return model
    data = root / "data" / record
    rc, said = stage("simulate", *FRESH[record], f"data.path={data}")
    assert rc == 0, said
    if record.startswith("dl"):
        day_files(data)
    rc, said = stage("run", f"data.path={data}", f"out={model.parent}", "plots=none", "model=arx_rf",
                     *FAMILIES["arx_rf"], "track=false", *extra_of(record))
    assert rc == 0, said
    return model


def fresh(root: str, label: str, *chosen: str) -> None:
    """The ``fresh`` table (module doc)."""
    root = Path(root).resolve()
    print(f"{'record/case':<34}{'campaign':>10}{'fb':>6}{'rows':>7}{'same':>7}{'first':>7}"
          f"{'cut':>7}{'pack':>6}{'maxd':>11}", flush=True)
    for record in [r for r in FRESH if r in chosen] or list(FRESH):
        deployed, ds, _, test_ids = deployed_cell(root, record, made(root, record))
        healthy = {c: ds.campaigns[c] for c in test_ids}
        cases = {"healthy": healthy, "spikes": planted(healthy, list(deployed.fallbacks_))}
        for name, campaigns in cases.items():
            for r in case(root / label / record / name, deployed, ds, campaigns):
                print(f"{record + '/' + name:<34}{r['campaign']:>10}{r['fb']:>6}{r['rows']:>7}"
                      f"{r['same']:>7}{r['first']:>7}{r['cut']:>7}{r['pack']:>6}{r['maxd']:>11.3g}",
                      flush=True)


def trace(root: str, record: str, cell: str, first: str = "760", last: str = "772") -> None:
    """The ``trace`` rows (module doc)."""
    from thermocomp.apps.deploy.export import Simulator, state_space
    from thermocomp.apps.deploy.export.pack import beyond
    from thermocomp.apps.deploy.export.watch import NOT_IN_CODE, REASONS

    root = Path(root).resolve()
    deployed, ds, _, test_ids = deployed_cell(root, record, root / "reports" / record / cell / "model.pkl")
    ss = state_space(deployed, monitor=True)
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    print("fallbacks:", list(deployed.fallbacks_))
    print("fallback_set:", {s: k for s, k in zip(names, ss.monitor["fallback_set"])
                            if s in deployed.fallbacks_})
    cid = test_ids[0]
    frame, lead, want, fb = streamed(deployed, ds, {cid: ds.campaigns[cid]})[cid]
    print(f"{cid}: {lead} lead-in rows, {len(frame) - lead} rows, {fb} served by a fallback")
    sim = Simulator(ss)
    sim.reset()
    U, t = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
    parted = None
    for i in range(len(frame)):
        c = sim.step(U[i], t[i])
        row = i - lead + 1
        if parted is None and beyond(c, want[i]).any():
            parted = row
        if int(first) <= row <= int(last):
            w = sim.watch
            flag = REASONS[w.missed] if w.flags & NOT_IN_CODE else ""
            print(f"row {row}: C {np.round(c, 5)} served {np.round(want[i], 5)} "
                  f"|d| {np.max(np.abs(c - want[i])):.2g} serving {sim.serving} {flag[:70]}")
    print("first row where C and served part:", parted or "none")


DRIVER = r"""
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>
#include "compensator.h"
int main(int argc, char **argv) {
    static char line[1 << 16];
    static double rows[20000][TC_N_INPUTS + 1];
    int n = 0, pass, i, j;
    double best = 1e300, c[TC_N_OUTPUTS], sink = 0.0;
    FILE *f = fopen(argv[1], "r");
    tc_state s;
    fgets(line, sizeof line, f);
    while (n < 20000 && fgets(line, sizeof line, f)) {
        char *p = line;
        for (j = 0; j <= TC_N_INPUTS; j++) {
            char *end;
            rows[n][j] = (*p == ',' || *p == '\n') ? NAN : strtod(p, &end);
            if (*p != ',' && *p != '\n') p = end;
            if (*p == ',') p++;
        }
        n++;
    }
    for (pass = 0; pass < 5; pass++) {
        clock_t t0 = clock();
        tc_init(&s);
        for (i = 0; i < n; i++) { tc_step(&s, &rows[i][1], rows[i][0], c); sink += c[0]; }
        double ns = 1e9 * (double)(clock() - t0) / CLOCKS_PER_SEC / n;
        if (ns < best) best = ns;
    }
    printf("%d %.1f %g\n", n, best, sink);
    return 0;
}
"""


def timing(rows: str, *folders: str) -> None:
    """``tc_step``'s ns per sample of each exported C folder fed ``rows`` (module doc)."""
    rows = str(Path(rows).resolve())
    for folder in map(Path, folders):
        (folder / "timing.c").write_text(DRIVER)
        subprocess.run(["gcc", "-O2", "compensator.c", "timing.c", "-lm", "-o", "timing"], cwd=folder,
                       check=True, capture_output=True)
        out = subprocess.run(["./timing", rows], cwd=folder, capture_output=True,
                             text=True, check=True).stdout.split()
        print(f"{folder}: {out[0]} rows, tc_step {out[1]} ns per sample", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "fresh": fresh, "timing": timing}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
