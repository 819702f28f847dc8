"""The docs as a stranger reads them (stop 107, audit107b; issue 34): every shell command shown in
README.md and docs/ (install, own-data, cli, models, evaluation, sweeps, diagnose, monitoring,
to-the-machine, dvc, volumetric, simulation; not docs/measured/), run as written, in page order,
in a fresh clone of this tree at BASE, and what it prints or writes held to what the page says.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_audit107b.py list                 # every command and its verdict rule
    python benchmarks/bench_audit107b.py walk CLONE [ID ...]  # run them (or some; ID+: from it on)
    python benchmarks/bench_audit107b.py coverage             # each command a page shows -> its entry

``list``: :data:`COMMANDS`, one line each: id, page:line, run / skipped (and why), the command.
``coverage``: every command the pages show (each line of a ``bash`` block, each code span that
starts with a command) with the entry of :data:`COMMANDS` (or :data:`COVERS`) near it, else
"name" (a command named in prose: ``thermocomp export``) or "synopsis" (``<file>``, ``[...]``).
``walk``: CLONE a ``git clone`` of this tree (made where missing) whose ``.venv/bin`` holds
bench_audit97's shims (the shared venv's python on the clone's ``src``; nothing installed, the
venv reused: install.md's block is not run); each command of :data:`COMMANDS` run by ``bash -euo
pipefail`` in CLONE, the venv not activated, no PYTHONPATH of the caller; per command its exit,
CPU (user + sys of its children) and each check of what the page says (a regex on what it
printed, a file it writes, a key of a JSON it writes).  A placeholder the page leaves open
(``<file>``, ``<family>``, a seed) is filled and said; a seed only from 10141-10143.  The twin's
and the server's ports are moved off the written ones (other helpers share the machine).

BAR (written and committed BEFORE any command was run)
-----------------------------------------------------
B1. Every command the pages show as one to run is in :data:`COMMANDS` with its verdict: OK (exit
    0, or 2 where the page says it refuses, and every check of what the page says it prints or
    writes met), BREAK (a command that fails as written, or prints / writes not what the page
    says: an override, key, file or number stated as today's output that the code no longer
    has), or SKIPPED with the reason (a synopsis, a name in prose, marked long by its page).
B2. Every BREAK mended (the docs or the code, whichever is wrong; where the code was wrong a
    cheap test failing on BASE, in tests/test_docs*.py where one fits) and its command run again
    passing, or named as left with the reason.
Dated measurements ("measured 2026-12-01 ...") are not held to today's output.

Scored (2026-12-07, 12:02-12:20 UTC; ``walk`` of a fresh ``git clone`` checked out at a2b4c5d2, the
shared /work/main/.venv through the shims, nothing installed; 2 cores shared, load 8-15):
74 commands run, 74 OK, 0 BREAK; 27 SKIPPED (``list``: the test suite, installs, a browser's server,
what the pages mark long -- volumetric, fleet, Ray, Optuna, lstm / auto on fl_thermal, dvc's sweep --,
a vendor's server, a DVC remote, the team server, --ambient's model, a test's TOA5 file).  324 s CPU
(user 288.8 + sys 35.4, /usr/bin/time of the walk).  ``coverage``: of 369 commands shown, 213 by an
entry, 144 names in prose (``thermocomp export``), 12 synopses (``<file>``, ``[...]``).
Held and met, besides exit statuses: make run's table (every digit), fl_thermal E_ch5 3.0x, the
monitor table and its three figures, the door diagnosis table, "6242 rows in 2 campaigns",
``arx_bicc_large_mill`` 8.56 -> 2.00 / 21.30 -> 2.45 / 65.99 -> 2.61, evaluation.md's E_P95 (E_Z 39 ->
9.8 at 4 h, 2.4 -> 3.8 at 5 min), long_record's MLR 24.19 -> 0.75 (one-step 0.44, persistence 0.46),
the lstm refusal's one line (torch hidden by an import hook), the second promote's "no new version".
Dated, compared: own-data.md's 90/10 table (mlr, pcr, arx, lagbank, hammerstein) the same to its two
digits; init74's fs7481 (0.275 / 0.293 / 0.754) the same to three.  Every dotted key the pages set
exists (127, now tests/test_docs.py).  Two harness slips mended before this walk (not the docs'):
``sys.modules['torch'] = None`` broke SciPy, and a workbook of the lab's manifest has no error column.
"""

from __future__ import annotations

import json
import os
import re
import resource
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import _cli  # noqa: E402

TWIN_PORT, SERVE_PORT = 48417, 50217     # off 4840 / 5002 / 5001: other helpers share the machine
TC = ".venv/bin/thermocomp"
FL = "datasets/fl_thermal/spindle_test.csv"
K03 = "data/raw/yearround_spindle/K03.csv"
MAKE_RUN_TABLE = """\
E_X             0.72   0.26         4.91 ->   0.75      84.7%       0.75   0.58     0.63
E_Y             1.38   0.50        12.08 ->   1.42      88.2%       1.42   0.58     0.62
E_Z             5.46   2.60        30.61 ->   5.80      81.0%       5.80   1.08     1.12"""
MONITOR_TABLE = """\
E_X            2.125          0.749       8.14    True
E_Y            8.769          1.397       21.2    True
E_Z           41.545          5.819       57.2    True
events: 22, exclusions: 15 (30.6 per 100 h), first: T_motor2 (K03, 4.08 h)"""
DOOR_TABLE = """\
E_X                  0.75 ->   0.75        0.77 ->   0.77   none
E_Y                  6.25 ->   2.85        6.88 ->   3.78   signal:S_door first_order_lag(tau=3600s)
E_Z                  6.25 ->   1.02        6.54 ->   0.92   ambient_interval:- model inputs x \
(ambient_c0 - 20°C), signal:S_door first_order_lag(tau=7200s)"""
CURL = ("curl -s --retry 60 --retry-connrefused --retry-delay 5 http://127.0.0.1:{port}/invocations "
        "-H 'Content-Type: application/json' -d '{{\"dataframe_split\": {{\"columns\": [\"time\", "
        "\"T_bearing_f1\", \"T_bearing_f2\", \"T_bearing_f3\", \"T_nose\", \"T_bearing_r\", \"T_motor1\", "
        "\"T_motor2\", \"T_box1\", \"T_box2\", \"T_amb\"], \"data\": [[0, {row}]]}}, "
        "\"params\": {{\"session\": \"machine-7\", \"reset\": true}}}}'")


