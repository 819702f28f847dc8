"""The rows the correction guard changed, summed over replayed campaigns by one helper (small71).

``replay``/``promote`` (deploy), ``monitor`` and ``diagnose`` each summed the count their own
way, under a key defined twice; what they report is unchanged (tests/shell/
test_guarded_everywhere70.py holds the four equal on a record whose guard bounds 51 test rows).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from thermocomp.core.guarded import mark_guarded, summed, summed_frames


def _frame(rows) -> pd.DataFrame:
    frame = pd.DataFrame({"E_X": [0.0], "E_Z": [0.0]})
    if rows is not None:
        mark_guarded(frame, ["E_X", "E_Z"], np.asarray(rows, np.int64))
    return frame


def test_the_count_is_summed_per_target_and_none_without_a_guard():
    targets = ["E_X", "E_Z"]
    assert summed_frames([_frame([3, 0]), _frame([4, 2])], targets) == {"E_X": 7, "E_Z": 2}
    assert summed([np.array([3, 0]), np.array([4, 2])], targets) == {"E_X": 7, "E_Z": 2}
    # one campaign through the plain stream (no guard): no count, not a partial one
    assert summed_frames([_frame([3, 0]), _frame(None)], targets) is None
    assert summed([], targets) == {"E_X": 0, "E_Z": 0}
    assert all(type(n) is int for n in summed_frames([_frame([1, 1])], targets).values())  # JSON
