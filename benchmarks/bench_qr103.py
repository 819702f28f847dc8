"""The C's POD operator of a solved set by a QR of the basis rows, not the normal equations
(issue 34; stop 103, qr103; dep103's next step).

dep101 / dep103 (bench_dep101.py, bench_dep103.py, KEPT through a rounding clause) held a drop,
its return and a dropout beside two or more out as served, but the C (``watch_c.py``
``mon_operator``) and its mirror (``export/watch.py`` ``_solved_operator``) solve a set the code
does not hold by the Cholesky ``L`` of ``G = Phi_a^T Phi_a``: the normal system squares the
condition of ``Phi_a``.  On square, ill-conditioned sets the operator parts from served's
``pod.operator`` (``np.linalg.pinv(phi[active])``) and so do the corrections: dep103's seen
pt9890 far ``third`` 1.05e-6 µm (three out, cond 2.05e4, M 1.4e-4 apart), 7 of 60 seen cases past
1e-9 µm; dep101's pt9910 near 2.6e-9..3.3e-9 (cond 1496).

RULE (``mon_operator`` and ``_solved_operator``, the same arithmetic in the same order): ``R`` of a
modified Gram-Schmidt QR of ``Phi_a`` (s x r, worked in the rows of the fixed array ``W``;
``R^T R = G``, ``G`` never formed), ``w_k = R^-T phi_k`` (forward substitution, as ``L^-1 phi_k``
was), ``M[k, m] = w_k . w_m``, the leverage ``w_k . w_k``.  The refusal keeps its meaning:
Cholesky's pivot at ``p`` IS ``R[p, p]^2`` (the squared part of column ``p`` the earlier columns
do not span), and it refused where that was not above 1e-12 times ``G[p, p]`` (column ``p``'s
squared norm over the set); the QR refuses where ``R[p, p]^2`` (its squared norm of the residual
column) is not above 1e-12 times the same ``G[p, p]``: in exact arithmetic the same sets.  Fixed
arrays (``R``, ``g`` replace ``G``, ``L``), no allocation; about ``2 s r^2`` multiply-adds for the
QR where ``G`` and ``L`` took ``s r^2 + r^3 / 6``, at a change of the out set only.  No key; the
ST (no solve of its own) untouched.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_qr103.py compare BEFORE_LOG AFTER_LOG
    python benchmarks/bench_qr103.py cpu ROOT RECORD REPEATS
    python benchmarks/bench_qr103.py solves ROOT RECORD [RECORD ...]

``compare``: two logs of the same bench command (bench_dep103 ``returns``, bench_dep101
``drops``, bench_dep100b ``planted``, bench_wires100 ``swaps``, bench_dep99 ``card``), main's then
the rule's, line by line (``CPU`` lines aside): the lines whose text differs, each line's
``max|C - served|`` (µm), ``max|compiled - mirror|`` and ``max|M C - served|`` before -> after,
those that moved by more than 1e-9 µm and whether toward served; then the count of lines, of
identical lines, of lines closer / farther, and the largest ``max|C - served|`` and
``max|compiled - mirror|`` after.  ``cpu``: bench_dep103's ``third`` case ``far`` of ``RECORD``
(the pair and ``c`` out: the solved set), the C (``stream``, built into ``ROOT/cpu/RECORD``
by this tree) fed its rows ``REPEATS`` times: CPU (user + sys of the children) per row.
``solves`` (a trace, written after the rule's seen run; not part of the bar): per case of
``RECORD`` (bench_wires99's ``far`` / ``near``) and out set (the pair; with ``c``), the set's
M by served's pinv, this tree's solve, the Cholesky of 8afba209 and two Householder QRs (numpy),
each against the exact M (mpmath, 40 digits): max|M - exact| and the error of the out sensors
rebuilt from the readings (less the first row's) from the fault row on.

BAR (written and committed BEFORE any measurement of the rule on a seen case; no fresh seed: the
brief's seen cases only.  main = ``git archive 8afba209 src``; its numbers are dep103's logs
(``/tmp/dep103/log``: its final returns run and its D2 rule runs, on 68156a2b whose ``watch.py``,
``watch_c.py`` and ``pod.py`` are 8afba209's), the rule's from copies of the same roots
(``data``, ``reports``; no ``c``: every stream built anew by the rule's tree))
---
Q1. Every seen ``back`` / ``beside`` / ``third`` case of bench_dep103 ``returns`` and ``drop``
    case of bench_dep101 ``drops`` (the 10 records: pt9851 pt9890 tr9891 cr9892 pt9910 tr9911
    cr9912 pt9950 tr9951 cr9952): max|C - served| <= 1e-9 µm (main <= 1.05e-6), 0 rows past it,
    0 rows ``NOT_IN_CODE``, compiled C = mirror <= 1e-12 µm.  No rounding clause.
Q2. Every other line of dep103's D2 benches (bench_dep101 ``drops`` on the 10, bench_dep100b
    ``planted`` dl9934 sw9935 cr9936, bench_wires100 ``swaps`` pt9851, bench_dep99 ``card`` tr9828
    tr9873): its max|C - served| the same as main's or closer to served (``compare``); each line
    that moves by more than 1e-9 µm listed.  A set main solved not refused by the rule, nor the
    reverse (a ``MISSING_SECOND`` / ``the set not solved`` that appears or goes is listed).
Q3. The healthy frames of every record above: 0 rows flagged, max|C - served| 0 µm.
Q4. tests/shell/test_export.py (PARSED_DIGEST unchanged: the ST is not touched) and
    test_export_{wires100,dep100,dep99b,freezeu100,cmon85,cmon86,cmon88,cmon89,cmon93,step99}.py
    pass on the rule's tree.
Q5. ``cpu`` on pt9890 (a seen record of 2640 rows, its ``third`` set cond 2.05e4), REPEATS 20,
    under main's tree and the rule's, alternately, twice each: the rule's per-row CPU (the lower
    of its two) not above 1.2 x main's (the lower of its two).
KEPT if Q1-Q5 hold and a sharpened existing test (tests/shell/test_export_wires100.py, its
fixture) fails on 8afba209 and passes here, <= 1 s CPU added; else REFUSED
(benchmarks/qr103_rule.patch, src as 8afba209), the numbers kept here.

SCORED (bar ea7a33ed, unchanged; 2026-12-07 00:53-01:11 UTC, load 4-10 on 2 cores; main = dep103's
logs, /tmp/dep103/log; the rule's runs from copies of the same roots, /tmp/qr103/R*, logs
/tmp/qr103/log).  THE BAR'S RULE (one Gram-Schmidt pass, ``w_k = R^-T phi_k`` for every row) FAILS
Q1.  max|C - served| (µm) of the seen cases past 1e-9, main -> rule::

  pt9890 far  beside / third (three out, cond 2.05e4)   6.74e-7 / 1.05e-6 -> 1.03e-6 / 1.32e-6
  pt9910 far  beside / third (three out, cond 1971)     2.58e-8 / 3.7e-8  -> 3.64e-8 / 3.68e-8
  pt9910 near back / third (the pair out, cond 1496)    2.61e-9 / 2.35e-9 -> 1.44e-9 / 1.44e-9
  pt9910 near drop (bench_dep101)                       3.29e-9           -> 1.59e-9
  pt9851 near beside / third                            1.16e-9 / 1.2e-9  -> 2.98e-11 / 7.25e-11

0 rows ``NOT_IN_CODE``; compiled - mirror <= 4.99e-11 (4 of 60 ``returns`` cases past 1e-12, as
main's 4, <= 7.32e-11).  The set's M came 5000 x closer to served's (pt9890 far three out:
max|M C - served| 1.4e-4 -> 2.7e-8) but the corrections did not.  ``solves`` (the trace, after this
run) says why: the rows in, ``R^-T phi_k``, give a Q no more orthogonal than one Gram-Schmidt
pass's (eps cond), and M's error then lies along the readings: the out sensors rebuilt from
pt9890's readings are 1.4e-6 °C from exact (served's pinv 1.6e-9, 8afba209's Cholesky 1.2e-5),
the same with a Householder R (1.7e-6); with Householder's Q kept for the rows in, 3.8e-10.
Q2 met (no line farther by > 1e-9 µm; drops pt9910 near 3.29e-9 -> 1.59e-9 closer; planted <=
4.65e-12, swaps / card changes < 4e-12 µm, read by eye: ``compare`` reads no ``kelvin`` / ``drop's``
field); Q3 met (10 healthy frames 0 flags, 0 µm); Q4 not run on it; Q5 met (``cpu`` pt9890, the
lower of two: main 3.92, rule 3.94 µs per row).  VERDICT: REFUSED (benchmarks/qr103_rule.patch:
src and the cmon85 test of ea7a33ed / 09b7a1a6; src back to 8afba209).

RULE 2, built AFTER the bar's rule was measured on these very cases (so not the bar's rule, not
called kept; benchmarks/qr103_rule2.patch, a6a53721): Gram-Schmidt twice (each column projected
off the earlier ones two times), Q's rows kept for the sensors in, ``R^-T phi_k`` for those out;
the same refusal test.  ``solves``: pt9890 far three out rebuilt 8.6e-10 °C from exact (M 4.9e-9).
The bar's clauses on it (logs ``*_R2.log``, roots /tmp/qr103/S*):
Q1 C - served: every seen case <= 1.12e-10 µm (pt9890 far third; beside 4.29e-11, pt9910 far
   <= 2.9e-11, pt9910 near <= 1.55e-11, drops <= 1.84e-11), 0 rows past 1e-9, 0 ``NOT_IN_CODE``;
   compiled = mirror NOT <= 1e-12: 4 ``returns`` cases 4.97e-12..7.32e-11 (pt9890 / pt9910 far
   beside / third) and 1 drop 1.17e-12 -- main had the same cases past it, 7.32e-11 the same
   number: outside the solve.  Not traced to the row; a candidate measured: on pt9890's three-out
   set (max|M| 1.47e4) numpy's ``D @ M.T`` (the mirror's products, e.g. ``watch.py`` l.644) and
   the C's sequential sums part by up to 6.6e-11 °C in the out sensors.
Q2 met: 8 ``returns`` lines closer by > 1e-9, 0 farther; drops pt9910 near 3.29e-9 -> 1.84e-11;
   planted <= 5.61e-12, swaps / card changes < 4e-12 µm; no refusal appears or goes.
Q3 met.  Q4 met: 52 passed (the 11 modules, 274 s wall; PYTHONPATH = a6a53721's src).
Q5 met: 4.00 µs per row against main's 3.92 (1.02 x).
Tests of both patches: test_export_cmon85's square sets (20 drawn, < 2 eps cond max|M| from served's
pinv) fail on 8afba209 (2.79e-10 against a bound of 1.0e-10 on a drawn set), pass on both rules;
0.05 s call.  The wires100 / dep101 cases could not be sharpened to fail on 8afba209: their sets
have cond 1.5-1.6 (the test machine's 3 modes), C = served 2e-14 on main already.
"""

