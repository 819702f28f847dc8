"""How long each unit of `make test`'s scheduling took, so that its xdist workers start the
longest first (tests/conftest.py): a unit that starts late must be short, or one worker idles
while the other finishes it.

A unit is a module (``--dist loadfile``: its tests on one worker, its module fixtures built once)
or a test of its own (conftest's ``ALONE``).  ``pytest --store-durations`` (any selection, with
or without ``-n``) adds up each unit's setup, call and teardown seconds and writes them into
``tests/durations.json``, the units it did not run kept as they were.  A unit the file does not
name (a new module) goes first: started early, even a long one ends in time.

Why measured seconds and not a rule (a ``slow`` mark, the number of tests): the mark ordered
modules alphabetically among 40 marked ones, and put a 40 s module 729 s into an 823 s run;
the number of tests says little (145 tests of test_config_schema take 12 s, 6 of
test_dvc_metrics 66 s).
"""

from __future__ import annotations

import json
from collections import Counter
from pathlib import Path

from thermocomp.base.files import atomic_write_text

FILE = Path(__file__).with_name("durations.json")


def load(path: Path = FILE) -> dict[str, float]:
    """The seconds of each unit measured so far (none if the file is missing)."""
    return json.loads(path.read_text()) if path.exists() else {}


def longest_first(units: list[str], seconds: dict[str, float]) -> list[str]:
    """``units`` (each once) in the order to start them: the unmeasured ones, then the measured
    from the longest down; ties in the order given."""
    return sorted(units, key=lambda u: -seconds.get(u, float("inf")))


class Recorder:
    """The ``--store-durations`` plugin: each report's seconds added to its unit's (``unit_of``
    names it); written at the session's end, in the process that gets every report (xdist's
    controller, or the only one)."""

    def __init__(self, unit_of, path: Path = FILE):
        self.unit_of, self.path, self.seconds = unit_of, path, Counter()

    def pytest_runtest_logreport(self, report):
        self.seconds[self.unit_of(report.nodeid)] += report.duration

    def pytest_sessionfinish(self, session):
        if hasattr(session.config, "workerinput") or not self.seconds:
            return   # an xdist worker: its controller writes the whole run's
        merged = {**load(self.path), **{u: round(s, 1) for u, s in self.seconds.items()}}
        # atomically: a run killed while writing must not leave a file every later session fails to read
        atomic_write_text(self.path, json.dumps(dict(sorted(merged.items())), indent=0) + "\n")
