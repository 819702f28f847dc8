"""The suffixes of a lab's files read as delimited text (one place for the choice: the manifest
lists a folder's runs by them, the first timestamp of a file is read by them)."""

from __future__ import annotations

from pathlib import Path

from .jsonlines import JSON_LINES_SUFFIXES

# a one-file record may also carry a logger's text suffix: read as CSV is (delimiter detected)
# (JSON Lines: read through its CSV text, :mod:`.jsonlines`)
TEXT_SUFFIXES = (".csv", ".txt", ".tsv", ".dat", *JSON_LINES_SUFFIXES)


def is_text(path) -> bool:
    """Read as delimited text (else Parquet)."""
    return Path(path).suffix.lower() in TEXT_SUFFIXES
