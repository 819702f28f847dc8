"""A sensor no other predicts, excluded for explaining the others' errors, in the exported C
(cmon82c, issue 34): the compiled code's corrections against the served adaptive model's.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_cmon82c.py blind [ROOT] [SEEDS] \
        [MODEL] [KINDS] [SIM] [FALLBACKS]

As bench_cmon82b's ``states`` (its record, its columns), on fresh seeds (default 8421-8430, not
used before) of ``column_moving_source`` into ``ROOT`` (default ``/tmp/cmon82c-bench``); the
found cases of cmon82b (8371, 8375, 8376: the C flagged where the served monitor excluded
``T_front3`` / ``T_amb`` for explaining the others' errors) run apart with SEEDS
``8371,8375,8376``.  FALLBACKS (default ``unobservable``, as deployed): ``monitor.fallbacks``
(``none``: no model fitted without a sensor no other predicts, the model reads it held).
"C before": the same bench with the sources of main at 481c34c6.

This changes no rule of the served monitor: the code is measured against it, so no bar is
written (the C must equal the served corrections, ~1e-9 µm, and the pack keep the rows).

Traced (the served monitor at 481c34c6, surveillance/judgement.py, monitor.py,
readmission.py):

* entry (``_exclude_by_judgement``, before the culprit rule, no new thermal state declared): a
  judged sensor beyond the field's band and ``_explaining`` names an active sensor no other
  predicts whose removal brings every judged sensor within the band (the largest standardised
  residual above every judged one's);
* exclusion (``_exclude(u, by_field=True)``): out, its calm count 0, its return wait a window
  times 2 to its drift exclusions (``MAX_BACKOFF`` at most), ``_explains`` set, ``_since`` the
  sample count (the field may follow it: ``_follow_field`` re-admits it at once as a new
  thermal state); the judgement then runs again in the same sample, the field's band now the
  alarm band (a sensor out by the field);
* hold: the model reads its last reading while it was in (``_last_good``: no other predicts it);
* re-admission (``_pass_once_back``): due after its wait of calm samples, it passes where every
  judged sensor of the trial set (it in) has its leave-one-out error over the whole window
  within its warning band; its jumps while out undone as for any sensor no other predicts.
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import made_folder, run_commands, seed_list  # noqa: E402
from bench_cmon82b import record  # noqa: E402

SEEDS = "8421-8430"
SIM = "column_moving_source"


def blind(root: str = "/tmp/cmon82c-bench", seeds: str = SEEDS, model: str = "mlr",
          kinds: str = "healthy,drift", sim: str = SIM, fallbacks: str = "unobservable") -> None:
    folder = made_folder(root)
    for seed in seed_list(seeds):
        print("\n".join(record(folder, seed, model, tuple(kinds.split(",")), sim,
                               (f"monitor.fallbacks={fallbacks}",))), flush=True)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"blind": blind}, sys.argv[1:] if argv is None else argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
