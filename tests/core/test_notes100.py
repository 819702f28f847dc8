"""A temperature header's note in brackets, and auto's skipped ATI said in the log (notes100).

audit100: ``T1 (front)``, ``Spindel (Gehäuse)`` were refused as foreign units ("unit 'front' is
not a temperature's"), with a hint to write ``data.columns`` into the config ``init`` writes,
which ``init``, refusing, never wrote; ``model=auto`` said why it skipped ``ati`` in
metrics.json alone.  Both tests fail on fb0ed988.  data101: an all-empty column whose bracket is
a note ('Reserve (leer)') was said "read as part of the name", then refused as empty; the last
test fails on 7676398c.
"""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from thermocomp.base.errors import ThermocompError
from thermocomp.core.context import AMBIENT_C0
from thermocomp.core.io.options import _roles
from thermocomp.core.io.read import read_campaign
from thermocomp.core.io.roles import naming
from thermocomp.core.models import MLR
from thermocomp.core.models.auto import AutoRegressor

HEADERS = ["time [s]", "T1 (front)", "Spindel (Gehäuse)", "T2 (K)", "dX [µm]"]
ROLES = _roles({"roles": {"error": ["dX*"]}})     # as `init` proposes for the file
FIRST = {"time [s]": "0", "T1 (front)": "20.0", "Spindel (Gehäuse)": "20.1", "T2 (K)": "293.2",
         "dX [µm]": "0.1"}


def test_a_note_in_brackets_is_part_of_the_name_and_an_ambiguous_one_is_refused(caplog):
    with caplog.at_level(logging.INFO, logger="thermocomp"):
        plan = naming(HEADERS, ROLES, {}, FIRST)
    assert plan.names["T1 (front)"] == "T_T1_front"
    assert plan.names["Spindel (Gehäuse)"] == "T_Spindel_Gehäuse"
    assert "T_T1_front" not in plan.scales                    # no unit: °C, the contract's
    assert plan.names["T2 (K)"] == "T_T2" and plan.scales["T_T2"] == (1.0, -273.15)   # a unit
    # (said by the reader once the column is read: data101)
    assert plan.noted == {"T1 (front)": "T_T1_front", "Spindel (Gehäuse)": "T_Spindel_Gehäuse"}
    for note in ("(R)", "(K Kühlung)"):        # a unit not known, or a note: both readings named
        header = f"T3 {note}"
        with pytest.raises(ThermocompError) as refused:
            naming([*HEADERS, header], ROLES, {}, {**FIRST, header: "20"})
        said = str(refused.value)
        assert f"{note} reads as a unit the reader does not know or as a note" in said
        assert "data.units=" in said and "data.columns=" in said
        assert "'defaults: [default]'" in said and "hydra.searchpath=[file://$PWD/myconf]" in said


def test_auto_says_in_the_log_why_it_skipped_ati(caplog):
    rng = np.random.default_rng(0)
    X = 20 + rng.normal(0.0, 1.0, (400, 2))
    y = 2.0 * (X[:, 0] - 20) + rng.normal(0.0, 0.1, 400)
    campaign = np.repeat([f"K{c}" for c in range(4)], 100)
    context = pd.DataFrame({"campaign": campaign,
                            AMBIENT_C0: np.repeat([18.0, 18.0, 24.0, 24.0], 100)})
    with caplog.at_level(logging.INFO, logger="thermocomp"):
        auto = AutoRegressor({"mlr": MLR(), "ati": MLR()}).fit(X, y, context=context)
    assert "span 2 ambient level(s)" in auto.skipped_["ati"]
    assert f"auto: ati skipped: {auto.skipped_['ati']}" in caplog.text


def test_an_empty_column_with_a_note_is_refused_as_empty_and_not_said_named(tmp_path, caplog):
    rows = [f"{60 * i},{20 + 0.1 * i:.1f},,{0.3 * i:.1f}" for i in range(12)]
    path = tmp_path / "lab.csv"
    path.write_text("\n".join(["time [s],T1 (front),Reserve (leer),dX [µm]", *rows]) + "\n",
                    encoding="utf-8")
    cfg = {"roles": {"error": ["dX*"]}}
    with caplog.at_level(logging.INFO, logger="thermocomp"), pytest.raises(ThermocompError) as no:
        read_campaign(path, cfg)
    said = str(no.value)
    assert "'T_Reserve_leer'" in said and "every cell is empty" in said and "lab.csv" in said
    assert "'Reserve (leer)'" in said                          # its header in the file
    assert "Reserve (leer)': the bracket read" not in caplog.text    # 7676398c said it first
    caplog.clear()
    with caplog.at_level(logging.INFO, logger="thermocomp"):
        table, _ = read_campaign(path, {**cfg, "roles": {**cfg["roles"], "ignore": ["Reserve*"]}})
    assert "T_T1_front" in table.column_names
    assert caplog.text.count("'T1 (front)': the bracket read as part of the name, no unit: °C "
                             "assumed (T_T1_front)") == 1
