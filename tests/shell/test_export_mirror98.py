"""The numpy mirror's per-sample arrays made once (ci98, issue 34; benchmarks/bench_ci98.py): the
code's monitor (``CodeMonitor``) hands out the active set's arrays (``_set``) and the judgement's
(``_judge``) as last made while the sensors out, the operator, the window, its errors and the bands
stay, read only, and the active mask as a copy a caller may mark.  The mirror then gives what it
gave when each call made them anew, bit for bit, on cmon80's faults (a reading beyond its range,
its return, a common step, a machine hotter than training, a second sensor out): exclusions,
re-admissions and re-references, where the memo must be made again."""

from __future__ import annotations

import numpy as np

from test_export_cmon80 import _faulty, served  # noqa: F401  (the module's fixture)
from thermocomp.apps.deploy.export import Simulator
from thermocomp.apps.deploy.export.watch import CodeMonitor

KINDS = ("spike", "beyond", "common", "hotter", "second")


class _Anew(CodeMonitor):
    """The monitor with every ``_set`` and ``_judge`` made anew (as before ci98)."""

    def _set(self):
        self._set_memo = None
        return super()._set()

    def _judge(self):
        self._judge_memo = None
        return super()._judge()


def _trace(ss, frame, anew: bool = False) -> list[bytes]:
    """Per row: the corrections, the refusal, the monitor's flags, event and sensors out."""
    sim = Simulator(ss)
    if anew:
        sim.watch = _Anew(ss.monitor)
    sim.reset()
    rows = []
    for u, t in zip(frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)):
        c, w = sim.step(u, t), sim.watch
        rows.append(c.tobytes() + np.array([sim.refused, w.flags, w.sensor, w.rule, w.missed,
                                            w.out, w.out2]).tobytes())
    return rows


def _monitor_after(ss, campaign, rows: int) -> CodeMonitor:
    """The mirror's monitor after ``campaign``'s first ``rows`` samples."""
    sim = Simulator(ss)
    sim.reset()
    for u, t in zip(campaign[ss.inputs].to_numpy(float)[:rows], campaign["time"].to_numpy(float)):
        sim.step(u, t)
    return sim.watch


def test_the_mirror_gives_what_it_gave_with_its_arrays_made_anew(served):  # noqa: F811
    _, ss, campaign = served
    flagged = 0
    for kind in KINDS:
        frame = _faulty(campaign, kind)
        made_once = _trace(ss, frame)
        assert made_once == _trace(ss, frame, anew=True), kind
        flagged += sum(row != made_once[0] for row in made_once)
    assert flagged          # (the faults move the monitor: the memo is made again)


def test_a_sample_gets_the_same_read_only_arrays_and_a_mask_it_may_mark(served):  # noqa: F811
    """Fails on 16d3b58d: each call made new arrays (``_set() is _set()`` false)."""
    w = _monitor_after(*served[1:], 5)
    assert w._set() is w._set() and w._judge() is w._judge()
    assert not any(a.flags.writeable for a in (*w._set()[1:], *w._judge()))
    mask = w._active()
    mask[0] = False              # (a caller's trial set: the next mask is whole again)
    assert w._active().all() and w._active() is not w._active()


def test_an_exclusion_within_a_sample_makes_the_judgement_again(served):  # noqa: F811
    """A sensor taken out (``_exclude``: out, the window's errors and bands made again) within a
    sample, at the same window position: ``_judge`` and ``_set`` answer for the new set, as made
    anew, not as made before it (a memo keyed on the window's position alone fails here)."""
    w = _monitor_after(*served[1:], 25)
    level, err = w._judge()
    w._put_out(1)
    w._recompute()
    got = w._judge(), w._set()
    w._judge_memo = w._set_memo = None
    anew = w._judge(), w._set()
    assert not w._set()[1][1] and not np.array_equal(got[0][1], err, equal_nan=True)
    for mine, fresh in zip((*got[0], *got[1][1:]), (*anew[0], *anew[1][1:])):
        assert np.array_equal(mine, fresh, equal_nan=True)
