"""diagnose's bar on held-out runs re-referenced at their first samples (issue 34; stop 65, diagref65).

Usage::

    python benchmarks/bench_remeasure62.py write ROOT              # the records (once)
    python benchmarks/bench_remeasure62.py diagnose ROOT           # the shipped rows (shipped src)
    python benchmarks/bench_diagref65.py run ROOT [GROUP ...]      # the same cases, the rule in src
    python benchmarks/bench_diagref65.py score ROOT                # the bar: both against each other

``run`` is ``bench_remeasure62``'s diagnose runner (``diagnose_rows``: the memory bench's 41 cases and
12 machines, bench_diagnose_few's 8 other planted seeds, the 10 fresh grinders, the 20 null draws,
the jig grinder; 92 cases, 139 case x target) with the src this branch ships, rows to
ROOT/diagref65.jsonl with their CPU s (user + sys); the shipped rows are ROOT/diagnose.jsonl, written by
the same runner from an archive of the base commit's tree.  ``score`` prints bench_remeasure62's
table of the new rows, its ``compare`` of every case x target that changed, and the bar.  Nothing
chooses on the test split: it is only scored.

The rule (written and committed before anything was scored; not tuned afterwards)
------------------------------------------------------------------------------------
bench_remeasure62 (step 2) traced diagnose's three grinder harms (null:3 +17.8 %, fresh 5682
+7.4 %, grinder-nocoolant +4.7 %) to the first sample's noise: with ``reference=first_sample`` a
held-out run's label is ``E(t) + n(t) - E(t0) - n(t0)``, ``n(t0)`` an offset of the whole run
that a candidate can seem to explain.  Labels referenced at the second sample instead collapsed
those CV gains but lost vendor5's real lag and 5687's lag: one other draw of the noise.  The rule
here averages it instead (autorep65's mechanism, one for auto and diagnose): where diagnose's CV
holds out whole campaigns (``diagnose.cv`` campaigns scheme, each CV unit's rows exactly one
campaign's rows) whose labels are referenced to their first sample (the unit's first held-out,
measured label exactly 0, as autorep65 detects it), the squared error of the base and of every
candidate at each held-out row of that unit is ``rereferenced_squares``'s
(``thermocomp.core.models.blend``, reused): the mean over ``j < k`` of ``(r(t) - r(t_j))^2``,
``t_j`` the unit's j-th measured held-out row, ``k = min(10, max(1, floor(0.05 n)))``.  Those
squares make ``CVResult``'s ``rmse`` (so the gain and its %, the cv_rmse reported), ``unit_mse``
(``choose``'s one-standard-error rule), ``block_mse`` (the sign-flip p, the family-wise max-T of
``_family_bar``, the margin p, the gain's lower bounds) and ``in_range_rmse`` (the gain where no
fold extrapolates): every statistic ``_clears`` and ``choose`` read.  Unchanged: the residual
itself (screening, figures, the test blocks' length), the ridge penalty chosen per candidate
(least CV error on the plain squares, and the deployed one-standard-error penalty), forward
chaining over one record / time blocks of one campaign (a unit that is not a whole campaign),
``reference=none`` and any unit whose first held-out label is not 0 (a late first probe).

Adoption bar (written before scoring), the new rows against the shipped ones over all 139 case x
target: (1) the case x target whose test RMSE ends > 2 % worse than before diagnose must fall
(bench_remeasure62 shipped 4 of 139); (2) planted found (the planted effect accepted first) must
not fall (19 of 23); (3) clean + null cases accepting anything must not rise (1 of 44); (4) no case
x target may end > 2 % worse than its shipped ``after``.  All four: adopted (src, a test failing on
the old code, docs/diagnose.md); else refused (this bench and a docs/diagnose.md paragraph with the
numbers, src reverted).  CPU of both runs reported.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import bench_remeasure62 as rm62  # noqa: E402


def bar(shipped: list[dict], new: list[dict]) -> list[str]:
    """The four counts of the bar, shipped -> new, and whether each holds."""
    def counts(rows):
        worse, clean, clean_n, found, planted_n = [], [], 0, 0, 0
        for r in rows:
            kind = r["case"].split(":")[0]
            for t, o in r["targets"].items():
                before, after = o["test_rmse"]
                worse += [f"{r['case']} {t}"] if after > 1.02 * before else []
                if kind == "planted":
                    planted_n += 1
                    found += bool(o.get("right_first"))
            if kind in ("clean", "null"):
                clean_n += 1
                clean += [r["case"]] if any(o["accepted"] for o in r["targets"].values()) else []
        return worse, clean, clean_n, found, planted_n

    (w0, c0, cn, f0, pn), (w1, c1, _, f1, _) = counts(shipped), counts(new)
    against = [f"{b['case']} {t} {rm62._pct(a['targets'][t]['test_rmse'][1], o['test_rmse'][1]):+.1f} %"
               for b, a in zip(shipped, new) for t, o in b["targets"].items()
               if a["targets"][t]["test_rmse"][1] > 1.02 * o["test_rmse"][1]]
    assert [r["case"] for r in shipped] == [r["case"] for r in new]
    checks = [(f"(1) > 2 % worse than before diagnose {len(w0)} -> {len(w1)}: " + ", ".join(w1),
               len(w1) < len(w0)),
              (f"(2) planted found {f0} -> {f1} of {pn}", f1 >= f0),
              (f"(3) clean + null accepting {len(c0)} -> {len(c1)} of {cn}: " + ", ".join(c1),
               len(c1) <= len(c0)),
              (f"(4) > 2 % worse than the shipped after: {len(against)}: " + ", ".join(against),
               not against)]
    lines = [f"{text} [{'holds' if ok else 'FAILS'}]" for text, ok in checks]
    lines.append("bar: " + ("PASSES" if all(ok for _, ok in checks) else "FAILS"))
    return lines


def main(argv: list[str]) -> int:
    what, root, rest = argv[0], Path(argv[1]).resolve(), argv[2:]
    if what == "run":
        groups = rest or ["cases", "few", "fresh", "null", "jig"]
        rm62.measure(root / "diagref65.jsonl", rm62.diagnose_rows(root, groups))
    elif what == "score":
        shipped, new = rm62._read(root / "diagnose.jsonl"), rm62._read(root / "diagref65.jsonl")
        print(rm62._wrapped(["shipped"] + ["  " + s for s in rm62.diagnose_table(shipped)[-4:]]))
        print(rm62._wrapped(["rule"] + ["  " + s for s in rm62.diagnose_table(new)]))
        print(rm62._wrapped(["changed"] + ["  " + s for s in rm62.compare(shipped, new)]))
        print(rm62._wrapped(bar(shipped, new)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
