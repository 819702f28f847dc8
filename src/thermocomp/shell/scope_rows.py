"""``python -m thermocomp.shell.scope_rows EXPORT.csv [overrides]`` (lab77): kept as an alias of
``thermocomp rows EXPORT.csv [overrides]`` (lab78, :mod:`.stages.rows`), the one command that
writes any file the reader takes as the rows the exported ``stream.c`` reads, now under the
model's contract names (lab77's module wrote a Scope export's own headers)."""

from __future__ import annotations

import sys


def main(argv: list[str] | None = None) -> int:
    """``thermocomp rows`` with ``argv`` (the command line's when None); its exit status."""
    from .cli import main as thermocomp

    return thermocomp(["rows", *(sys.argv[1:] if argv is None else argv)])


if __name__ == "__main__":
    sys.exit(main())