NO_TORCH = """import sys
class NoTorch:   # the import of torch fails as where the lstm extra is not installed
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] == "torch":
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
sys.meta_path.insert(0, NoTorch())
from thermocomp.shell.cli import main
sys.exit(main(["run", "model=lstm", "track=false", "plots=none", "out=/tmp/a107b_lstm"]))
"""


OF_DAY = """import numpy as np
rng = np.random.default_rng(10141)
t = np.r_[np.arange(70200, 86101, 300), np.arange(1800, 20101, 300)]
temp = 22 + np.cumsum(rng.normal(0, 0.05, len(t)))
air = 20 + np.cumsum(rng.normal(0, 0.02, len(t)))
err = 3.0 * (temp - temp[0]) + rng.normal(0, 0.2, len(t))
rows = ["t,T_spindle (°C),T_air (°C),E_X (µm)"] + [f"{a},{b:.3f},{c:.3f},{d:.3f}" for a, b, c, d in
                                                   zip(t, temp, air, err)]
open("of_day.csv", "w").write("\\n".join(rows) + "\\n")
"""


def served(model: str, row: str, name: str) -> str:
    """serve (in the background, port moved) then the page's request, then the server stopped."""
    return (f"{TC} serve {model} serve.port={SERVE_PORT} > /tmp/a107b_{name}.log 2>&1 & pid=$!\n"
            + CURL.format(port=SERVE_PORT, row=row) + "\nkill $pid; wait $pid || true")


