"""Why diagnose misses the planted position on 9440 and 8969 (stop 92, diag92b; issue 34:
"diagnose accepts a planted position effect with 8 train campaigns"; bench_diag91b's "left").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag92b.py trace CASE...   # E_Y's rounds, every gate, the guard's view

``trace``: each CASE (``SEED`` or ``planted:SEED``, ``clean:SEED``, ``lag:SEED``: bench_diag86's
``draw``, 12 campaigns, every 3rd test, 8 train; ``few:4004``: test_diagnose_few's clean draw),
E_Y diagnosed with MLR, ``max_effects=2``, as bench_diag91b runs it.  Per round: the test blocks
and the smallest p they can reach, then every evaluated candidate ranked by CV gain with its
gain %, gain % within the held-out campaigns, p, p_fam, p_margin and whether it clears the bar;
the position candidate (an interaction on S_pos_Y) is marked ``<-- position``.  The train side
only is read to say which gate refuses the position: the test figures are printed, never used.

No rule was scored: the fresh seeds 9486-9495 were not run (a trace, no rule to score), so no bar.

Traced (2026-12-05, main 2b918bfd's src; train side only; ``trace 9440 8969 few:4004 8966 8968``)
----------------------------------------------------------------------------------------------
planted:9440 E_Y (test 4.1717, nothing taken): round 1 on 62 blocks of 8 samples (smallest p
5e-5: not the floor).  The position ranks FIRST (S_pos_Y x the inputs' rises: CV gain 30.7 %,
p 0.031, p_fam 0.389, p_margin 0.058; S_pos_Y x T_box2 second, 20.2 %, p_fam 0.33); no lag
ranks above it and none clears either.  It is refused by p_fam (0.39 against 0.01): its gain
lies in ONE train campaign, K11 giving 41.7 of the 51.9 points of train loss it removes (K08
5.8, the other six -0.2 .. 2.8), so the 62 blocks' gains are a few large ones among noise and
the sign-flip sees some 8 units.  The guard plays no part (member shares <= 0.14 per sample).
A power problem of the DESIGN (one campaign excites the effect), not of the blocks.

planted:8969 E_Y (test 5.0569, nothing taken): round 1 on 8 blocks (one per campaign, smallest
p 1/256).  The position ranks first (S_pos_Y x T_box1 over T_amb: 50.5 %, p 2/256, p_fam 3/256
= 0.0117, p_margin 0.0078); refused by p_fam, by 0.0017 over alpha 0.01: the family-wise FLOOR
of 8 units (three T_motor lags reach p 1/256 beside it).  The 8 blocks are not the guard (no
member's per-sample share > 0.32) but the family's longest decorrelation length: S_pos_Y raw's
gain takes 51 samples (the residual's blocks 74; the position members 32-33, the lags 30-31),
one block per campaign.  Here too K05 gives 51.6 of the position's ~75 points removed.

The guard's share on the blocks' mean gains (bench_diag91b's "not measured"; blocks of the
member's own decorrelation length): 4004's offset lags read 0.405 / 0.488 (per sample 0.132 /
0.176), so a 0.4 threshold on blocks' means would single them out -- but it would also fire on
the wins: 8968's round-1 position members read 0.343 / 0.563 and S_pos_Y raw 0.610 (8966's
0.119 / 0.144 / 0.170, its lags 0.22-0.54), and 8969's position 0.80.  Means of L samples lift
every share (the within-campaign noise shrinks by L), so the blocks'-mean share separates
nothing at any threshold between 4004 (0.488) and 8968 (0.563, 0.610): a guard on it would
return 8968 to 9 blocks and lose its win (4.9939 -> 2.2098 on main today, -55.7 %; not run
as a rule: read off the trace).

Which campaign: in both draws the one carrying the gain is the only train campaign held at a
constant 6000 rpm (9440 K11, 7.7 h; 8969 K05, 7.5 h; the manifests): the planted position term
rides on the thermal rise, largest there, so the other seven train campaigns hold little of it.

Verdict: TRACED, no rule.  Both misses are a position whose train gain sits in one campaign of
8: 9440 refused at p_fam 0.39 on 62 fine blocks (power), 8969 at p_fam 0.0117 on 8 (the floor).
CPU of ``trace``: 2-3 s per draw.
"""

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402


