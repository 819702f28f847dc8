"""A diagnosed state times the inputs' rises around an ATI model, to code (exportprod65).

The gantry of ``tests/shell/test_export_inputs_product62.py`` (a rail ``T_a`` and its top plate
``T_b`` whose rises reach the tool through where a saddle stands, ``S_y_pos``, a new place
every 5 samples; ten campaigns at initial ambients 14-33 °C, eight to train), here with
``ROWS`` rows per campaign (one every 120 s), gets per family and with / without the ambient
interaction the model ``diagnose ati=cmeans`` builds: ``AugmentedRegressor`` with the effect
``interaction:S_y_pos product(model inputs' rises) (absolute)`` around ``ATIRegressor(family,
n_intervals=2)``, fitted on the train campaigns, deployed as ``replay`` deploys it (the clamp on
every excursion).  The two test campaigns (15 and 32 °C) have every temperature shifted by
``SHIFT_C`` away from the train campaigns' ambients (7 and 40 °C: outside the trained range of
``A0``) and ``T_a`` pushed 30 K out from half-way (the clamp acting, its bound grown by the
position held at the sample before the first excess).

Printed per case: the largest |C - replay|, |ST - replay| (the tests' transpiler) and |numpy -
replay| (the JSON read back), µm, and the largest correction; ``compensator.c``'s size; the CPU
(user + sys) of the state space and the C and ST texts in this process; how much the effect
matters: the test MAE of ``E_X`` of the ATI model alone and of the diagnosed one on the shifted
campaigns not pushed, and the largest change of the corrections if the state's held value did
not grow the bound (``clamp_state_gain`` zeroed).  Then ``thermocomp export`` of one saved model
(lag bank, interaction) with its check pack, compiled with warnings as errors: its CPU (child's
user + sys) and the pack's verdict.  The bar, written before any figure: every emitter = replay
to 1e-9 µm (the pack's ``CHECK_UM``); a case that misses it stays refused.  Everything in a
scratch root.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_export_atiprod65.py [gantry61]

``gantry61``: instead, the gantry of ``benchmarks/bench_influx61.py`` (seed 6101, the lab's
InfluxDB files ``init``-ed as there), ``diagnose ati=cmeans diagnose.targets=[E_drift_Y]``, its
written config rerun, ``thermocomp export`` of that model.pkl as C with its pack, built with
warnings as errors and checked: a record nobody wrote for this, whose ATI model and effect
diagnose chose.

Measured (2026-12-01, 2 shared cores; 400 test rows, the whole bench 18.5 s CPU):

    family      inter.  |C-rep|  |ST-rep| |np-rep|  max|C| laws c KB gain moves  MAE ATI -> diag
    mlr         no      2.3e-13  2.3e-13  2.3e-13   887    2    24   927        34.937 -> 0.044
    mlr         yes     4.5e-13  4.5e-13  5.7e-13   887    4    25   926        38.008 -> 0.227
    pcr         no      2.3e-13  2.3e-13  2.3e-13   671    2    24   860        34.937 -> 7.306
    pcr         yes     6.8e-13  6.8e-13  5.7e-13   1281   4    24   677        36.767 -> 27.379
    arx         no      3.4e-13  3.4e-13  2.3e-13   887    2    24   927        35.044 -> 0.044
    arx         yes     5.7e-13  5.7e-13  5.7e-13   887    4    24   927        36.662 -> 0.106
    lagbank     no      6.8e-13  6.8e-13  4.5e-13   886    2    25   916        35.185 -> 0.054
    lagbank     yes     9.1e-13  9.1e-13  6.8e-13   890    4    26   911        35.122 -> 0.213
    hammerstein no      6.8e-13  6.8e-13  6.8e-13   887    2    25   917        13.726 -> 0.057
    hammerstein yes     1.0e-12  1.0e-12  6.8e-13   891    4    26   919        30.302 -> 0.452
    arx_rf      no      4.3e-13  4.3e-13  3.7e-13   228    2    24   outright   35.083 -> 0.044
    arx_rf      yes     4.3e-13  4.3e-13  4.0e-13   228    4    24   outright   37.223 -> 0.106
    lstm        no      4.0e-13  4.0e-13  4.0e-13   228    2    32   outright   34.952 -> 0.060
    lstm        yes     4.5e-13  4.5e-13  4.0e-13   228    4    37   outright   38.044 -> 0.247

(µm; gain moves: the largest change of the corrections with ``clamp_state_gain`` zeroed;
the state space and the C and ST texts 0.00-0.01 s CPU per case; the Hammerstein model
with the position's power entering, ``choose_exponents=False``; arx_rf and lstm have no step
gain: clamped outright, as streamed.)  Every case meets the bar.  ``thermocomp export`` of the
lag bank with the interaction: 1.70 s CPU with its pack, ``compensator.c`` 26 KB, the pack
passes on the strict build (2 x 200 rows, largest |difference| 8.5e-14 µm).

``gantry61`` (measured twice): diagnose ati=cmeans (4 train / 2 test campaigns; its ATI CV
fell back to one model: "2 training campaign(s) with 2 distinct ambient(s)") accepted the
position times the rises for E_drift_Y, test RMSE 8.69 -> 2.47 µm as deployed, 16.7 / 17.2 s
CPU; the old code's export refused it (exit 2, "... around an ATI model (diagnose ati=cmeans)
does not export"); now ``thermocomp export`` 7.98 / 7.34 s CPU with its pack,
``compensator.c`` 33 KB, the pack passes on the strict build (10,077 rows, largest |difference|
4.3e-14 µm).
"""