from __future__ import annotations

import re
import resource
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests"), str(HERE.parent / "tests" / "shell")]
from _cli import run_commands  # noqa: E402

APART = 1e-9     # µm: C and served alike (bench_dep101's)
FIELDS = ("max|C - served|", "max|compiled - mirror|", "max|M C - served|")
NUMBER = r" ([-+0-9.eE]+|nan|inf)"


def _numbers(line: str) -> dict[str, list[float]]:
    """Each of :data:`FIELDS` in ``line``: the numbers printed after it, in order."""
    return {f: [float(x) for x in re.findall(re.escape(f) + NUMBER, line)] for f in FIELDS}


def _lines(path: str) -> list[str]:
    return [line.rstrip("\n") for line in Path(path).read_text().splitlines()
            if line.strip() and not line.startswith("CPU")]


def compare(before: str, after: str) -> None:
    """The ``compare`` lines (module doc)."""
    old, new = _lines(before), _lines(after)
    if len(old) != len(new):
        print(f"line counts differ: {len(old)} before, {len(new)} after")
    same = closer = farther = 0
    worst, compiled = 0.0, 0.0
    for i, (a, b) in enumerate(zip(old, new)):
        na, nb = _numbers(a), _numbers(b)
        served = list(zip(na[FIELDS[0]], nb[FIELDS[0]]))
        worst = max([worst, *nb[FIELDS[0]]])
        compiled = max([compiled, *nb[FIELDS[1]]])
        if a == b:
            same += 1
            continue
        moved = [(x, y) for x, y in served if abs(y - x) > APART]
        closer += any(y < x for x, y in moved)
        farther += any(y > x for x, y in moved)
        refused = [w for w in ("MISSING_SECOND", "the set not solved") if (w in a) != (w in b)]
        print(f"line {i + 1}: {b[:70].strip()}")
        for f in FIELDS:
            if na[f] != nb[f]:
                print(f"    {f} {' '.join(f'{x:.3g}' for x in na[f])} -> "
                      f"{' '.join(f'{y:.3g}' for y in nb[f])}")
        if moved:
            print(f"    moved past {APART:g} µm: " + ", ".join(
                f"{x:.3g} -> {y:.3g} ({'closer' if y < x else 'FARTHER'})" for x, y in moved))
        if refused:
            print(f"    refusal changed: {', '.join(refused)}")
    print(f"{len(new)} lines, {same} identical, {closer} moved closer to served by > {APART:g} µm, "
          f"{farther} farther; after: max|C - served| {worst:.3g} µm, max|compiled - mirror| "
          f"{compiled:.3g} µm")


