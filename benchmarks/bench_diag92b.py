"""Why diagnose misses the planted position on 9440 and 8969 (stop 92, diag92b; issue 34:
"diagnose accepts a planted position effect with 8 train campaigns"; bench_diag91b's "left").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag92b.py trace SEED...   # planted draws' E_Y rounds, every gate

``trace``: bench_diag86's planted ``draw`` (12 campaigns, every 3rd test, 8 train) of each SEED,
E_Y diagnosed with MLR, ``max_effects=2``, as bench_diag91b runs it.  Per round: the test blocks
and the smallest p they can reach, then every evaluated candidate ranked by CV gain with its
gain %, gain % within the held-out campaigns, p, p_fam, p_margin and whether it clears the bar;
the position candidate (an interaction on S_pos_Y) is marked ``<-- position``.  The train side
only is read to say which gate refuses the position: the test figures are printed, never used.

Results (measured below) decide the verdict.
"""

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402


def _is_position(ev) -> bool:
    return (ev.effect.kind == "interaction"
            and "S_pos_Y" in f"{ev.effect.column} {ev.effect.other}")


def _fmt(x) -> str:
    return "-" if x is None else f"{x:.4g}"


def trace(*seeds: str) -> None:
    """Each planted SEED's E_Y rounds: every evaluated candidate's gates (module doc)."""
    from bench_diag86 import draw

    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.apps.diagnose.cv import smallest_p
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    for seed in map(int, seeds):
        d = diagnose(draw("planted", seed, 12), Compensator(MLR()), targets=["E_Y"],
                     options=SearchOptions(max_effects=2))
        x = d.targets["E_Y"]
        j = d.to_json("E_Y")
        print(f"planted:{seed} E_Y test {j['before']['test_rmse']:.4f} -> "
              f"{j['after']['test_rmse']:.4f}; accepted {[e.effect.title for e in x.accepted]}")
        for k, rnd in enumerate(x.search.rounds, 1):
            print(f"  round {k}: {rnd.test_blocks} test blocks ({rnd.block_samples} samples), "
                  f"smallest p {smallest_p(rnd.test_blocks):.2g}, {rnd.n_candidates} screened, "
                  f"accepted {rnd.accepted.effect.title if rnd.accepted else None}")
            ranked = sorted(rnd.evaluated, key=lambda e: e.gain, reverse=True)
            for r, ev in enumerate(ranked, 1):
                print(f"    {r:2d} {ev.effect.title[:58]:58s} gain {ev.gain_pct:6.1f} % "
                      f"within {_fmt(ev.gain_pct_within)} rest {_fmt(ev.gain_pct_within_rest)} "
                      f"p {_fmt(ev.p_value)} p_fam {_fmt(ev.p_family)} "
                      f"p_margin {_fmt(ev.p_margin)} clears {ev.clears_bar}"
                      f"{'  <-- position' if _is_position(ev) else ''}"
                      f"{'  (control)' if ev.control else ''}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
