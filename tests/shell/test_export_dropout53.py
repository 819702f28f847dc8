"""The exported code on a sample with a sensor dropout (an input NaN or infinite).

A CNC integrating ``tc_step`` (or a PLC the function block) is handed what its fieldbus reads.
One NaN stepped stayed in the lags, the AR feedback and the guard's previous output: every later
correction of the campaign was NaN (an ARX with AR on a fresh ``yearround_spindle``, seed 5353:
one empty cell of ``T_motor2`` at row 24 of 47 gave 24 NaN corrections, silently).  Now the
sample is refused before anything is remembered, as the plain stream refuses such a row: the
last correction is repeated (0 before a campaign's first sample), ``tc_step`` returns -1 (the
block's ``refused``), no reference is taken there, and the stream goes on as if the row had not
been read.  The C, the Structured Text and the numpy reference are checked against one another
and against the same stream without the refused rows.  (These are the plain code's forms: the C
of an adaptive model holds its sensor monitor, which since cdrop77 rebuilds a monitored sensor's
missing reading instead, tests/shell/test_export_cdrop77.py; here it is built without it, as the
ST and the numpy reference of the plain system are.)
"""

from __future__ import annotations

import subprocess

import numpy as np
import pytest

from cbuild import compiled
from test_export import TOLERANCE_UM, StructuredText, _make_dataset, needs_cc
from test_export_guard import _adaptive, _simulated
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space

# (campaign, row, value): one NaN mid-campaign, an infinity, a campaign's first row missing
BAD = ((0, 7, np.nan), (0, 8, np.inf), (1, 0, np.nan), (1, 20, -np.inf))

HARNESS = r"""
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "compensator.h"
/* stdin: per row 'reset time u...' ; stdout: 'returned c...' */
int main(void) {
    tc_state s; double u[TC_N_INPUTS], c[TC_N_OUTPUTS], t; int reset, i, r;
    char cell[64];
    tc_init(&s);
    while (scanf("%d %63s", &reset, cell) == 2) {
        t = strtod(cell, NULL);
        for (i = 0; i < TC_N_INPUTS; i++) {
            if (scanf("%63s", cell) != 1) return 1;
            u[i] = strtod(cell, NULL);
        }
        if (reset) tc_reset(&s);
        r = tc_step(&s, u, t, c);
        printf("%d", r);
        for (i = 0; i < TC_N_OUTPUTS; i++) printf(" %.17g", c[i]);
        printf("\n");
    }
    return 0;
}
"""


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return _make_dataset(tmp_path_factory.mktemp("dropout") / "data")


def _with_dropouts(tests, column):
    bad = [df.copy() for df in tests]
    for k, row, value in BAD:
        bad[k].loc[row, column] = value
    return bad


def _c(deployed, folder, tests, columns, monitor=False) -> tuple[np.ndarray, np.ndarray]:
    for name, text in exported_files(deployed, "c", monitor=monitor).items():
        (folder / name).write_text(text)
    (folder / "harness.c").write_text(HARNESS)
    compiled(folder, ("compensator.c", "harness.c"), "harness", warnings=False)
    return _c_run(folder, tests, columns)


def _c_run(folder, tests, columns) -> tuple[np.ndarray, np.ndarray]:
    """``(tc_step's returns, corrections)`` of the harness built in ``folder``."""
    lines = [" ".join([str(int(k == 0)), repr(float(t)), *(repr(float(v)) for v in u)])
             for df in tests for k, (t, u) in enumerate(zip(df["time"], df[columns].to_numpy(float)))]
    run = subprocess.run([str(folder / "harness")], input="\n".join(lines) + "\n", text=True,
                         capture_output=True, check=True)
    out = np.array([[float(v) for v in line.split()] for line in run.stdout.splitlines()])
    return out[:, 0], out[:, 1:]


def _st(deployed, tests, columns, monitor=True) -> tuple[np.ndarray, np.ndarray]:
    fb = StructuredText(exported_files(deployed, "st", monitor=monitor)["compensator.st"])
    refused, out = [], []
    for df in tests:
        for k, (u, t) in enumerate(zip(df[columns].to_numpy(float), df["time"])):
            fb.vars["ref_valid"][:] = False
            out.append(fb(u, t, k == 0))
            refused.append(bool(fb.vars.get("refused", False)))
    return np.array(refused), np.array(out)