# (id, page:line, command as run (None: skipped), checks or the skip's reason, note).
# Checks: "exit N" (default 0), "re <regex>" on stdout + stderr, "table" + lines that must be
# printed, "file <path>", "json <path> <dotted key>", "no <regex>".
COMMANDS: list[tuple] = [
    # ---- README.md
    ("readme-make-run", "README.md:15", "make run",
     ["table " + MAKE_RUN_TABLE, "re model=mlr  select=all  mode=simulation  dataset=yearround_spindle",
      "file reports/default/metrics.json", "file reports/default/model.pkl",
      "file reports/default/thermocomp.log", "file data/raw/yearround_spindle/campaigns.csv"], ""),
    ("readme-make-test", "README.md:19", None, "the test suite itself (the lead's CI)", ""),
    ("readme-help", "README.md:64", f"{TC} --help && {TC} run --help",
     ["re simulate", "re monitor", "re rows", "re calibrate"], "lists the stages; <stage> --help"),
    ("readme-fl", "README.md:76", f"{TC} run data=fl_thermal out=reports/fl_thermal plots=none",
     [r"re E_ch5\s.*->\s+3\.0\d", "no reports/fl_thermal/plots"], ""),
    ("readme-c", "README.md:107",
     f"{TC} export export.model=reports/default/model.pkl export.format=c out=code/\n"
     "cd code && cc compensator.c stream.c -lm -o stream && ./stream < ../data/raw/yearround_spindle/K03.csv"
     " > corrections.csv && head -3 corrections.csv", ["re (?m)^C_X,C_Y,C_Z", "file "
                                                                              "code/check/check.sh"], ""),
    ("readme-onnx", "README.md:163",
     f"{TC} export export.model=reports/default/model.pkl export.format=onnx out=onnx/",
     ["exit 2", "lines 1", "no onnx/"], "export.format=onnx is refused"),
    ("readme-rows", "README.md:103", f"{TC} rows {K03} | head -2",
     ["re (?m)^time,T_bearing_f1"], "<file>: K03 of the default dataset"),
    ("readme-twin", "README.md:119",
     f"{TC} twin 'twin.campaigns=[K03]' twin.speed=40 twin.port={TWIN_PORT} out=reports/twin &\n"
     f"{TC} connect connect.endpoint=opc.tcp://127.0.0.1:{TWIN_PORT} connect.model=reports/default/model.pkl"
     " out=reports/connect\nwait $!",
     [r"re E_Z: RMS \d\d\.\d+ -> \d\.\d+ µm compensated", "file reports/twin/twin.json",
      "file reports/connect/connect.json"], "port moved"),
    ("readme-serve", "README.md:129",
     served("serve.model=reports/default/model.pkl",
            "5.83, 5.72, 5.78, 5.66, 5.84, 6.23, 6.06, 5.69, 5.85, 7.49", "readme"),
     ['re "C_Z":'], "port moved; curl retries until the server answers"),
    ("readme-mkdocs", "README.md:153", ".venv/bin/mkdocs build --strict -q -d /tmp/a107b_site", [],
     "site moved to /tmp"),
    ("readme-mkdocs-serve", "README.md:168", None, "a server for a browser (the build above)", ""),
    ("readme-pip", "README.md:142", None, "installs (the venv is reused, not reinstalled)", ""),
    # ---- docs/install.md
    ("install-block", "docs/install.md:9", None, "what make install runs: the venv is reused", ""),
    ("install-find-links", "docs/install.md:20", ".venv/bin/python -m pip config get global.find-links",
     [], "where this machine keeps its CPU torch"),
    ("install-lstm-msg", "docs/install.md:52", ".venv/bin/python - <<'PY'\n" + NO_TORCH + "PY",
     ["exit 2", r"re thermocomp: error: model=lstm needs torch, an optional dependency: pip install -e "
      r"'\.\[lstm\]' \(or make install, which has all\)"], "torch refused by an import hook (it is "
                                                           "installed)"),
    ("install-core", "docs/install.md:28", None, "pip install -e .: an install (the venv is reused)", ""),
    ("install-freeze", "docs/install.md:71", None, "rewrites the lock (a maintainer's step)", ""),
    ("install-make-benchmark", "docs/install.md:3", None, "every bench: long", ""),
    # ---- docs/own-data.md
    ("own-lathe", "docs/own-data.md:11",
     f"{TC} simulate sim=swiss_lathe_door data.path=data/raw/lathe\n"
     ".venv/bin/python -m thermocomp.core.io.export data/raw/lathe data/raw/lab T_headstock=T0 "
     "T_guidebush=T1 "
     "\"E_X=delta L\" --delimiter \";\" --decimal \",\"", ["file data/raw/lab/campaigns.csv"], ""),
    ("own-myconf", "docs/own-data.md:28",
     f"{TC} run \"hydra.searchpath=[file://$PWD/myconf]\" data=lab data.path=data/raw/lab "
     "data.delimiter=\";\" "
     "data.decimal=\",\" out=reports/lab plots=none", ["re E_L"], "myconf/data/lab.yaml as the page writes "
                                                                  "it"),
    ("own-ingest", "docs/own-data.md:38",
     f"{TC} ingest \"data.columns={{T0:T_0,T1:T_1,delta L:E_L}}\" data.sample_period_s=60 "
     "data.delimiter=\";\" "
     "data.decimal=\",\" data.path=data/raw/lab", ["re 6242 rows in 2 campaigns"], ""),
    ("own-fl-roles", "docs/own-data.md:70",
     f"{TC} run data.path={FL} \"data.roles.error=['ch*']\" \"data.roles.state=['spindle*']\" "
     "data.test_fraction=0.1 out=reports/fl_thermal plots=none", [r"re E_ch5\s.*->\s+3\.0\d"], ""),
    ("own-init", "docs/own-data.md:144", f"{TC} init {FL} out=reports/fl_init",
     ["re next: thermocomp run", "file reports/fl_init/conf/data/spindle_test.yaml"], ""),
    ("own-init-xlsx", "docs/own-data.md:152",
     f".venv/bin/python -c \"import pandas as pd; pd.read_csv('{FL}').to_excel('lab.xlsx', index=False)\"\n"
     f"{TC} init lab.xlsx out=reports/xlsx_init",
     ["file reports/xlsx_init/conf/data/lab.yaml", "re next: thermocomp run"],
     "lab.xlsx: fl_thermal's CSV saved as a workbook by pandas"),
    *[(f"own-family-{m}", "docs/own-data.md:161",
       f"{TC} run data=fl_thermal model={m} track=false plots=none out=reports/fl_{m}", [f"fl90 {m}"],
       "<family> filled; the table is dated (stop 63/64): compared, not held") for m in
      ("mlr", "pcr", "arx", "lagbank", "hammerstein")],
    ("own-family-lstm", "docs/own-data.md:161", None, "lstm: 41 s CPU on the 90/10 cut by the page", ""),
    ("own-family-auto", "docs/own-data.md:161", None, "auto: 35 s CPU on the 90/10 cut by the page", ""),
    ("own-toa5", "docs/own-data.md:999", None, "therm10min_toa5.dat: a test's file, not shipped", ""),
    ("own-fs7481", "docs/own-data.md:1173",
     ".venv/bin/python benchmarks/bench_stranger74.py write data/st74 7481 > /dev/null\n"
     f"{TC} init data/st74/fs7481.txt out=reports/fs_init\n"
     f"{TC} run \"hydra.searchpath=[file://$PWD/reports/fs_init/conf]\" data=fs7481 model=mlr track=false "
     "plots=none out=reports/fs7481",
     [r"in reports/fs_init/conf/data/fs7481.yaml ambient:\s+- Halle\s+- Halle#2\s+- Hallenmitte\s",
      "in reports/fs_init/conf/data/fs7481.yaml max_gap_samples: 120", r"re (?m)^E_\w+\s"],
     "ROOT: data/st74, as the page's bench writes it; run's figures (dated, init74) compared"),
    # ---- docs/cli.md
    ("cli-bare", "docs/cli.md:181", f"{TC}", ["exit 2", "re simulate"], "alone: the list, exit 2"),
    ("cli-h", "docs/cli.md:181", f"{TC} -h && {TC} help", ["re simulate"], ""),
    ("cli-version", "docs/cli.md:184", f"{TC} --version && {TC} -V", [r"re \d+\.\d+"], ""),
    ("cli-q", "docs/cli.md:182", f"{TC} -q run track=false plots=none out=reports/q", ["no INFO"], ""),
    ("cli-nosuch", "docs/cli.md:187", f"{TC} run model=nosuch --cfg job", ["exit 2", "lines 1"], ""),
    ("cli-init-cfg", "docs/cli.md:188", f"{TC} init --cfg job {FL}", [r"re (?m)^data:"], "<file>: "
                                                                                         "fl_thermal"),
    ("cli-rows-cfg", "docs/cli.md:189", f"{TC} rows --cfg job {K03}", [r"re (?m)^data:"], "(and rows)"),
    ("cli-help-keys", "docs/cli.md:190", f"{TC} run --help keys model && {TC} monitor --help keys",
     ["re model.estimator", "re monitor.input"], "<command> run / monitor, <group> model"),
    ("cli-scope-rows", "docs/cli.md:807", f".venv/bin/python -m thermocomp.shell.scope_rows {K03} | head -2",
     ["re (?m)^time,T_bearing_f1"], "lab77's module, kept as an alias of thermocomp rows"),
    ("cli-rows-campaigns", "docs/cli.md:783",
     f"{TC} rows data/raw/yearround_spindle 'rows.campaigns=[K03,K06]' rows.errors=true > rows2.csv && "
     "head -1 rows2.csv && grep -c '^$' rows2.csv", [r"re (?m)^time,T_.*,E_X", r"re (?m)^1$"],
     "two campaigns: one blank line between them, errors kept"),
    ("cli-of-day", "docs/cli.md:321",
     ".venv/bin/python - <<'PY'\n" + OF_DAY + "PY\n"
     f"set +e; {TC} init of_day.csv out=reports/of_day; echo \"bare: exit $?\"; set -e\n"
     f"{TC} init of_day.csv data.time=of_day out=reports/of_day",
     ["re bare: exit 2", "re data.time=of_day", r"re time: 't', seconds of day \(since midnight, a day added "
      r"where it passes midnight, data.time=of_day\)", "in reports/of_day/conf/data/of_day.yaml of_day"],
     "<file>: of_day.csv (seed 10141), seconds of day, the logger paused over midnight (86100, then 1800)"),
    ("cli-simulate", "docs/cli.md:459", f"{TC} simulate seed=0 data.path=data/raw/seed0",
     ["file data/raw/seed0.truth.json", "file data/raw/seed0/campaigns.csv"], "data.path moved"),
    ("cli-replay", "docs/cli.md:546", f"{TC} replay replay.model=reports/default/model.pkl "
                                      "out=reports/replay",
     ["file reports/replay/replay.json"], ""),
    ("cli-monitor-model", "docs/cli.md:851",
     f"{TC} monitor monitor.model=reports/default/model.pkl out=reports/monitor_model",
     ["file reports/monitor_model/monitor.json", "file reports/monitor_model/monitor"], ""),
    ("cli-calibrate", "docs/cli.md:864", None, "a volumetric dataset: volumetric.md's, marked long", ""),
    ("cli-design", "docs/cli.md:872", None, "the 200-machine study: marked long (volumetric.md)", ""),
    ("cli-compare-model", "docs/cli.md:947", f"{TC} compare model=arx",
     ["exit 2", "re model: thermocomp compare does not read the model group \\(it composes data, sim, eval, "
      "compare\\)"], ""),
    ("cli-cfg-job", "docs/cli.md:949", f"{TC} monitor --cfg job", [r"re (?m)^monitor:"], "<command>: "
                                                                                         "monitor"),
    ("cli-sweep", "docs/cli.md:969", f"{TC} run -m model=mlr,pcr seed=1,2 plots=none",
     ["sweep 4", "re (?i)sweep"], "plots=none added (the table alone)"),
    ("cli-submitit", "docs/cli.md:982", f"{TC} run -m model=mlr,pcr hydra/launcher=submitit_local plots=none",
     ["sweep 2", "submitit"], "plots=none added"),
    ("cli-ray", "docs/cli.md:981", None, "a Ray instance: minutes (sweeps.md marks it)", ""),
    ("cli-optuna", "docs/cli.md:983", None, "20 Optuna trials: ~48 s wall by sweeps.md, marked long", ""),
    ("cli-optuna-arx", "docs/cli.md:984", None, "20 trials over ARX: as long", ""),
    ("cli-volumetric-sim", "docs/cli.md:1915", None, "volumetric.md: marked long", ""),
    ("cli-group-by", "docs/cli.md:2791", None, "the fleet: 8.64 M rows, 1 GB (sweeps.md)", ""),
    # ---- docs/models.md
    ("models-auto", "docs/models.md:132", f"{TC} run model=auto track=false plots=none out=reports/auto",
     ["json reports/auto/metrics.json targets"], "track=false plots=none added"),
    ("models-arx-bicc", "docs/models.md:309",
     f"{TC} simulate experiment=arx_bicc_large_mill && {TC} run experiment=arx_bicc_large_mill plots=none",
     [r"re E_X\s.*8\.56 ->\s+2\.00", r"re E_Y\s.*21\.30 ->\s+2\.45", r"re E_Z\s.*65\.99 ->\s+2\.61"],
     "the table's test RMS before -> after, undated"),
    ("models-experiment", "docs/models.md:303",
     f"{TC} simulate experiment=pcr_pearson_yearround && {TC} run experiment=pcr_pearson_yearround "
     "plots=none",
     [], "<name>: pcr_pearson_yearround (the cheapest row)"),
    # ---- docs/evaluation.md
    ("eval-ep95", "docs/evaluation.md:19", f"{TC} run track=false plots=none out=reports/ep95",
     ["ep95 reports/ep95/metrics.json"], "E_Z's E_P95 of the default MLR: 39 -> 9.8 at 4 h, 2.4 -> 3.8 at 5 "
                                         "min"),
    ("eval-evaluate", "docs/evaluation.md:3",
     f"{TC} ingest && {TC} train && {TC} evaluate",
     [*(f"json reports/default/metrics.json {k}" for k in ("anova", "mutual_prediction", "ati",
                                                           "targets.E_Z.test.iso10791_a3",
                                                           "targets.E_Z.test.e_p95")),
      "file reports/default/plots"],
     "the stages in turn: own-data.md's ingest of the lab left data/interim/default the lab's"),
    # ---- docs/sweeps.md
    ("sweeps-sweep", "docs/sweeps.md:4",
     f"{TC} run -m model=mlr,arx hydra/launcher=joblib plots=none\n"
     f"{TC} compare compare.sort_by=val_rsd_mean\n"
     f"{TC} promote data.path=data/raw/yearround_spindle\n"
     f"{TC} promote data.path=data/raw/yearround_spindle",
     ["re (?i)no new version|already"], ""),
    ("sweeps-sort-test", "docs/sweeps.md:29",
     f"{TC} compare compare.sort_by=test:rmse && {TC} compare compare.sort_by=rmse",
     [r"re (?i)test"], "a test column sorts when asked (the table says so)"),
    ("sweeps-serve", "docs/sweeps.md:254",
     served("", "4.06, 3.91, 3.99, 3.94, 4.06, 4.17, 4.12, 3.95, 4.07, 5.01", "sweeps"),
     ['re "C_Z":'], "the champion of the sweep above; port moved"),
    ("sweeps-lathe", "docs/sweeps.md:316",
     f"{TC} simulate sim=swiss_lathe_door\n{TC} replay model=arx_rf ati=cmeans "
     "data.path=data/raw/swiss_lathe_door",
     [], ""),
    ("sweeps-dvc-sweep", "docs/sweeps.md:27", None, "a DVC sweep of the study: long", ""),
    ("sweeps-ray-optuna", "docs/sweeps.md:342", None, "marked by the page: minutes", ""),
    ("sweeps-fleet", "docs/sweeps.md:356", None, "8.64 M rows, 1 GB", ""),
    ("sweeps-remote", "docs/sweeps.md:324", None, "a DVC remote of one's own (a synopsis)", ""),
    ("sweeps-team", "docs/sweeps.md:322", None, "needs the team server (CI's)", ""),
    # ---- docs/diagnose.md
    ("diag-door", "docs/diagnose.md:7",
     f"{TC} simulate \"sim.generator.effects=[door]\" data.path=data/raw/door\n"
     f"{TC} diagnose data.path=data/raw/door out=reports/door",
     ["table " + DOOR_TABLE, "file reports/door/diagnosis.json", "file "
                                                                 "reports/door/diagnosis/conf/experiment/diagnosed.yaml",
      "json reports/door/diagnosis.json rerun", "json reports/door/diagnosis.json cv.scheme"], ""),
    ("diag-rerun", "docs/diagnose.md:796",
     f"{TC} run \"hydra.searchpath=[file://$PWD/reports/door/diagnosis/conf]\" experiment=diagnosed "
     "data.path=data/raw/door plots=none", [], ""),
    ("diag-auto-refused", "docs/diagnose.md:801", f"{TC} diagnose model=auto out=reports/door_auto",
     ["exit 2", "lines 1"], "model=auto is refused (exit 2) before any search"),
    # ---- docs/monitoring.md
    ("mon-faulty", "docs/monitoring.md:33",
     f"{TC} simulate \"sim.generator.effects=[sensor_faults]\" "
     "sim.generator.effect_params.sensor_faults.kind=freeze "
     "sim.generator.effect_params.sensor_faults.column=T_motor2 data.path=data/raw/faulty_spindle\n"
     f"{TC} monitor data.path=data/raw/faulty_spindle out=reports/monitor",
     ["table " + MONITOR_TABLE, "file reports/monitor/monitor/self_prediction.png",
      "file reports/monitor/monitor/sensor_map.png", "file reports/monitor/monitor/compensation.png"], ""),
    ("mon-stdin", "docs/monitoring.md:74",
     f"{TC} monitor monitor.input=- data.path=data/raw/yearround_spindle out=reports/monitor_stdin "
     "< data/raw/faulty_spindle/K03.csv", [r"re first: T_motor2 \(stdin"], ""),
    # ---- docs/to-the-machine.md
    ("machine-arx-c", "docs/to-the-machine.md:338",
     f"{TC} run model=arx track=false plots=none out=reports/machine\n"
     f"{TC} export export.model=reports/machine/model.pkl data.path=data/raw/yearround_spindle "
     "export.format=c out=code/\n"
     "cd code && cc compensator.c stream.c -lm -o stream && ./stream < ../data/raw/yearround_spindle/K03.csv"
     " > corrections.csv && head -1 corrections.csv", ["re (?m)^C_X,C_Y,C_Z"], ""),
    ("machine-pack", "docs/to-the-machine.md:1045",
     "cd code && c=$(ls check | grep -v '\\.' | head -1) && ./stream --check check/$c/expected.csv "
     "< check/$c/rows.csv > /dev/null && sh check/check.sh", ["re (?i)largest"],
     "<campaign>: the pack's first"),
    ("machine-stream-flags", "docs/to-the-machine.md:673",
     "cd code && ./stream --flags < ../data/raw/yearround_spindle/K03.csv | head -1 && "
     "./stream --state state.txt < ../data/raw/yearround_spindle/K03.csv > /dev/null && test -s state.txt",
     ["re (?m)^C_X,C_Y,C_Z,.*mon_excluded.*excluded_inputs", "file code/state.txt"],
     "--flags (cli.md:595) and --state FILE (to-the-machine.md:823)"),
    ("machine-strict-cc", "docs/to-the-machine.md:287",
     "cd code && gcc -std=c99 -Wall -Wextra -Werror compensator.c stream.c -lm -o stream_c99 && "
     "cc -O2 -Wall -Werror compensator.c stream.c -lm -o stream_o2 && ./stream_c99 < ../" + K03 + " | head "
                                                                                                  "-1",
     ["re (?m)^C_X,C_Y,C_Z"], "the flags the pages build with (and to-the-machine.md:243's -O2)"),
    ("machine-ambient", "docs/to-the-machine.md:815", None,
     "--ambient C needs a model on a manifest's ambient_c reading no ambient sensor: none made here", ""),
    ("machine-st", "docs/to-the-machine.md:348",
     f"{TC} export export.model=models:/thermocomp-compensator@champion export.format=st out=plc/",
     ["file plc/compensator.st"], "the champion of sweeps.md's sweep (mlr or arx: linear)"),
    ("machine-rows", "docs/to-the-machine.md:956",
     f"{TC} rows {K03} > rows.csv && ./code/stream < rows.csv | head -2", ["re (?m)^C_X,C_Y,C_Z"],
     "<file>: K03 with the default data config"),
    ("machine-twin-bias", "docs/to-the-machine.md:1071",
     f"{TC} twin twin.speed=20 twin.port={TWIN_PORT} out=reports/twin &\n"
     f"{TC} connect connect.endpoint=opc.tcp://127.0.0.1:{TWIN_PORT} connect.model=reports/default/model.pkl "
     "adapt.method=bias out=reports/connect\nwait $!", ["re compensated"], "port moved"),
    ("machine-vendor", "docs/to-the-machine.md:1117", None, "a vendor's server at its own address (a "
                                                            "synopsis)",
     ""),
    # ---- docs/dvc.md
    ("dvc-repro", "docs/dvc.md:19", ".venv/bin/dvc repro && .venv/bin/dvc repro && .venv/bin/dvc metrics "
                                    "show",
     [], "marked by its page as 1.5 min of CI: run last, if the time allows"),
    ("dvc-force-ingest", "docs/dvc.md:31", ".venv/bin/dvc repro -s -f ingest && .venv/bin/dvc repro",
     [r"re Running stage 'ingest'"], ""),
    ("dvc-plots", "docs/evaluation.md:12", ".venv/bin/dvc plots show -o /tmp/a107b_plots",
     ["re (?i)file:///tmp/a107b_plots/index.html|index.html"], "output folder moved to /tmp"),
    ("dvc-grep", "docs/dvc.md:13", "grep -l '\\${' conf -r",
     ["re conf/common.yaml", "re conf/data/default.yaml", "re conf/diagnose/default.yaml",
      "re conf/ati/cmeans.yaml", "re conf/model/lstm.yaml"], "the files the page names"),
    # ---- docs/volumetric.md
    ("vol-block", "docs/volumetric.md:11", None, "marked by its page: ~2 min", ""),
    # ---- docs/simulation.md
    *[(f"sim-{s}", "docs/simulation.md:10", f"{TC} simulate sim={s}", ["file "
                                                                       f"data/raw/{s}/campaigns.csv"], "")
      for s in ("large_mill_week", "column_moving_source", "long_record", "climate_room")],
    ("sim-fleet", "docs/simulation.md:17", None, "8.64 M rows, 1 GB", ""),
    ("sim-volumetric", "docs/simulation.md:16", None, "volumetric.md: marked long", ""),
    ("sim-long-mlr", "docs/simulation.md:40", f"{TC} run sim=long_record model=mlr track=false plots=none "
     "out=reports/long", [r"re E_Z\s"], "<m>: mlr; the page's 0.75 µm (seed 0) compared"),
    ("sim-effects", "docs/simulation.md:117",
     f"{TC} simulate sim=column_moving_source \"sim.generator.effects=[door,lag_node]\" "
     "data.path=data/raw/eff",
     ["json data/raw/eff.truth.json undeclared_effects"], "<scenario>: column_moving_source"),
    ("sim-my-column", "docs/simulation.md:80",
     f"{TC} simulate \"hydra.searchpath=[file://$PWD/myconf]\" sim=my_column data.path=data/raw/my_column\n"
     f"{TC} diagnose \"hydra.searchpath=[file://$PWD/myconf]\" sim=my_column data.path=data/raw/my_column "
     "out=reports/my_column plots=none", ["file reports/my_column/diagnosis.json"],
     "myconf/sim/my_column.yaml as the page writes it"),
    # ---- last
    ("dvc-exp-run", "docs/dvc.md:9", ".venv/bin/dvc exp run -S "
                                     "conf/model/mlr.yaml:estimator.fit_intercept=false"
     " && .venv/bin/dvc exp show --no-pager | head -5", [r"re (?i)experiment"],
     "last: it applies fit_intercept=false to conf/ (the workspace), which every command after would read"),
]

