"""Faults injected into the deployed compensator's input stream, every deployed form side by side
(prints numbers; no assertions).

A record nobody tuned on: ``yearround_spindle`` seed 5353, 9 campaigns of 3-5 h (K03, K06, K09
held out, 5-min samples), each model fitted by ``thermocomp run`` and made deployable as
``replay`` makes it.  Test campaign K06 (47 rows), from its middle row (23) on ``T_motor2``, the
sensor the models lean on: one empty cell (``nan_1``), 16 (``nan_16``), to the end
(``nan_end``), its first cell (``nan_first``); stuck at its value; a one-sample +50 °C spike; the
reading in K (+273.15) from the middle or throughout; (code71) a DAQ's overload mark +9.9E+37
for one sample (``ovld_1``) or to the end (``ovld_end``, an open thermocouple); the time +3 h from the middle
(``gap3h``); a duplicated row, a duplicated time, two rows swapped; the first time blank; and
(session 54) ``T_amb``'s column +5 K from the middle row on (``amb_offset5``: the column alone,
the machine unchanged: a sensor's offset, which session 54 first took for a real step of the air).
Then (session 54, ``ambient_cases``) the air itself stepped in the simulation (+5 K, +2 K, +5 K
over 30 min; ``SteppedAmbient``, every other campaign identical) against ``T_amb``'s column
offset (+5, +2 K), scored against the measured errors, and whether a model of the structure
following the air (``air_evidence``) tells them apart.
Forms: ``adaptive`` (the served model, ``replay``, ``monitor``: sensor monitor + guard),
``plain`` (the streaming compensator alone, ``monitor.adaptive=false``), ``code`` (the exported
arithmetic: numpy Simulator; the compiled C's ``tc_step`` and the ST block equal it to 1e-13 µm on
every fault, ``tests/shell/test_export_dropout53.py`` and the export tests prove them).  Per form:
the largest |correction| (µm), the largest change from the healthy stream, the change at the
campaign's last row, or what it did.

Run: ``PYTHONPATH=src .venv/bin/python benchmarks/bench_deploy_faults.py [--root /tmp/df53]``
(10 s of CPU with the fits made, 18 s with them).  Measured 2026-11-30 (session 54): max|C| over
E_X/E_Y/E_Z / the largest change from the same form's healthy stream / the change at the last
row (µm; a repeated row's output left out, swapped rows' swapped back); ``refused (n)``: the
plain stream refuses data row n (``replay`` exit 2 naming file, column and row); ``code`` is the
arithmetic exported from the adaptive deployable (its guard included, no sensor monitor);
``before ->`` the clamp's bound of each sample (session 53), the one line that changed::

  fault             model      adaptive             plain                  code
  healthy           mlr/arx/lb 27.5/25.4/24.2 µm max|C| in every form, no change
  nan_1             mlr        27.5 / 4.2 / 0.0     refused (24)           27.5 / 2.7 / 0.0
                    arx        25.5 / 0.9 / 0.1     refused (24)           25.4 / 0.5 / 0.0
                    lagbank    24.8 / 2.2 / 0.3     refused (24)           24.2 / 0.6 / 0.0
  nan_end           mlr        26.7 / 4.2 / 0.8     refused (24)           19.4 / 8.1 / 6.6  (last C held)
                    lagbank    26.8 / 3.1 / 2.4     refused (24)           19.1 / 5.5 / 5.5
  nan_first         lagbank    28.1 / 4.0 / 3.8     refused (1)            22.6 / 1.9 / 1.9
  stuck             mlr        38.1 / 16.0 / 0.8    79.7 / 53.8 / 53.8     62.0 / 40.0 / 36.1
                    arx        26.6 / 2.7 / 1.2     46.1 / 20.7 / 20.7     46.1 / 20.7 / 20.7
                    lagbank    27.8 / 6.0 / 2.9     72.4 / 48.2 / 48.2     62.0 / 38.1 / 37.8
  spike50 (1 row)   mlr        27.5 / 4.2 / 0.0     271.4 / 288.1 / 0.0    27.5 / 19.1 / 0.0
                    arx        25.5 / 0.9 / 0.1     83.2 / 105.2 / 5.6 ->  21.2 / 34.3 / 5.6 ->
                                                    24.5 / 19.1 / 0.9      24.5 / 18.1 / 0.9
                    lagbank    24.8 / 2.2 / 0.3     241.6 / 260.8 / 8.9 -> 19.1 / 33.8 / 8.9 ->
                                                    22.8 / 41.4 / 1.4      22.8 / 29.5 / 1.4
  amb_offset5       mlr        27.5 / 1.8 / 0.0     20.4 / 10.5 / 6.1      20.4 / 10.5 / 6.1
                    arx        25.4 / 1.1 / 0.0     24.8 / 7.1 / 5.3       24.8 / 7.1 / 5.3
                    lagbank    23.5 / 1.1 / 0.8     46.4 / 22.2 / 22.2     46.4 / 22.2 / 22.2
  kelvin_half       mlr        26.7 / 4.2 / 0.8     271.4 / 288.1 / 234.4  19.4 / 37.8 / 36.3
                    lagbank    26.8 / 3.1 / 2.4     1825 / 1849 / 1849     19.1 / 34.6 / 34.6
  kelvin_all        lagbank    26.7 / 3.2 / 2.2     24.2 / 0.0 / 0.0       24.2 / 0.0 / 0.0  (referenced)
  gap3h             lagbank    32.2 / 8.0 / 8.0     32.2 / 8.0 / 8.0       32.2 / 8.0 / 8.0  (no event)
  dup_row           mlr        27.5 / 0.0 / 0.0     27.5 / 0.0 / 0.0       27.5 / 0.0 / 0.0 (time substituted)
                    lagbank    24.3 / 0.6 / 0.0     24.3 / 0.6 / 0.0       24.3 / 0.6 / 0.0
  swap              arx        25.4 / 0.4 / 0.0     25.4 / 0.4 / 0.0       25.4 / 0.4 / 0.0 (time substituted)
                    lagbank    24.3 / 0.8 / 0.0     24.3 / 0.8 / 0.0       24.3 / 0.8 / 0.0
  dup_time, time_first_blank: every form as healthy (0.0)

(code71, 2026-12-02, 12.1 s CPU) ``ovld_1`` / ``ovld_end``: adaptive and plain as ``nan_1`` /
``nan_end`` (held; plain refused at row 24); the code took +9.9E+37 as a temperature and clamped
it (before -> now, as ``nan_1`` / ``nan_end`` to the digit)::

  ovld_1            mlr        27.5 / 16.7 / 0.0  -> 27.5 / 2.7 / 0.0
                    arx        21.2 / 25.4 / 25.4 -> 25.4 / 0.5 / 0.0
                    lagbank    19.1 / 24.2 / 24.2 -> 24.2 / 0.6 / 0.0
  ovld_end          mlr        19.4 / 27.5 / 26.0 -> 19.4 / 8.1 / 6.6
                    arx        21.2 / 25.4 / 25.4 -> 21.2 / 4.2 / 4.2
                    lagbank    19.1 / 34.6 / 34.6 -> 19.1 / 5.5 / 5.5

The compiled C (``tc_step`` in a small harness) equals the code on every fault to 2.3e-13 µm.
Every correction of every form is finite.  Before session 53 the code stepped a NaN: one empty
cell gave a NaN correction on every later row of the campaign (the guard, the lags and the AR
feedback kept it; ``nan_1``: 24 of 47 rows NaN, every family); now the sample is refused and the
last correction repeated, as the plain stream refuses the row (``stream.c``, the C driver, still
stops there: exit 2 naming row and input).

The one-row spike (session 54): the clamp's bound ``|clamp_gain . ex|`` was 0 once the excess
ended, so a dynamic model's memory of the spike (lags, AR feedback) passed on to the campaign's
end; back in range the last excess's bound now holds (``streaming.py``, the Simulator, the C, the
ST), and what remains is the memory of the reading the clamp gives for that row, the envelope's
edge (7.9 K above the true reading here): the lag bank's plain stream 260.8 µm off the row after
-> 41.4, 8.9 -> 1.4 at the end; the code (its guard spreads it) 33.8 -> 29.5 at most, 8.9 -> 1.4
at the end.  Every other line is unchanged to the printed digit.  Measured and not chosen: the
sensor monitor's jump limit (3 x the largest training step per sensor, per sample elapsed)
refusing the sample in the code (a numpy prototype, last correction repeated): spike50 0.6 /
0.5 / 2.7 µm largest change for lagbank / arx / mlr, 0 at the end, but ``amb_offset5`` refused for
9 samples (45 min; ``T_amb``'s limit 0.57 K per 5 min), and so was the same +5 K reached by a
ramp of 1 K per sample.  Left as designed, measured: the plain stream has no guard, and the
clamp puts a far-out reading at its envelope's edge (MLR's -36 µm/K on ``T_motor2``: -271 µm for
one spiked row; a lag bank on a reading in K: 1825 µm); the adaptive compensator reads a spike
as missing (0.9-4.2 µm), and +5 K on ``T_amb`` as a jump of the sensor (excluded, re-referenced
by it, re-admitted after 11 samples): it moves 1.1-1.8 µm where the plain stream and the code
move 7-22 µm (``amb_offset5``).  It does the same with a real step of the air.  RMS over
E_X/E_Y/E_Z of measured minus predicted error from the middle row on (µm), adaptive (its
exclusions) / plain::

  K06               mlr             arx             lagbank
  healthy            4.38 (0) / 4.38  5.77 (0) / 5.77  4.43 (0) / 4.43
  air +5 K          10.77 (1) / 6.46 10.57 (1) / 5.61  7.20 (1) / 11.77
  air +2 K           6.30 (1) / 3.08  6.58 (1) / 5.47  3.92 (1) / 7.80
  air +5 K/30 min    7.90 (1) / 6.76  8.37 (1) / 5.69  5.57 (1) / 10.17   (stop 59; 7.92 / 8.38 / 5.68
                                                     adaptive when measured in session 54)
  T_amb offset +5 K  4.70 (1) / 8.01  5.78 (1) / 8.82  3.99 (1) / 18.18
  T_amb offset +2 K  4.70 (1) / 6.33  5.78 (1) / 7.95  3.99 (1) / 10.80

(sub71, ``monitor.fallbacks``: while ``T_amb``, which no other sensor predicts, is out the
correction is the family's fitted without it; measured 2026-12-02, adaptive: air +5 K 10.29 /
10.19 / 6.70, +2 K 5.87 / 6.43 / 3.60, +5 K/30 min 6.21 / 7.39 / 3.93, offset +5 K and +2 K 4.37 /
5.81 / 3.72; ``amb_offset5``'s largest change mlr 1.0, arx 0.8, lagbank 1.2 µm; every other line
the same.)  The offset is held at the healthy error; the real step is re-referenced away as the offset is
(never re-admitted as measured), and the MLR and ARX corrections lose 1.2-2.0x against the plain
stream that follows it; the lag bank extrapolates the step worse than it ignores it.  A model of the
structure following the air, fitted on the train campaigns (``air_evidence``; squared
standardised residuals of the 9 structure sensors over the 10 samples from the step, the air as
measured / re-referenced): healthy 38.7 / 38.7, air +5 K 52.4 / 53.8, +2 K 38.7 / 38.8, ramp
46.7 / 46.5, offset +5 K 54.5 / 38.7, +2 K 41.7 / 38.7: the offsets are told, the real steps
only by noise (the training has no step of air).  docs/monitoring.md, "A real ambient step".

Deployed against scored on the same healthy record (session 53, the CLI as a stranger runs it:
``run model=F ati=W eval.mode=M``, ``replay replay.model=<model.pkl> monitor.adaptive=true|false``,
``export export.format=json|c|st``, the C compiled with gcc and fed the raw test files, the ST
run by the tests' transpiler): every family (mlr, pcr, arx, lagbank, hammerstein, lstm, auto) x
``ati=none|cmeans`` x ``eval.mode=simulation|one_step`` on ``yearround_spindle`` seed 5353, and
mlr/arx/lagbank/hammerstein/arx_rf on ``swiss_lathe_door`` seed 5354 (24 h / 8 h): ``replay``'s
RMSE (plain and adaptive, no event on healthy data) equals ``run``'s simulation RMSE within
2.1e-15 relative, max|stream - batch| <= 3.3e-13 µm; the exported json (Simulator), the C and
the ST equal the adaptive ``replay`` stream within 3.0e-13 µm (corrections up to 40 µm) for every
family that exports (ati=none: mlr, pcr, arx, lagbank, hammerstein); ati=cmeans, lstm, arx_rf and
auto were refused, exit 2, in one line naming what exports.  Since export57 ATI models and
``auto`` export too (``benchmarks/bench_deployed_as_scored59.py``: every family x ``ati``, through
``promote`` and the registered version, C / ST / json within 4e-13 µm of ``run``'s predictions).
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
import pandas as pd
from hydra import compose, initialize_config_dir

from thermocomp.apps.deploy.export import Simulator, state_space
from thermocomp.apps.deploy.report import plain, stream_rows
from thermocomp.apps.sim.ambient import step_air
from thermocomp.apps.sim.scenario import write_scenario
from thermocomp.apps.sim.yearround import YearRoundSpindle
from thermocomp.base.paths import conf_dir
from thermocomp.shell.builders import deployable_model
from thermocomp.shell.cli import main
from thermocomp.shell.source import read_streamed

SENSOR, CAMPAIGN, FAMILIES = "T_motor2", "K06", ("mlr", "arx", "lagbank")
TARGETS = ["E_X", "E_Y", "E_Z"]


class _AirStepped(YearRoundSpindle):
    """The bench's record with the air of ``CAMPAIGN`` changed from its middle row (real)."""

    def __init__(self, *args, step_c=5.0, ramp_s=0.0, **kwargs):
        super().__init__(*args, **kwargs)
        self.step_c, self.ramp_s = step_c, ramp_s

    def plans(self, rng):
        return step_air(super().plans(rng), CAMPAIGN, self.step_c, self.ramp_s)