from __future__ import annotations

import json
import os
import resource
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "tests" / "shell"), str(REPO / "tests")]

from test_export import StructuredText, _compiled, _stdin, _streamed, checked_pack  # noqa: E402
from test_export_ati57 import CAMPAIGNS  # noqa: E402
from test_export_atiprod65 import FAMILIES, SHIFT_C  # noqa: E402
from test_export_inputs_product62 import PRODUCT, _diagnosed, _gantry  # noqa: E402
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space  # noqa: E402
from thermocomp.apps.deploy.export.statespace import StateSpace  # noqa: E402
from thermocomp.apps.deploy.streaming import replay  # noqa: E402
from thermocomp.core.models.ati import ATIRegressor  # noqa: E402
from thermocomp.shell.model_store import save_model  # noqa: E402

ROOT = Path(os.environ.get("BENCH_ROOT", "/tmp/exportprod65-bench"))
ROWS = 200
PY = str(REPO / ".venv" / "bin" / "python")


def shifted(tests):
    """Each test campaign's temperatures moved out of the train campaigns' ambients."""
    trained = [a0 for _, split, a0 in CAMPAIGNS if split == "train"]
    for df in tests:
        d = -SHIFT_C if df["T_amb"].iloc[0] < np.mean(trained) else SHIFT_C
        for c in ("T_a", "T_b", "T_amb"):
            df[c] += d
    return tests


def simulated(ss, stream, tests) -> np.ndarray:
    sim, rows = Simulator(ss), []
    for df in tests:
        sim.reset()
        rows += [sim.step(u, t) for u, t in zip(df[stream.columns_].to_numpy(float), df["time"])]
    return np.array(rows)


def case(data: Path, family: str, interaction: bool, folder: Path) -> dict:
    ati = ATIRegressor(FAMILIES[family](), n_intervals=2, ambient_interaction=interaction)
    stream, tests, comp = _diagnosed(data, [PRODUCT], ati)
    tests = shifted(tests)
    expected = np.vstack([-replay(stream, df)[stream.targets_].to_numpy(float) for df in tests])
    cpu = time.process_time()
    ss = state_space(stream)
    files = {**exported_files(stream, "c"), **exported_files(stream, "st")}
    cpu = time.process_time() - cpu
    folder.mkdir(parents=True)
    c = _streamed(_compiled(stream, folder), _stdin(stream, tests)).to_numpy(float)
    fb, st = StructuredText(files["compensator.st"]), []
    for df in tests:
        st += [fb(u, t, k == 0) for k, (u, t) in enumerate(zip(df[stream.columns_].to_numpy(float),
                                                                 df["time"]))]
    back = StateSpace.from_dict(json.loads(exported_files(stream, "json")["compensator.json"]))
    out = {"C": np.abs(c - expected).max(), "ST": np.abs(np.array(st) - expected).max(),
           "numpy": np.abs(simulated(back, stream, tests) - expected).max(),
           "max_corr": np.abs(expected).max(), "c_kb": len(files["compensator.c"]) / 1024,
           "cpu": cpu, "laws": len(ss.laws), "outright": bool(ss.clamp_outright)}
    if ss.clamp_states:
        still = state_space(stream)
        still.clamp_state_gain = np.zeros_like(ss.clamp_state_gain).tolist()
        out["state_gain_moves"] = np.abs(simulated(still, stream, tests) - expected).max()
    # the effect's worth: healthy shifted campaigns, the ATI model alone and diagnosed
    healthy = shifted(_diagnosed(data, [PRODUCT], ati, pushed_from=None)[1])
    alone = _diagnosed(data, [], ATIRegressor(FAMILIES[family](), n_intervals=2,
                                                ambient_interaction=interaction),
                       pushed_from=None)[0]
    for name, s in (("mae_ati", alone), ("mae_diag", stream)):
        out[name] = float(np.mean(np.concatenate([
            np.abs(replay(s, df)["E_X"].to_numpy(float) - df["E_X"].to_numpy(float))
            for df in healthy])))
    return out


