"""``python -m thermocomp.shell.scope_rows EXPORT.csv > rows.csv`` (extension, lab77): a TwinCAT
Scope CSV export written as the one CSV table the served model reads it as, for the exported
``stream.c`` (which reads a table of rows, and refuses the export naming this command): every
channel on the union of their times, none held, as :mod:`thermocomp.core.io.scope` reads it."""

from __future__ import annotations

import sys
from pathlib import Path

from ..core.io.contract import ContractError
from ..core.io.encoding import detect, text_codec
from ..core.io.scope import SAMPLE_KEY, is_scope, scope_as_csv


def main(argv: list[str] | None = None) -> int:
    """``python -m thermocomp.shell.scope_rows EXPORT.csv > rows.csv``: the export as the CSV table
    the served model reads it as (:func:`scope_as_csv`: ``time`` in UTC where ``StartTime``
    says it, a column per channel, on the union of their times), for the exported ``stream.c``,
    which reads one table of rows (lab77).  Its text UTF-8 or, where it is not, Windows-1252;
    a broken export refused naming file, channel and line, exit 2, nothing written."""
    args = sys.argv[1:] if argv is None else argv
    if len(args) != 1:
        print("thermocomp: error: usage: python -m thermocomp.shell.scope_rows EXPORT.csv", file=sys.stderr)
        return 2
    path = Path(args[0])
    try:
        if not is_scope(path):
            raise ContractError("no TwinCAT Scope export (its first line 'Name<sep>...', a "
                                f"'{SAMPLE_KEY}' row in its head)", file=path)
        text = path.read_bytes().decode(text_codec(detect(path)))
        table = scope_as_csv(text, str(path))
    except (ContractError, OSError) as exc:
        print(f"thermocomp: error: {exc}", file=sys.stderr)
        return 2
    sys.stdout.write(table)
    return 0


if __name__ == "__main__":
    sys.exit(main())
