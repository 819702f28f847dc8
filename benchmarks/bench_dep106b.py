"""A lab's pause as served and as the C does it, through ``connect`` and the registry's C too
(stop 106, dep106b; issue 34).  audit106 (a16ebcdc) made a served session start a campaign at the
model's ``pause_s_`` (``data.runs_at_pauses``) as the reader and ``stream.c`` (``TC_PAUSE_S``) do;
it left (a) ``connect`` (OPC UA) with no pause rule, (b) the registry's C given ``TC_PAUSE_S``
checked by hand only, (c) a served block refused in its part after a pause keeping the part
before it.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dep106b.py lab ROOT          # the fresh lab 10118, cells a-c

``lab``: seed 10118's lab export built as bench_audit106's cell L builds it (bench_audit91's swiss
production campaign, 1441 rows at 60 s, a 3 h gap of rows left out, tab-delimited, bracketed
units, local ISO-8601 stamps across the change to summer time; ``once.tsv``: the copy of a row
deleted), ``init`` with no key (``runs_at_pauses: true``), ``run model=mlr`` on init's config;
then the test rows of the whole record (both runs, the pause between them) through: the served
model as one block from a reset; ``connect`` (the Connection the stage builds) against an
in-process vendor server (tests' ``vendor_machine``, one NC program, its clock the lab's, Double
offset nodes) fed the same rows; the C exported from the registered pyfunc folder, built by
tests/cbuild.py and fed the lab's raw rows; per form the largest |difference| from the C (µm)
and the events at the pause.

BAR (written and committed BEFORE seed 10118 was built; not to move after):
  a. connect across a pause longer than the model's ``pause_s_``: the offsets it writes on every
     row = the served block's corrections = the C's to 1e-9 µm; the pause said in an event of
     connect.json at the first row after it (a campaign from a reset there).
  b. the C exported from a registered model (a pyfunc folder, no record read) carries the
     model's ``TC_PAUSE_S`` (not 0), and fed the raw rows across the pause = served to 1e-9 µm.
  c. a served block refused in its part after a pause leaves the session as it was before the
     block (no half state): the block sent again repaired = the session that never saw the
     refused one, to 1e-9 µm; served, connect and the C agree on what a refusal leaves, or the
     difference is named (not_in_code / the docs).
  Each of a-c has a test failing on c668e59b (or a measured trace that it holds there), <= ~3 s
  CPU each.  Fresh seed 10118 (scored once, after this bar is committed): a and b the same, to
  1e-9 µm.  KEPT where every case holds; else REFUSED (src reverted, the rule kept as a patch).

Scored: (below, after the run)
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE), str(REPO / "tests")]
from _cli import run_commands  # noqa: E402

BASE = "c668e59b"
LAB_SEED = 10118


def lab(root: str) -> None:
    """Cell lab (module doc)."""
    raise NotImplementedError("written after the bar")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"lab": lab}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