def _is_position(ev) -> bool:
    return (ev.effect.kind == "interaction"
            and "S_pos_Y" in f"{ev.effect.column} {ev.effect.other}")


def _fmt(x) -> str:
    return "-" if x is None else f"{x:.4g}"


def _block_means(gain, campaigns, ok, length: int):
    """Mean ``gain`` of each run of ``length`` scored samples within a campaign, and its campaign."""
    means, labels = [], []
    for c in np.unique(campaigns[ok].astype(str)):
        idx = np.flatnonzero(ok & (campaigns.astype(str) == c))
        for start in range(0, idx.size - length + 1, length):
            means.append(gain[idx[start:start + length]].mean())
            labels.append(c)
    return np.array(means), np.array(labels, dtype=object)


def _guard_log(log: list):
    """Wrap ``Search._gain_length``'s caller: log each family member's between-campaign share of
    its per-sample gain, the same share of its blocks' mean gains (bench_diag91b's "not
    measured"), its decorrelation length and the residual's block length."""
    from thermocomp.apps.diagnose.search import Search
    from thermocomp.core.model_selection.blocks import between_campaign_share, decorrelation_length

    original = Search._recut_on_gains

    def recut(self, evals, current):
        p = self.problem
        camp = np.asarray(p.campaigns, dtype=object)
        ok = np.asarray(p.validated, bool) & np.isfinite(current.residual)
        loss = current.residual ** 2
        for ev in evals:
            if ev.control or ev.effect.transform == "remove" or p.block_samples is None:
                continue
            gain = loss - ev.result.residual ** 2
            length = decorrelation_length(gain, p.campaigns, p.validated, p.held_out)
            bm, bl = _block_means(gain, camp, ok, max(int(length), 1))
            log.append({"title": ev.effect.title, "share": between_campaign_share(gain, camp, ok),
                        "share_blocks": between_campaign_share(bm, bl, np.ones(bm.size, bool)),
                        "length": int(length), "residual_blocks": int(p.block_samples),
                        "per_campaign_pct": {str(c): round(100 * float(
                            gain[ok & (camp.astype(str) == str(c))].sum() / loss[ok].sum()), 1)
                            for c in np.unique(camp[ok].astype(str))}})
        return original(self, evals, current)

    Search._recut_on_gains = recut


def trace(*cases: str) -> None:
    """Each planted SEED's E_Y rounds: every evaluated candidate's gates (module doc)."""
    from bench_diag86 import draw

    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.apps.diagnose.cv import smallest_p
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    log: list = []
    _guard_log(log)
    for case in cases:
        kind, _, seed = case.rpartition(":")
        if kind == "few":   # test_diagnose_few's clean draw (bench_diag91b's few:4004)
            from test_diagnose_few import few
            ds = few(None, int(seed))[0]
        else:
            ds = draw(kind or "planted", int(seed), 12)
        log.clear()
        d = diagnose(ds, Compensator(MLR()), targets=["E_Y"], options=SearchOptions(max_effects=2))
        x = d.targets["E_Y"]
        j = d.to_json("E_Y")
        print(f"{case} E_Y test {j['before']['test_rmse']:.4f} -> "
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
        print("  the guard's view of each family member (every round, in order): share of the "
              "per-sample gain between campaigns | of its blocks' means | decorrelation length / "
              "residual's blocks | each campaign's share of the round's train loss removed (%)")
        for g in log:
            print(f"    {g['title'][:58]:58s} {g['share']:.3f} | {g['share_blocks']:.3f} | "
                  f"{g['length']} / {g['residual_blocks']} | {g['per_campaign_pct']}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