def cpu(root: str, record: str, repeats: str) -> None:
    """The ``cpu`` line (module doc)."""
    from bench_dep101 import FRESH, SEEN
    from bench_dep103 import planted
    from bench_wires99 import _cell, framed_cases
    from bench_wires100 import _compiled

    base = Path(root).resolve()
    deployed, ss, frame, _, start, _ = _cell(base, record, {**SEEN, **FRESH})
    names = list(deployed.monitor.names)
    kind, (a, b), _, _ = next(iter(framed_cases(frame, start, deployed.monitor)))
    c = next(n for n in names if n not in (a, b))
    dropped, _ = planted(frame, start, (a, b), c, "third")
    folder = base / "cpu" / record
    _compiled(folder, deployed, ss, dropped)        # builds stream once
    text = dropped[["time", *ss.inputs]].to_csv(index=False, float_format="%.17g")
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    for _ in range(int(repeats)):
        subprocess.run([str(folder / "stream")], input=text, text=True, capture_output=True,
                       check=True)
    now = resource.getrusage(resource.RUSAGE_CHILDREN)
    seconds = now.ru_utime + now.ru_stime - used.ru_utime - used.ru_stime
    print(f"{record} {kind} third ({a} + {b}, {c} out): {len(dropped)} rows x {repeats}: "
          f"{seconds:.3f} s CPU, {seconds / len(dropped) / int(repeats) * 1e6:.2f} µs per row")


