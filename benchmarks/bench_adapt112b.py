"""adapt112b (REFUSED): each target's ``adapt.method=bias`` filter chosen by replaying the training campaigns.

The rule (``benchmarks/adapt112b_rule.patch``, applies to 759e02af; bar ``benchmarks/adapt112b_bar.md``):
each training campaign streamed frozen through the deployed stream of the model refitted on the
other training campaigns (one campaign: three time blocks), the campaigns replayed in order with a
reference every ``adapt.every_s`` and the offset carried across them; per target the least RMSE on
the grid "none" + prior_var_bias {1, 100} x forgetting {0.5, 0.9, 1.0}, "none" under a 2 % gain.

Usage (repository root; BASE_TREE a checkout of 759e02af, RULE_TREE one with the patch applied)::

    python benchmarks/bench_adapt112b.py cut SRC DST         # each test campaign cut in two (adapt111)
    python benchmarks/bench_adapt112b.py pair BASE_TREE RULE_TREE ROOT RECORD [RECORD ...]
    python benchmarks/bench_adapt112b.py planted RULE_TREE ROOT RECORD

``pair`` (bench_adapt112's): ``mlr`` fitted once per record with BASE's tree into ROOT/<record>/model,
replayed with none and bias on both trees.  ``planted`` (after ``pair``, RULE_TREE's code in this
process): the choice, then offline on the frozen test stream as replay streams it, per target none /
BASE's filter (100 um^2, 0.5) / the choice, and the gain on +3 um planted on the first target from the
25 % row of the middle test campaign to its end.

Scored (2026-12-08, 2 cores shared; mlr; test RMSE um, change vs none; replay.json = offline to 1e-9)::

  record   target  none   BASE bias         rule bias         choice (prior, forgetting)
  cut      E_X     0.840  0.924 (+10.1 %)   0.840 (+0.0 %)    none
           E_Y     3.045  3.108 (+2.1 %)    3.102 (+1.9 %)    (1, 0.5)
           E_Z     3.677  3.441 (-6.4 %)    3.677 (+0.0 %)    none
  fl       ch1..5  BASE -43.6/-40.7/-17.2/-20.1/-4.2 %, rule -36.2/-34.9/-21.4/-23.3/-10.2 %, all (1, 0.5)
  s10236   E_X/Y/Z BASE +2.3/-13.0/-22.5 %, rule +0.0/-12.7/-22.5 %    none, (1, 0.5), (100, 0.5)
  s10267   E_X/Y/Z BASE -3.5/-8.2/-33.8 %,  rule +0.8/-9.4/-33.8 %     (100, 0.9), (1, 0.5), (100, 0.5)
  s10268   E_X/Y/Z BASE -1.9/-13.0/-20.0 %, rule -2.7/-13.0/-20.0 %    (1, 0.5), (100, 0.5) x 2
  s10269   E_X/Y/Z BASE -4.7/-15.9/-17.7 %, rule +0.0/-15.9/-17.7 %    none, (100, 0.5) x 2
  planted gain BASE / rule: cut 0.130 / 0.000, fl 0.569 / 0.455 (80 %), s10236 1.767 / 0.000;
  fresh s10267 1.102 / 0.446 (41 %), s10268 2.013 / 2.013, s10269 1.521 / 0.000.

Mean bias/none: seen (11 targets) BASE 0.861, rule 0.855; fresh 10267-10269 (9) BASE 0.868, rule 0.876.
A1 met (worst +1.9 %), A2 fails (>= 60 % on fl only: E_X is "none" on cut and s10236, where the
training replay showed a best gain of 0.4 % and 1.7 %, so a new offset there is not followed), A3
fails on its mean (0.876 > 0.868; no target worse than none by 2 %: met, worst +0.8 %).  CPU (user +
sys): the choice is made where the deployed model is built (replay, promote, export, serve), 0.4-0.8 s
on mlr (16 refits, or 3 blocks for fl); replay bias BASE / rule: cut 3.25, 2.48, 2.43 / 4.26, 2.94,
2.69 s, fl 3.27 / 3.75, s10236 2.80 / 3.55; ``run`` (make run's record) does not make it: 2.27, 2.19 /
2.11, 2.07 s.  C / ST: not done (the patch's export refuses a per-target choice, NotExportable).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import run_commands  # noqa: E402
from bench_adapt112 import cut, pair  # noqa: E402

BASE_FILTER = (100.0, 0.5)     # conf/adapt/default.yaml: prior_var_bias, forgetting


def planted(rule: str, root: str, record: str) -> None:
    """The choice on ``record``'s train split and its test figures, offline (module doc)."""
    import numpy as np

    tree = Path(rule).resolve()
    sys.path.insert(0, str(tree / "src"))
    os.chdir(tree)
    from thermocomp.apps.deploy.adapt_choice import rms_columns, streamed

    from thermocomp.apps.deploy.report import plain, stream_rows
    from thermocomp.core.context import TIME
    from thermocomp.core.continuation import lead_ins
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.cli import _compose
    from thermocomp.shell.source import read_streamed

    name = Path(record).name
    model = Path(root).resolve() / name / "model" / "model.pkl"
    data = "data=fl_thermal" if record == "fl_thermal" else f"data.path={Path(record).resolve()}"
    cfg = _compose([data, "adapt.method=bias", f"replay.model={model}", "track=false"], "replay")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    deployed = deployable_model(cfg, ds, train_ids, str(model), "replay.model")[0]
    choice = deployed.adapt_choice_ or [BASE_FILTER] * len(deployed.targets_)
    comp = plain(deployed).compensator
    leads = lead_ins(comp, ds, test_ids)
    measured = comp.measured({c: ds.campaigns[c] for c in test_ids})
    streams = []
    for c in test_ids:
        df = ds.campaigns[c]
        m = measured[c][list(deployed.targets_)]
        streams.append((stream_rows(deployed, df, c, None, leads.get(c)).y, df[TIME].to_numpy(float),
                        m.to_numpy(float)))

    def adapted(s):
        every = float(cfg.adapt.every_s)
        cols = {k: streamed(s, every, *k, float(cfg.adapt.max_bias_um))[0] for k in {*choice, BASE_FILTER}}
        return cols[BASE_FILTER], np.column_stack([cols[k][:, j] for j, k in enumerate(choice)])

    none = np.concatenate([m - y for y, _, m in streams])
    base, mine = adapted(streams)
    for j, t in enumerate(deployed.targets_):
        n, b, r = (rms_columns(x)[j] for x in (none, base, mine))
        print(f"{name} {t}: none {n:.3f}  BASE {b:.3f} ({100 * (b / n - 1):+.1f} %)  "
              f"rule {r:.3f} ({100 * (r / n - 1):+.1f} %)  choice {choice[j]}")
    middle = len(streams) // 2
    plant = [(y, t, m.copy()) for y, t, m in streams]
    plant[middle][2][len(plant[middle][2]) // 4:, 0] += 3.0
    rows = np.concatenate([np.full(len(y), i) for i, (y, _, _) in enumerate(plant)]) == middle
    p_none = rms_columns(np.concatenate([m - y for y, _, m in plant])[rows])[0]
    p_base, p_mine = (rms_columns(x[rows])[0] for x in adapted(plant))
    print(f"{name} planted +3 um gain: BASE {p_none - p_base:.3f}  rule {p_none - p_mine:.3f}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"cut": cut, "pair": pair, "planted": planted}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