SHARED = Path("/work/main/.venv/bin/python")
SHIMS = {"thermocomp": "-m thermocomp", "python": "", "mkdocs": "-m mkdocs", "dvc": "-m dvc",
         "mlflow": "-m mlflow"}
FILE_BLOCK = re.compile(r"<!--\s*readme-test:\s*file\s+(\S+)\s*-->\n```yaml\n(.*?)^```", re.S | re.M)


def clone_of(word: str) -> Path:
    """CLONE: a ``git clone`` of this tree, its ``.venv/bin`` shims (bench_audit97's), the install
    stamps newer than pyproject.toml (``make run`` then runs the two commands, installs nothing),
    and the files the pages write by a ``readme-test: file`` block (myconf/...)."""
    clone = Path(word).resolve()
    if not (clone / "src").exists():
        subprocess.run(["git", "clone", "-q", str(HERE.parent), str(clone)], check=True)
    bin_dir = clone / ".venv" / "bin"
    bin_dir.mkdir(parents=True, exist_ok=True)
    for name, how in SHIMS.items():
        shim = bin_dir / name
        shim.write_text(f'#!/bin/sh\nPYTHONPATH="{clone / "src"}" exec {SHARED} {how} "$@"\n')
        shim.chmod(0o755)
    for stamp in (".installed-core", ".installed"):
        (clone / ".venv" / stamp).touch()
    for page in [clone / "README.md", *sorted((clone / "docs").glob("*.md"))]:
        for path, body in FILE_BLOCK.findall(page.read_text()):
            (clone / path).parent.mkdir(parents=True, exist_ok=True)
            (clone / path).write_text(body)
    return clone


