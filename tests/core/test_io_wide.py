"""The reader's checks of a wide file, taken over every column at once, say what they said
column by column (a volumetric campaign: 1430 distance columns)."""

from __future__ import annotations

import numpy as np
import pyarrow as pa

from thermocomp.core.io.values import _error_ranges


def test_error_ranges_of_columns_side_by_side_are_each_columns_own():
    nan, inf = np.nan, np.inf
    table = pa.table({
        "time": [0.0, 1.0, 2.0, 3.0],
        "E_X": [1.0, 4.0, -2.0, 3.0],
        "E_dead": [2.5, 2.5, 2.5, 2.5],                  # constant: a dead channel
        "E_two": [nan, 7.0, 7.0, nan],                   # constant, but too few values to say
        "E_gaps": [nan, 7.0, inf, 7.0 - 1e-9],           # an infinite cell is no value either
        "E_empty": pa.array([None, None, None, None], pa.float64()),
        "T_a": [20.0, 20.0, 20.0, 20.0],                 # not an error column
    })
    ranges = _error_ranges(table)
    assert list(ranges) == ["E_X", "E_dead", "E_two", "E_gaps"]
    for name, (span, constant) in ranges.items():
        v = table.column(name).to_numpy(zero_copy_only=False)
        v = v[np.isfinite(v)]
        assert span == float(np.ptp(v)) and isinstance(span, float)
        assert constant is (len(v) >= 3 and bool(np.all(v == v[0])))
    assert ranges["E_dead"][1] and not ranges["E_two"][1] and not ranges["E_gaps"][1]