def ambient_cases(root: Path, raw: pd.DataFrame) -> dict[str, tuple[pd.DataFrame, pd.DataFrame]]:
    """``{name: (readings, measured errors)}`` of K06: the air really stepped (+5 K, +2 K, +5 K
    ramped over 30 min; the simulation rerun, every other campaign identical) and ``T_amb``'s
    column offset (+5, +2 K; the machine unchanged)."""
    out = {"healthy": (raw, raw)}
    for name, step_c, ramp_s in (("real +5 K", 5.0, 0.0), ("real +2 K", 2.0, 0.0),
                                 ("real +5 K/30 min", 5.0, 1800.0)):
        path = root / f"air_{step_c:g}_{ramp_s:g}"
        if not path.exists():
            write_scenario(_AirStepped(n_campaigns=9, duration_h=(3.0, 5.0), seed=5353,
                                       step_c=step_c, ramp_s=ramp_s), path)
        df = pd.read_csv(path / f"{CAMPAIGN}.csv")
        out[name] = (df, df)
    for dT in (5.0, 2.0):
        f = raw.copy()
        f.loc[len(raw) // 2:, "T_amb"] += dT
        out[f"offset +{dT:g} K"] = (f, raw)
    return out


def _air_steps(df: pd.DataFrame, air: np.ndarray, sensors: list[str]):
    """Each structure sensor's next change, its last change and its gap to ``air`` (rows 1..)."""
    T = df[sensors].to_numpy(float)
    dT = np.diff(T, axis=0)
    return dT[1:], dT[:-1], air[1:-1, None] - T[1:-1]


def air_evidence(data: Path, cases: dict, train: list[str], window: int = 10) -> dict[str, tuple]:
    """Would a model of the structure following the air tell a real step from an offset?  Per
    structure sensor, its change per sample regressed on its last change and its gap to the air
    over the ``train`` campaigns; per case, the sum over ``window`` samples from the step of the
    squared standardised residuals, the air as measured / re-referenced by its jump."""
    sensors = [c for c in pd.read_csv(data / f"{train[0]}.csv").columns
               if c.startswith("T_") and c != "T_amb"]
    rows = [_air_steps(f, f["T_amb"].to_numpy(float), sensors)
            for f in (pd.read_csv(data / f"{c}.csv") for c in train)]
    y, last, gap = (np.vstack(part) for part in zip(*rows))
    fits = []
    for i in range(len(sensors)):
        A = np.c_[last[:, i], gap[:, i], np.ones(len(y))]
        coef = np.linalg.lstsq(A, y[:, i], rcond=None)[0]
        fits.append((coef, np.std(y[:, i] - A @ coef)))

    def score(df, air, h):
        y, last, gap = (v[h - 1:h - 1 + window] for v in _air_steps(df, air, sensors))
        return sum(float(np.sum(((y[:, i] - np.c_[last[:, i], gap[:, i], np.ones(len(y))] @ c) / sd) ** 2))
                   for i, (c, sd) in enumerate(fits))
    out = {}
    for name, (df, _) in cases.items():
        air, h = df["T_amb"].to_numpy(float), len(df) // 2
        back = air.copy()
        back[h:] -= (air[h] - air[h - 1]) - (air[h - 1] - air[h - 2])    # re-referenced by the jump
        out[name] = (score(df, air, h), score(df, back, h))
    return out


def _rms_after_onset(deployed, readings, errors) -> tuple[float, int]:
    """RMS over targets and rows of measured minus predicted error from the middle row on, and
    the monitor's exclusions."""
    s = stream_rows(deployed, readings, CAMPAIGN)
    h = len(readings) // 2
    r = errors[TARGETS].to_numpy(float)[h:] - s.y[h:]
    return float(np.sqrt((r ** 2).sum(axis=1).mean())), sum(e.get("to") == "excluded" for e in s.events)


def faults(df: pd.DataFrame) -> dict[str, pd.DataFrame]:
    """Each fault applied to a copy of the campaign ``df`` (rows as recorded)."""
    h, out = len(df) // 2, {}

    def put(name, rows, column, value):
        f = df.copy()
        f[column] = f[column].astype(float)
        f.loc[rows, column] = value(f.loc[rows, column])
        out[name] = f
    put("nan_1", [h], SENSOR, lambda v: np.nan)
    put("nan_16", list(range(h, h + 16)), SENSOR, lambda v: np.nan)
    put("nan_end", list(range(h, len(df))), SENSOR, lambda v: np.nan)
    put("nan_first", [0], SENSOR, lambda v: np.nan)
    put("stuck", list(range(h, len(df))), SENSOR, lambda v: v.iloc[0])
    put("spike50", [h], SENSOR, lambda v: v + 50)
    put("amb_offset5", list(range(h, len(df))), "T_amb", lambda v: v + 5)   # the column only
    put("kelvin_half", list(range(h, len(df))), SENSOR, lambda v: v + 273.15)
    put("kelvin_all", list(range(len(df))), SENSOR, lambda v: v + 273.15)
    put("ovld_1", [h], SENSOR, lambda v: 9.9e37)     # a DAQ's overload mark (code71)
    put("ovld_end", list(range(h, len(df))), SENSOR, lambda v: 9.9e37)   # the thermocouple open
    put("gap3h", list(range(h, len(df))), "time", lambda v: v + 3 * 3600)
    put("dup_time", [h + 1], "time", lambda v: df.loc[h, "time"])
    put("time_first_blank", [0], "time", lambda v: np.nan)
    out["dup_row"] = pd.concat([df.iloc[:h + 1], df.iloc[h:]]).reset_index(drop=True)
    swapped = df.copy()
    swapped.iloc[[h, h + 1]] = df.iloc[[h + 1, h]].to_numpy()
    out["swap"] = swapped
    return out


def _aligned(name: str, y: np.ndarray, h: int) -> np.ndarray:
    """``y`` row for row with the healthy record's rows: the repeated row's output dropped, the
    swapped rows' outputs swapped back."""
    if name == "dup_row":
        return np.delete(y, h + 1, axis=0)
    if name == "swap":
        y = y.copy()
        y[[h, h + 1]] = y[[h + 1, h]]
    return y


def _cfg(data: Path, *overrides):
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        return compose(config_name="config", overrides=[f"data.path={data}", "track=false", *overrides])


def _streamed(deployed, df) -> tuple[np.ndarray, str]:
    try:
        s = stream_rows(deployed, df, CAMPAIGN)
    except Exception as exc:                      # the plain stream refuses a missing value
        return None, f"refused ({str(exc).split('data row ')[-1].split(':')[0].strip()})"
    events = sorted({e.get("to") for e in s.events})
    return -s.y, ",".join(events)


def _code(deployed, df) -> np.ndarray:
    sim = Simulator(state_space(deployed))
    t = df["time"].to_numpy(float)
    return np.array([sim.step(u, tt) for u, tt in zip(df[plain(deployed).columns_].to_numpy(float), t)])


def _compiled_c_agrees(deployed, frames, folder: Path) -> float | None:
    """Largest |C tc_step - Simulator| over the faults (a small harness; None without gcc)."""
    if shutil.which("gcc") is None:
        return None
    from thermocomp.apps.deploy.export import exported_files
    for name, text in exported_files(deployed, "c").items():
        (folder / name).write_text(text)
    (folder / "h.c").write_text(
        '#include <stdio.h>\n#include <stdlib.h>\n#include "compensator.h"\n'
        "int main(void){tc_state s; double u[TC_N_INPUTS], c[TC_N_OUTPUTS], t; int r, i; char b[64];\n"
        "tc_init(&s); while (scanf(\"%d %63s\", &r, b) == 2) { t = strtod(b, NULL);\n"
        "for (i = 0; i < TC_N_INPUTS; i++) {\n"
        "    if (scanf(\"%63s\", b) != 1) return 1;\n"
        "    u[i] = strtod(b, NULL);\n"
        "}\n"
        "if (r) tc_reset(&s); tc_step(&s, u, t, c);\n"
        "for (i = 0; i < TC_N_OUTPUTS; i++) printf(\"%.17g \", c[i]); printf(\"\\n\"); } return 0; }\n")
    subprocess.run(["gcc", "-O2", "compensator.c", "h.c", "-lm", "-o", "h"], cwd=folder, check=True)
    cols, worst = plain(deployed).columns_, 0.0
    for df in frames:
        lines = [" ".join([str(int(k == 0)), repr(float(t)), *map(repr, map(float, u))])
                 for k, (t, u) in enumerate(zip(df["time"], df[cols].to_numpy(float)))]
        run = subprocess.run([str(folder / "h")], input="\n".join(lines) + "\n", text=True,
                             capture_output=True, check=True)
        got = np.array([[float(v) for v in line.split()] for line in run.stdout.splitlines()])
        worst = max(worst, float(np.max(np.abs(got - _code(deployed, df)))))
    return worst


def main_(root: Path) -> None:
    data = root / "ys"
    if not data.exists():
        main(["simulate", "sim=yearround_spindle", "seed=5353", "sim.generator.n_campaigns=9",
              "sim.generator.duration_h=[3.0,5.0]", f"data.path={data}", f"out={root / 'sim'}"])
    raw = pd.read_csv(data / f"{CAMPAIGN}.csv")
    print(f"{'fault':17s} {'model':8s} {'adaptive':>24s} {'plain':>24s} {'code':>24s}")
    ambient = {}
    for family in FAMILIES:
        model = root / family / "model.pkl"
        if not model.exists():
            main(["run", f"data.path={data}", f"model={family}", "track=false", "plots=none",
                  f"out={root / family}"])
        forms = {}
        for adaptive in ("true", "false"):
            cfg = _cfg(data, f"monitor.adaptive={adaptive}")
            ds, train_ids, _, _ = read_streamed(cfg)
            forms[adaptive] = deployable_model(cfg, ds, train_ids, str(model), "replay.model")[0]
        healthy = {k: _streamed(d, raw)[0] for k, d in forms.items()}
        healthy["code"] = _code(forms["true"], raw)
        cases = {"healthy": raw, **faults(raw)}
        for name, df in cases.items():
            cells = []
            for form in ("true", "false", "code"):
                y, said = (_code(forms["true"], df), "") if form == "code" else _streamed(forms[form], df)
                if y is None:
                    cells.append(said)
                    continue
                y = _aligned(name, y, len(raw) // 2)
                n = min(len(y), len(healthy[form]))
                change = np.abs(y[:n] - healthy[form][:n])
                cells.append(f"{np.max(np.abs(y)):.1f} / {np.max(change):.1f} / {np.max(change[-1]):.1f}"
                             + ("" if np.isfinite(y).all() else " NaN!"))
            print(f"{name:17s} {family:8s} " + " ".join(f"{c:>24s}" for c in cells))
        with tempfile.TemporaryDirectory() as tmp:
            worst = _compiled_c_agrees(forms["true"], list(cases.values()), Path(tmp))
        print(f"{'':17s} {family:8s} compiled C tc_step vs the code over every fault: {worst}")
        ambient[family] = forms
    print("T_amb from K06's middle row: RMS of measured - predicted error from then on (µm), "
          "adaptive (exclusions) / plain")
    for name, (df, errors) in ambient_cases(root, raw).items():
        cells = []
        for family, forms in ambient.items():
            a, n = _rms_after_onset(forms["true"], df, errors)
            cells.append(f"{family} {a:5.2f} ({n}) / {_rms_after_onset(forms['false'], df, errors)[0]:5.2f}")
        print(f"{name:17s} " + "   ".join(cells))
    listed = pd.read_csv(root / "ys" / "campaigns.csv")
    train = listed.loc[listed["split"] == "train", "campaign"].tolist()
    print("the structure following the air (fitted on the train campaigns): squared standardised "
          "residuals over 10 samples, air as measured / re-referenced")
    for name, (measured, back) in air_evidence(root / "ys", ambient_cases(root, raw), train).items():
        print(f"{name:17s} {measured:6.1f} / {back:6.1f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--root", default="/tmp/df53")
    main_(Path(parser.parse_args().root))