def _solves(phi, active, served) -> dict:
    """M of the set ``active`` (its columns) by each solve :func:`solves` compares."""
    import numpy as np

    from thermocomp.apps.deploy.export.watch import _solved_operator

    r = min(phi.shape[1], int(active.sum()))
    P, Pa = phi[:, :r], phi[active][:, :r]
    q, R = np.linalg.qr(Pa)                                   # Householder (LAPACK)
    outside = np.linalg.solve(R.T, P.T).T                     # w_k = R^-T phi_k, every row
    L = np.linalg.cholesky(Pa.T @ Pa)
    tree = _solved_operator(phi.tobytes(), phi.shape, active.tobytes())
    return {"served (pinv)": served,
            "this tree's C / mirror": None if tree is None else tree[0][:, active],
            "Cholesky, L^-1 phi_k (8afba209)": np.linalg.solve(L, P.T).T @ np.linalg.solve(L, Pa.T),
            "Householder, R^-T phi_k every row": outside @ np.linalg.solve(R.T, Pa.T),
            "Householder, R^-T phi_k, Q's rows in": outside @ q.T}


def solves(root: str, *records: str) -> None:
    """The ``solves`` lines (module doc)."""
    import mpmath
    import numpy as np
    from bench_dep101 import FRESH, SEEN
    from bench_wires99 import _cell, framed_cases

    mpmath.mp.dps = 40
    base = Path(root).resolve()
    for record in records:
        deployed, ss, frame, _, start, _ = _cell(base, record, {**SEEN, **FRESH})
        mon, names = deployed.monitor, list(deployed.monitor.names)
        phi = np.asarray(ss.monitor["basis"], float)
        T = frame[names].to_numpy(float)
        D = T[start:] - T[0]
        for kind, (a, b), _, _ in framed_cases(frame, start, mon):
            c = next(n for n in names if n not in (a, b))
            for out in ([a, b], [a, b, c]):
                active = ~np.isin(np.asarray(names), out)
                r = min(phi.shape[1], int(active.sum()))
                A = mpmath.matrix(phi[active][:, :r].tolist())
                exact = mpmath.matrix(phi[:, :r].tolist()) * (A.T * A) ** -1 * A.T
                want = np.array([[float(mpmath.fsum(exact[k, j] * mpmath.mpf(float(d[j]))
                                                    for j in range(int(active.sum()))))
                                  for k in np.flatnonzero(~active)] for d in D[:, active]])
                M_exact = np.array(exact.tolist(), dtype=float)
                print(f"{record} {kind:<4} {' + '.join(out)} out: cond "
                      f"{np.linalg.cond(phi[active][:, :r]):.3g}", flush=True)
                for name, M in _solves(phi, active, mon._operator(active)[0]).items():
                    if M is None:
                        print(f"    {name:<38} the set not solved")
                        continue
                    print(f"    {name:<38} max|M - exact| {np.abs(M - M_exact).max():.2g}, the out "
                          f"sensors rebuilt from the fault row on: max|error| "
                          f"{np.abs(D[:, active] @ M[~active].T - want).max():.2g} °C", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"compare": compare, "cpu": cpu, "solves": solves}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
