"""The docs as a stranger reads them (stop 107, audit107b; issue 34): every shell command shown in
README.md and docs/ (install, own-data, cli, models, evaluation, sweeps, diagnose, monitoring,
to-the-machine, dvc, volumetric, simulation; not docs/measured/), run as written, in page order,
in a fresh clone of this tree at BASE, and what it prints or writes held to what the page says.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_audit107b.py list                 # every command and its verdict rule
    python benchmarks/bench_audit107b.py walk CLONE [ID ...]  # run them (or some) in CLONE

``list``: :data:`COMMANDS`, one line each: id, page:line, run / skipped (and why), the command.
``walk``: CLONE a ``git clone`` of this tree (made where missing) whose ``.venv/bin`` holds
bench_audit97's shims (the shared venv's python on the clone's ``src``; nothing installed, the
venv reused: install.md's block is not run); each command of :data:`COMMANDS` run by ``bash -euo
pipefail`` in CLONE, the venv not activated, no PYTHONPATH of the caller; per command its exit,
CPU (user + sys of its children) and each check of what the page says (a regex on what it
printed, a file it writes, a key of a JSON it writes).  A placeholder the page leaves open
(``<file>``, ``<family>``, a seed) is filled and said; a seed only from 10141-10143.  The twin's
and the server's ports are moved off the written ones (other helpers share the machine).

BAR (written and committed BEFORE any command was run)
-----------------------------------------------------
B1. Every command the pages show as one to run is in :data:`COMMANDS` with its verdict: OK (exit
    0, or 2 where the page says it refuses, and every check of what the page says it prints or
    writes met), BREAK (a command that fails as written, or prints / writes not what the page
    says: an override, key, file or number stated as today's output that the code no longer
    has), or SKIPPED with the reason (a synopsis, a name in prose, marked long by its page).
B2. Every BREAK mended (the docs or the code, whichever is wrong; where the code was wrong a
    cheap test failing on BASE, in tests/test_docs*.py where one fits) and its command run again
    passing, or named as left with the reason.
Dated measurements ("measured 2026-12-01 ...") are not held to today's output.
"""
