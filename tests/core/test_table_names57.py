"""The printed tables keep their columns under a lab's long target names (``E_X-Verlagerung``):
a fixed 8-character name column shifted that row's figures under the next header."""

from __future__ import annotations

from thermocomp.apps.deploy.report import replay_lines
from thermocomp.apps.monitor.report import summary_lines

NAMES = ("E_X", "E_X-Verlagerung")


def _ends_under(lines: list[str], label: str, cells: list[str]) -> None:
    """Each row's cell ends where the header's ``label`` ends."""
    end = lines[0].index(label) + len(label)
    for row, cell in zip(lines[1:], cells):
        assert row.index(cell, len(row.split()[0])) + len(cell) == end, (row, lines[0])


def test_replay_rows_stay_under_their_headers():
    targets = {t: {"n_samples": 1234 + k, "max_abs_stream_minus_batch": 1e-13, "rmse": 0.5,
                   "rmse_batch": 0.5, "us_per_sample": 50.0} for k, t in enumerate(NAMES)}
    lines = replay_lines({"targets": targets, "adaptive": False, "events": []})
    _ends_under(lines, "samples", ["1234", "1235"])


def test_monitor_rows_stay_under_their_headers():
    targets = {t: {"rmse_fixed": 1.0 + k, "rmse_adaptive": 0.5, "max_abs_correction": 3.0,
                   "all_finite": True} for k, t in enumerate(NAMES)}
    lines = summary_lines({"targets": targets, "sensors": {}, "events": []})
    _ends_under(lines, "RMSE fixed", ["1.000", "2.000"])