@needs_cc
def test_a_sensor_dropout_is_refused_by_every_form_of_the_code_and_the_stream_goes_on(dataset,
                                                                                     tmp_path):
    deployed, tests = _adaptive(dataset, "arx")          # AR feedback, lags, guard: all remember
    cols, ss = deployed.columns_, state_space(deployed)
    bad = _with_dropouts(tests, cols[1])
    returned, c_out = _c(deployed, tmp_path, bad, cols)
    assert np.isfinite(c_out).all(), f"{(~np.isfinite(c_out)).any(axis=1).sum()} NaN corrections"
    st_refused, st_out = _st(deployed, bad, cols)
    sim_out = _simulated(ss, bad, cols)
    assert np.isfinite(c_out).all() and np.isfinite(st_out).all() and np.isfinite(sim_out).all()
    for other in (st_out, sim_out):
        assert np.max(np.abs(other - c_out)) <= TOLERANCE_UM
    offsets = np.cumsum([0] + [len(df) for df in bad])
    at = [offsets[k] + row for k, row, _ in BAD]
    assert np.flatnonzero(returned < 0).tolist() == at == np.flatnonzero(st_refused).tolist()
    for i, (k, row, _) in enumerate(BAD):      # the last correction held; 0 at a campaign's start
        assert np.array_equal(c_out[at[i]], c_out[at[i] - 1] if row else np.zeros(len(ss.targets)))
    # the refused rows as if never read: the stream without them, row for row
    kept = [df.drop(index=[row for k2, row, _ in BAD if k2 == k]).reset_index(drop=True)
            for k, df in enumerate(bad)]
    clean = _simulated(ss, kept, cols)
    assert np.max(np.abs(np.delete(c_out, at, axis=0) - clean)) <= TOLERANCE_UM


@needs_cc
def test_an_overload_mark_in_a_temperature_is_a_missing_value_in_every_form_of_the_code(dataset,
                                                                                       tmp_path):
    """A DAQ's +9.9E+37 (an open thermocouple) is beyond MAX_ABS_T_C, which no sensor reads: a PLC
    cannot refuse the row, so tc_step, the ST block and the Simulator take it as they take NaN
    (code71; they clamped it into the model before: a lag bank's corrections far off)."""
    deployed, tests = _adaptive(dataset, "arx")
    cols = deployed.columns_
    column = next(c for c in cols if c.startswith("T_"))
    marked = [df.copy() for df in tests]
    marked[0].loc[7, column], marked[1].loc[20:24, column] = 9.9e37, -9.9e37   # mid-run
    missing = [df.copy() for df in tests]
    missing[0].loc[7, column], missing[1].loc[20:24, column] = np.nan, np.nan
    returned, c_out = _c(deployed, tmp_path, marked, cols)
    expected = _c_run(tmp_path, missing, cols)
    assert (returned < 0).sum() == 6
    assert np.array_equal(returned, expected[0]) and np.array_equal(c_out, expected[1])
    for form in (_st, lambda d, t, c: (None, _simulated(state_space(d), t, c))):
        got, want = form(deployed, marked, cols), form(deployed, missing, cols)
        assert np.array_equal(got[1], want[1])
        assert got[0] is None or np.array_equal(got[0], want[0])


def test_no_reference_is_taken_at_a_refused_sample(dataset):
    deployed, tests = _adaptive(dataset, "mlr", "adapt.method=bias")
    ss = state_space(deployed)
    sim = Simulator(ss)
    df = tests[0]
    u = df[deployed.columns_].to_numpy(float)
    sim.step(u[0], df["time"][0])
    bias = sim.output.bias.copy()
    u1 = u[1].copy()
    u1[0] = np.nan
    sim.step(u1, df["time"][1])
    sim.reference(np.full(len(ss.targets), 3.0))
    assert np.array_equal(sim.output.bias, bias) and sim.refused
    sim.step(u[2], df["time"][2])
    sim.reference(np.full(len(ss.targets), 3.0))
    assert not np.array_equal(sim.output.bias, bias)