def _env() -> dict:
    """A new user's shell: no venv on PATH, no project variables, no PYTHONPATH."""
    drop = ("THERMOCOMP_", "MLFLOW_", "VIRTUAL_ENV", "PYTEST", "DVC_", "PYTHONPATH",
            "PYTHONDONTWRITEBYTECODE")
    env = {k: v for k, v in os.environ.items() if not k.startswith(drop)}
    env["PATH"] = os.pathsep.join(p for p in env["PATH"].split(os.pathsep) if ".venv" not in p)
    return env


def _dig(data, key: str):
    for part in key.split("."):
        data = data[part]
    return data


def _fl90(clone: Path, family: str) -> str:
    """own-data.md's 90/10 RMSE mean / MAE mean of ``family`` against this run's (dated: said)."""
    page = (clone / "docs" / "own-data.md").read_text()
    row = re.search(rf"^\| `{family}` \|[^|]*\|[^|]*\|[^|]*\| ([\d.]+) \| ([\d.]+) \|", page, re.M)
    targets = json.loads((clone / f"reports/fl_{family}/metrics.json").read_text())["targets"]
    rmse = sum(t["test"]["rmse"] for t in targets.values()) / len(targets)
    mae = sum(t["test"]["mae"] for t in targets.values()) / len(targets)
    return f"page 90/10 RMSE/MAE mean {row[1]} / {row[2]}, today {rmse:.2f} / {mae:.2f}"