def exported(data: Path, root: Path) -> None:
    """``thermocomp export`` of one saved model with its pack: CPU and the check."""
    _, _, comp = _diagnosed(data, [PRODUCT], ATIRegressor(FAMILIES["lagbank"](), n_intervals=2,
                                                          ambient_interaction=True))
    pkl = save_model(comp, root / "model.pkl")
    out = root / "code"
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([PY, "-m", "thermocomp", "export", f"data.path={data}", f"export.model={pkl}",
                    "export.format=c", f"out={out}", "track=false"], check=True,
                   capture_output=True, env={**os.environ, "PYTHONPATH": str(REPO / "src")})
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    said = checked_pack(out).strip().splitlines()
    print(f"thermocomp export (lagbank, interaction): {cpu:.2f} s CPU with its pack; "
          f"compensator.c {(out / 'compensator.c').stat().st_size / 1024:.0f} KB; "
          f"{'; '.join(said)}")


def thermocomp(*args: str) -> tuple[float, str]:
    """``thermocomp`` in a child: ``(its CPU s, user + sys; its stdout and stderr)``, exit 0
    asserted."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    run = subprocess.run([PY, "-m", "thermocomp", *args], capture_output=True, text=True,
                         env={**os.environ, "PYTHONPATH": str(REPO / "src")})
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    assert run.returncode == 0, run.stderr[-2000:]
    return ((after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime),
            run.stdout + run.stderr)


def gantry61(root: Path) -> None:
    """The gantry of ``bench_influx61`` (seed 6101, its InfluxDB files ``init``-ed), diagnosed
    with ``ati=cmeans`` for ``E_drift_Y``, rerun, exported as C with its pack, built strictly."""
    root.mkdir(parents=True, exist_ok=True)
    env = {**os.environ, "PYTHONPATH": str(REPO / "src")}
    for step in ("write", "init"):
        subprocess.run([PY, str(REPO / "benchmarks" / "bench_influx61.py"), step, str(root)],
                       check=True, capture_output=True, env=env)
    conf = [f"hydra.searchpath=[file://{root}/init-gantry/conf,"
            f"file://{root}/diag-ati/diagnosis/conf]", "data=gantry", "track=false"]
    cpu, said = thermocomp("diagnose", f"hydra.searchpath=[file://{root}/init-gantry/conf]",
                           "data=gantry", "ati=cmeans", "diagnose.targets=[E_drift_Y]",
                           "track=false", "plots=none", f"out={root}/diag-ati")
    print(f"diagnose ati=cmeans: {cpu:.1f} s CPU; " + "; ".join(
        ln.strip() for ln in said.splitlines() if ln.startswith("E_drift_Y") or "FallbackWarning" in ln))
    thermocomp("run", *conf, "experiment=diagnosed", f"data.path={root}/gantry",
               f"out={root}/diag-ati/diagnosed", "plots=none")
    out = root / "code"
    cpu, _ = thermocomp("export", *conf, f"data.path={root}/gantry",
                        f"export.model={root}/diag-ati/diagnosed/model.pkl", "export.format=c",
                        f"out={out}")
    banner = next(ln for ln in (out / "compensator.c").read_text().splitlines()
                  if "per target" in ln)
    said = checked_pack(out).strip().splitlines()
    print(f"thermocomp export: {cpu:.2f} s CPU with its pack; compensator.c "
          f"{(out / 'compensator.c').stat().st_size / 1024:.0f} KB;{banner.strip(' *')}; "
          f"{'; '.join(said)}")


def main() -> None:
    if sys.argv[1:] == ["gantry61"]:
        gantry61(ROOT / "gantry61")
        return
    # its own outputs only (review96: ROOT was removed whole, ``gantry61``'s folder with it)
    for own in [ROOT / "data", *(ROOT / f"{f}-{int(i)}" for f in FAMILIES for i in (False, True))]:
        shutil.rmtree(own, ignore_errors=True)
    data = _gantry(ROOT / "data", ROWS)
    print("family      interaction  |C-replay|  |ST-replay| |numpy-replay| max|C|  laws  "
          "c KB  CPU s  state gain moves  MAE ATI -> diagnosed")
    for family in FAMILIES:
        for interaction in (False, True):
            r = case(data, family, interaction, ROOT / f"{family}-{int(interaction)}")
            moves = (f"{r['state_gain_moves']:.3g}" if "state_gain_moves" in r
                     else "outright" if r["outright"] else "-")
            print(f"{family:<11} {str(interaction):<12} {r['C']:.2g}  {r['ST']:.2g}  "
                  f"{r['numpy']:.2g}  {r['max_corr']:.0f}  {r['laws']}  {r['c_kb']:.0f}  "
                  f"{r['cpu']:.2f}  {moves}  {r['mae_ati']:.3f} -> {r['mae_diag']:.3f}",
                  flush=True)
    exported(data, ROOT)


if __name__ == "__main__":
    main()
