"""A lab file's independent refusals gathered into one message (refusals100, issue 34; audit100's
finding 2: excel.csv took three tries, its refusals coming one at a time).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_refusals100.py seen ROOT           # R1: audit100's excel.csv (seed 9921)
    python benchmarks/bench_refusals100.py fresh ROOT SEED     # R3: a new lab file (seed 9946)

``seen``: bench_audit100's :func:`~bench_audit100.write_excel` of seed 9921 under ROOT (BOM,
``sep=;``, local stamps over 2026-10-25's repeated hour, umlauts, ``KW`` text, the empty
``Reserve (leer)``); ``init`` with no key; the one suggested line the refusal prints run as
written; then ``run`` per family (mlr, lagbank) on the config it wrote.  Main's tries are
followed too (bench_audit100's :func:`~bench_audit100._init_tries`): the keys and figures compared.
``fresh``: seed SEED's contract file (bench_audit91's ``lab_files``) written as :func:`fresh_file`:
excel.csv's layout, and a new mix of faults chosen before it was made: the repeated hour, TWO
empty columns (``Reserve 1``, ``Reserve 2``), a flux sensor in ``W/m^2`` (no sensor of the
model: a column the naming refuses).  Scored once as ``seen``.

On main (063630e6, after notes100: ``Motor Spindel (Gehäuse)`` is read as a temperature) excel.csv
takes 3 tries: the clock (``data.timezone``, column 'time', data row 781), then the empty
``Reserve (leer)`` (``data.roles.ignore=['Reserve']``), then exit 0.

BAR (written and committed BEFORE seed 9946 was made or any rule measured; the brief's):
R1. excel.csv 9921 (seen) in ONE try: ``init`` with no key exits 2 with one message that names
    every key main's tries needed (``data.timezone=Europe/Berlin`` with column 'time' and row 781,
    ``data.roles.ignore`` with ``Reserve``), each with file, column (row where one is at fault),
    and ONE suggested command line with all keys together; that line, run as written, exits 0
    and writes the same data config as main's last try (the column table and the yaml equal);
    ``run`` mlr / lagbank on it: every test figure = main's 3-try config's to 1e-9 µm (audit100's
    digits were with ``Motor Spindel`` left out, which notes100 since reads; said, not scored).
R2. Every existing refusal test still passes: the test files under tests/core and tests/shell that
    match 'error:' and touch init / core.io (listed with their counts where run), and
    tests/test_lint.py, tests/test_benchmarks_cli.py.
R3. Fresh lab file seed 9946 (the faults above), scored ONCE: ``init`` with no key exits 2 with
    one message naming all its faults' keys; its suggested line run as written exits 0.
R4. A refusal another makes moot stays alone (no time column at all, a file without rows): said
    as main says it.  A test that fails on 063630e6 (< 3 s).
KEPT only if R1-R4 hold; else REFUSED (benchmarks/refusals100_rule.patch, src reverted).
"""