def _sweep(clone: Path) -> Path:
    folders = sorted((p for p in (clone / "reports" / "multirun").glob("*") if p.is_dir()),
                     key=lambda p: p.stat().st_mtime)
    return folders[-1]


def check(clone: Path, rule: str, done: subprocess.CompletedProcess) -> tuple[bool, str]:
    """One check of a command (COMMANDS' comment): (met, what was found)."""
    said = done.stdout + done.stderr
    word, _, arg = rule.partition(" ")
    if word == "exit":
        return done.returncode == int(arg), f"exit {done.returncode}"
    if word == "re":
        return bool(re.search(arg, said)), f"/{arg[:50]}/"
    if word == "no" and "/" in arg:
        return not (clone / arg).exists(), f"no {arg}"
    if word == "no":
        return not re.search(arg, said), f"no /{arg}/"
    if word == "table":
        printed = {" ".join(ln.split()) for ln in said.splitlines()}
        missing = [ln for ln in arg.splitlines() if " ".join(ln.split()) not in printed]
        return not missing, f"table, missing {missing}" if missing else "table"
    if word == "file":
        return (clone / arg).exists(), f"file {arg}"
    if word == "json":
        path, key = arg.split()
        try:
            _dig(json.loads((clone / path).read_text()), key)
            return True, f"{path}:{key}"
        except (OSError, KeyError, TypeError, ValueError) as exc:
            return False, f"{path}:{key} ({type(exc).__name__} {exc})"
    if word == "in":
        path, _, regex = arg.partition(" ")
        return bool(re.search(regex, (clone / path).read_text())), f"{path}: /{regex[:40]}/"
    if word == "ep95":
        e = json.loads((clone / arg).read_text())["targets"]["E_Z"]["test"]["e_p95"]
        got = dict(zip(e["window_s"], zip(e["before"], e["after"])))
        said = {14400.0: (39, 9.8), 300.0: (2.4, 3.8)}   # evaluation.md, to the digits it gives
        found = {w: (round(got[w][0], 1 if b % 1 else 0), round(got[w][1], 1)) for w, (b, _) in said.items()}
        return found == said, f"E_P95 E_Z 4 h / 5 min: page {said}, today {found}"
    if word == "lines":
        lines = [ln for ln in done.stderr.splitlines() if ln.strip()]
        return len(lines) == int(arg), f"{len(lines)} stderr lines"
    if word == "fl90":
        return True, _fl90(clone, arg)
    if word == "sweep":
        jobs = [p for p in _sweep(clone).iterdir() if (p / "metrics.json").exists()]
        return len(jobs) == int(arg), f"{len(jobs)} jobs in {_sweep(clone).name}"
    if word == "submitit":
        return (_sweep(clone) / ".submitit").exists(), "<sweep dir>/.submitit/"
    raise ValueError(rule)


