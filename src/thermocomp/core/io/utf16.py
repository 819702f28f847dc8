"""A text file written two bytes a character, UTF-16 with its byte-order mark (Excel's
'Unicode Text' export: tab-separated, little-endian), read as its UTF-8 text is: transcoded
into a temporary UTF-8 file that the CSV reader reads, and removes after, as a workbook's sheet
is (:mod:`.workbook`).  The lines are the file's, so a message names the file and its line as
the editor shows them; ``data.encoding`` does not apply to it (the mark says the set)."""

from __future__ import annotations

import codecs
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path

from .contract import ContractError
from .converted import at_file, named_as
from .encoding import UTF8

_BOMS = (codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)


def has_utf16_mark(head: bytes) -> bool:
    """``head`` (a text's first 4 bytes) begins with a UTF-16 byte-order mark (not UTF-32's,
    whose little-endian mark begins with UTF-16's: refused by the reader with the remedy)."""
    return head[:2] in _BOMS and head[:4] != codecs.BOM_UTF32_LE


def is_utf16(path) -> bool:
    """``path`` is a file that begins with a UTF-16 byte-order mark."""
    try:
        with open(path, "rb") as f:
            return has_utf16_mark(f.read(4))
    except OSError:              # (not a file: the reader says what it is)
        return False


def utf8_options(opts):
    """The read options of the transcoded file (its set: UTF-8)."""
    return replace(opts, encoding=UTF8)


@contextmanager
def utf16_as_utf8(path: Path) -> Iterator[Path]:
    """The UTF-16 file ``path`` as a temporary UTF-8 file (no mark; the same lines), removed
    after; a :class:`ContractError` or a warning about it names ``path``.  Two bytes that are
    no character (a lone surrogate, an odd length) are refused with their line."""
    data = path.read_bytes()
    try:
        text = data.decode("utf-16")          # the mark says the byte order, and is dropped
    except UnicodeDecodeError as exc:
        line = data[:exc.start].decode("utf-16", "replace").count("\n") + 1
        raise ContractError(f"bytes {exc.start}-{exc.end - 1} are no UTF-16 character (the "
                            "file begins with UTF-16's byte-order mark)", file=path,
                            line=line) from None
    with tempfile.TemporaryDirectory(prefix="thermocomp-utf16-") as tmp:
        out = Path(tmp) / path.name
        out.write_text(text, encoding=UTF8, newline="")
        with named_as(out, str(path), lambda exc: at_file(exc, out, path)):
            yield out

