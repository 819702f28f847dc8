"""What a CV result keeps: its own prediction, not every penalty's (scale59).

The search keeps the result of each candidate it weighs; the closed-form CV predicts every
penalty of :data:`~thermocomp.apps.diagnose.shrink.ALPHAS` (rows x 18) and keeps the best
column.  Kept as a view, that column held the whole matrix alive in every result: on a year at
1 min (473,041 train rows) 68 MB per candidate instead of 3.8 MB.
"""

import numpy as np
import pandas as pd

from thermocomp.apps.diagnose.cv import CrossValidator, Problem
from thermocomp.apps.diagnose.features import Effect
from thermocomp.core.models import MLR


def heated_problem(seed: int = 3) -> Problem:
    """Four campaigns: inputs T_a, T_b, an error from a lag of T_a and the square of T_b."""
    rng = np.random.default_rng(seed)
    frames = []
    for k in range(4):
        n = 200
        frames.append(pd.DataFrame({"time": np.arange(n) * 60.0,
                                    "T_a": 20 + np.cumsum(rng.uniform(0, 0.05, n)),
                                    "T_b": 20 + np.cumsum(rng.uniform(0, 0.03, n)),
                                    "campaign": f"C{k}"}))
    df = pd.concat(frames, ignore_index=True)
    lagged = df.groupby("campaign")["T_a"].transform(lambda s: s.ewm(alpha=0.05).mean())
    y = (2 * (df["T_a"] - 20) + 3 * (lagged - 20) + 0.5 * (df["T_b"] - 20) ** 2
         + rng.normal(0, 0.02, len(df))).to_numpy()
    camp = df["campaign"].to_numpy(object)
    return Problem(df[["T_a", "T_b"]], y, df[["time", "T_a", "T_b"]], camp, camp, "E_X",
                   scheme="forward", n_blocks=8, reference="none")


def test_a_penalised_cv_result_holds_only_its_own_rows():
    p = heated_problem()
    cv = CrossValidator(p, MLR())
    effects = [Effect(kind="dynamics", transform="lowpass_inputs", tau_s=1200.0),
               Effect(kind="nonlinear", transform="square", column="T_b")]
    result = cv.run(["T_a", "T_b"], effects)
    assert result.alpha is not None                  # the penalty path ran (several columns)
    kept = result.prediction if result.prediction.base is None else result.prediction.base
    assert kept.nbytes == len(p.y) * result.prediction.itemsize