def _checked(clone: Path, rule: str, done: subprocess.CompletedProcess) -> tuple[bool, str]:
    try:
        return check(clone, rule, done)
    except Exception as exc:    # a check that cannot be made is not met
        return False, f"{rule[:40]}: {type(exc).__name__} {exc}"


def _cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def list_commands() -> None:
    """``list`` (module doc)."""
    for ident, where, line, checks, note in COMMANDS:
        what = "run" if line else f"SKIPPED: {checks}"
        print(f"{ident:22} {where:26} {what}" + (f" ({note})" if note else ""))
        if line:
            print("    $ " + line.replace("\n", "\n    $ "))


# commands a page shows elsewhere that an entry of COMMANDS runs as well (its id: page:line, ...)
COVERS = {
    "readme-c": ["docs/monitoring.md:365", "docs/cli.md:577"],
    "readme-fl": ["docs/cli.md:1177"],
    "own-fs7481": ["docs/cli.md:227"],
    "diag-rerun": ["docs/cli.md:2260"],
    "cli-sweep": ["docs/dvc.md:5"],
    "mon-stdin": ["docs/own-data.md:91"],
    "machine-pack": ["docs/cli.md:759", "docs/cli.md:765", "docs/to-the-machine.md:1033"],
    "machine-stream-flags": ["docs/cli.md:595", "docs/cli.md:758", "docs/to-the-machine.md:823",
                             "docs/to-the-machine.md:1030", "docs/to-the-machine.md:1295"],
    "machine-rows": ["docs/to-the-machine.md:960", "docs/to-the-machine.md:966", "docs/own-data.md:1464"],
    "machine-arx-c": ["docs/to-the-machine.md:1025"],
    "dvc-exp-run": ["docs/cli.md:2146", "docs/dvc.md:27"],
    "dvc-plots": ["docs/install.md:37", "docs/cli.md:2760"],
    "machine-strict-cc": ["docs/to-the-machine.md:243", *(f"docs/own-data.md:{n}" for n in
                                                          (397, 399, 452, 1220, 1272, 1333, 1397))],
}
PAGES = ["README.md", *(f"docs/{p}.md" for p in (
    "install", "own-data", "cli", "models", "evaluation", "sweeps", "diagnose", "monitoring",
    "to-the-machine", "dvc", "volumetric", "simulation"))]
