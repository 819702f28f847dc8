"""The generated code's banner says what reads the time (deploy59).

An adaptive compensator's guard limits the correction's rate per second: the code reads the
time of every sample (``tc_step``'s ``time``, ``stream.c``'s column) even for a model without
lags.  The banner of such a model said ``time: s, not read; period 0 s`` (0: the lag period of a
model that has no lags), though a missing time is taken as the previous one plus the training's
sample period.
"""

from __future__ import annotations

import pytest

from test_export import _make_dataset, _trained
from thermocomp.shell.cli import main


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return _make_dataset(tmp_path_factory.mktemp("banner") / "data")


def test_an_adaptive_models_banner_says_the_guard_reads_the_time(dataset, tmp_path):
    model = _trained(dataset, tmp_path, "mlr")
    for adaptive, says in (("true", "time: s, read by the guard's rate limit; a missing or backward "
                                    "time is the previous + 120 s"),
                           ("false", "time: s, not read")):
        out = tmp_path / f"code-{adaptive}"
        assert main(["export", f"data.path={dataset}", f"export.model={model}", "export.format=c",
                     f"monitor.adaptive={adaptive}", f"out={out}", "track=false"]) == 0
        header = (out / "compensator.h").read_text()
        assert says in header and "period 0 s" not in header
    lagbank = _trained(dataset, tmp_path, "lagbank")
    out = tmp_path / "code-lagbank"
    assert main(["export", f"data.path={dataset}", f"export.model={lagbank}", "export.format=st",
                 f"out={out}", "track=false"]) == 0
    assert ("time: s, read by the first-order lags and the guard's rate limit; a missing or "
            "backward time is the previous + 120 s") in (out / "compensator.st").read_text()