SHOWN = re.compile(r"`((?:thermocomp|\.venv/bin/\w+|make|dvc|python3?|pip|curl|cc|gcc|\./stream|mkdocs|grep)"
                   r"(?:[ \t][^`\n]*)?)`")
NAME = re.compile(r"^(?:\.venv/bin/)?\w+(?: -\w)?(?: "
                  r"[a-z][\w-]*)?$")   # `thermocomp run`, `make test`, `dvc repro`


def shown() -> list[tuple[str, int, str]]:
    """Every command a page shows: each line of a ``bash`` block, each inline code span that
    starts with a command (page, line, text)."""
    found = []
    for page in PAGES:
        text = (HERE.parent / page).read_text()
        for m in re.finditer(r"^```bash\n(.*?)^```", text, re.S | re.M):
            first = text[:m.start()].count("\n") + 2
            found += [(page, first, ln) for ln in m[1].splitlines() if ln.strip()]   # the block's line
        prose = re.sub(r"^```.*?^```", lambda b: "\n" * b[0].count("\n"), text, flags=re.S | re.M)
        found += [(page, prose[:m.start()].count("\n") + 1, m[1]) for m in SHOWN.finditer(prose)]
    return found


def coverage() -> None:
    """``coverage``: each command a page shows (:func:`shown`) with the entry of :data:`COMMANDS`
    within 3 lines of it on its page, or "name": a command named in prose, no entry."""
    entries = [(w.split(":")[0], int(w.split(":")[1]), ident) for ident, w, *_ in COMMANDS]
    entries += [(w.split(":")[0], int(w.split(":")[1]), ident) for ident, ws in COVERS.items() for w in ws]
    for page, line, text in shown():
        near = [ident for p, n, ident in entries if p == page and abs(n - line) <= 3]
        kind = (", ".join(near) if near else "name" if NAME.match(text.strip())
                else "synopsis" if re.search(r"[<\[…]|\.\.\.", text) else "NOT LISTED")
        print(f"{page}:{line}: {text[:90]}  -> {kind}")


def walk(word: str, *ids: str) -> None:
    """``walk`` (module doc)."""
    clone = clone_of(word)
    start_at = next((i[:-1] for i in ids if i.endswith("+")), None)   # ID+: from it on
    for ident, where, line, checks, note in COMMANDS:
        start_at = None if start_at == ident else start_at
        if line is None or start_at or (ids and not start_at and ident not in ids and not
                                        any(i.endswith("+") for i in ids)):
            continue
        start, cpu = time.monotonic(), _cpu()
        done = subprocess.run(["nice", "bash", "-euo", "pipefail", "-c", line], cwd=clone, env=_env(),
                              capture_output=True, text=True, timeout=3600)
        (clone / ".a107b").mkdir(exist_ok=True)
        (clone / ".a107b" / f"{ident}.log").write_text(f"$ {line}\n{done.stdout}\n--- stderr\n{done.stderr}")
        rules = checks if any(c.startswith("exit") for c in checks) else ["exit 0", *checks]
        found = [_checked(clone, rule, done) for rule in rules]
        verdict = "OK" if all(met for met, _ in found) else "BREAK?"
        print(f"{ident:22} {where:26} {verdict:6} exit {done.returncode} {_cpu() - cpu:6.1f} s CPU "
              f"{time.monotonic() - start:6.1f} s wall; "
              + "; ".join(f"{'ok' if met else 'NOT'} {what}" for met, what in found), flush=True)
        if verdict != "OK":
            tail = (done.stdout + done.stderr).strip().splitlines()[-4:]
            print("".join(f"    | {t[:200]}\n" for t in tail), end="", flush=True)


def main(argv: list[str]) -> int:
    return _cli.run_commands(__doc__, {"list": list_commands, "walk": walk, "coverage": coverage}, argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
