"""``data.encoding``: the character set a lab's CSV file is written in (UTF-8, the contract's;
a Windows export or logger: cp1252 / Latin-1, where ``°`` is byte 0xB0 and ``µ`` 0xB5).

Arrow transcodes the file itself (``pyarrow.csv.ReadOptions.encoding``); the few lines read
here (header, preamble, footer, manifest) are decoded with the same codec.  A byte the codec
does not read is refused where it is (row, column) naming the setting that reads it.
"""

from __future__ import annotations

import codecs
from functools import lru_cache
from pathlib import Path

from .contract import ContractError
from .csvline import SPLIT, split_line

UTF8 = "utf-8"
WINDOWS = "cp1252"       # a Windows export; reads Latin-1's printable range alike
AUTO = "auto"            # (data87) each file's own: a folder with a file Excel saved again
_CHUNK = 1 << 20


def codec(name: str) -> str:
    """``data.encoding`` as Python names the codec (``latin-1`` -> ``iso8859-1``); ``auto``
    stays so, each file read in its own (:func:`own`).

    Raises
    ------
    ContractError
        An unknown codec, or one that does not write ``,;\\n`` as ASCII does (UTF-16: the
        lines and fields are found in the bytes).
    """
    if str(name) == AUTO:
        return AUTO
    try:
        found = codecs.lookup(str(name)).name
    except LookupError:
        found = None
    if found is None or "\n,;\t|0.".encode(found) != b"\n,;\t|0.":
        raise ContractError(f"data.encoding must be a character set that writes ASCII as ASCII "
                            f"(utf-8, cp1252, latin-1, ...), got {name!r}")
    return found


def text_codec(encoding: str) -> str:
    """The codec decoding a file's text here: UTF-8 drops a BOM."""
    return "utf-8-sig" if encoding == UTF8 else encoding


def arrow_encoding(encoding: str) -> str:
    """What ``pyarrow.csv.ReadOptions(encoding=)`` takes: ``utf8`` reads without transcoding."""
    return "utf8" if encoding == UTF8 else encoding


def detect(path: Path) -> str:
    """``utf-8`` when the whole file reads as UTF-8, else ``cp1252`` (``thermocomp init``; a
    byte cp1252 does not read either is refused when the file is read with it)."""
    decoder = codecs.getincrementaldecoder(UTF8)()
    with open(path, "rb") as f:
        try:
            while chunk := f.read(_CHUNK):
                decoder.decode(chunk)
            decoder.decode(b"", final=True)
        except UnicodeDecodeError:
            return WINDOWS
    return UTF8


def ascii_only(path: Path) -> bool:
    """Every byte of the file is ASCII (it reads alike in UTF-8 and cp1252)."""
    with open(path, "rb") as f:
        while chunk := f.read(_CHUNK):
            if not chunk.isascii():
                return False
    return True


def own(path: Path, encoding: str) -> str:
    """``encoding``, or where it is ``auto`` the file's own (:func:`detect`: UTF-8 where every
    byte reads so, else cp1252), decided once per file as it is."""
    if encoding != AUTO:
        return encoding
    stat = Path(path).stat()
    return _detected(str(path), stat.st_mtime_ns, stat.st_size)


@lru_cache(maxsize=256)
def _detected(path: str, mtime_ns: int, size: int) -> str:
    return detect(Path(path))


def decoded(data: bytes, encoding: str) -> str:
    """``data`` (a stream's bytes) as text in ``encoding``; ``auto``: UTF-8 where every byte
    reads so, else cp1252 (a byte neither reads raises ``UnicodeDecodeError``)."""
    if encoding != AUTO:
        return data.decode(text_codec(encoding))
    try:
        return data.decode(text_codec(UTF8))
    except UnicodeDecodeError:
        return data.decode(WINDOWS)


# a byte-order mark of a text written two or four bytes a character (UTF-32's before UTF-16's:
# UTF-32-LE's begins with UTF-16-LE's)
_WIDE_BOMS = ((codecs.BOM_UTF32_LE, "UTF-32"), (codecs.BOM_UTF32_BE, "UTF-32"),
              (codecs.BOM_UTF16_LE, "UTF-16"), (codecs.BOM_UTF16_BE, "UTF-16"))


GZIP_MAGIC = b"\x1f\x8b"


def gzipped(path: Path) -> ContractError:
    return ContractError("a gzip-compressed file, not CSV text: unpack it first", file=path)


def check_text(head: bytes, encoding: str, path: Path | str) -> None:
    """Refuse a file (its first bytes ``head``; a ``str`` path: a stream) that
    ``data.encoding`` cannot read as the text of its lines: a gzip-compressed file, UTF-16 or
    UTF-32 (Excel's 'Unicode Text' export, which writes a byte-order mark), or UTF-8 read with
    another encoding (:func:`check_not_utf8`)."""
    if head.startswith(GZIP_MAGIC) and isinstance(path, Path):
        raise gzipped(path)        # before any separator is sniffed in its binary head
    wide = next((name for bom, name in _WIDE_BOMS if head.startswith(bom)), None)
    if wide is not None:
        convert = (f"iconv -f {wide} -t UTF-8 {path.name} > {path.stem}-utf8.csv"
                   if isinstance(path, Path) else f"pipe it through iconv -f {wide} -t UTF-8")
        raise ContractError(f"{'file' if isinstance(path, Path) else 'stream'} is {wide} text "
                            "(Excel's 'Unicode Text' export?), which no data.encoding reads: "
                            f"save it as 'CSV UTF-8', or convert it ({convert})", file=path)
    if isinstance(path, Path):
        check_not_utf8(head, encoding, path)


def check_not_utf8(head: bytes, encoding: str, path: Path) -> None:
    """Refuse a UTF-8 file (its first bytes ``head``, holding more than ASCII) read with another
    ``data.encoding``: ``°C`` would be read ``Â°C`` (a folder of a Windows export and a file
    saved again as UTF-8)."""
    if encoding in (UTF8, AUTO) or head.isascii():
        return
    try:
        text = head.decode(UTF8)
    except UnicodeDecodeError as exc:
        if exc.start < len(head) - 3:      # (not a character cut at the end of ``head``)
            return
        text = head[:exc.start].decode(UTF8)
    word = next((w for w in text.split() if not w.isascii()), None)
    if word is None:
        return
    raise ContractError(f"file is UTF-8 text ({word!r}), not data.encoding={encoding}: save it "
                        "as the others, or read it with data.encoding=utf-8", file=path)


def undecodable(path: Path, delimiter: str, names: list[str] | None = None,
                encoding: str = UTF8, header_at: int = 0) -> ContractError:
    """The error naming the line (1-based, of the file) and field of the first byte
    ``encoding`` does not read, and the ``data.encoding`` that reads it; ``header_at``: the
    lines above the header (a logger's preamble), where ``names`` is None."""
    encoding = own(path, encoding)
    with open(path, "rb") as f:
        if f.read(2) == GZIP_MAGIC:
            return gzipped(path)
    return (first_undecodable(path, delimiter, names, encoding, header_at)
            or ContractError(f"file is not {encoding} text (set data.encoding)", file=path))


def first_undecodable(path: Path, delimiter: str, names: list[str] | None,
                      encoding: str = UTF8, header_at: int = 0) -> ContractError | None:
    """:func:`undecodable`'s error, or None if every line reads (line by line, so a large file
    is never held whole)."""
    encoding = own(path, encoding)
    with open(path, "rb") as f:
        header = names
        for line_no, line in enumerate(f):
            # the file's own header names the fields; a preamble line above it has none
            # (audit98: a '# Sample period: 60 s' line above the header was named the column)
            if header is None and line_no >= header_at:
                header = fields(line.decode(text_codec(encoding), "replace").lstrip("\ufeff"),
                               delimiter)
            try:
                line.decode(encoding)
            except UnicodeDecodeError as exc:
                field = line[:exc.start].count(delimiter.encode())
                column = header[field] if header and field < len(header) else None
                return ContractError(f"byte 0x{line[exc.start]:02x} is not {_said(encoding)} "
                                     f"text{_remedy(line, encoding)}", file=path, column=column,
                                     line=line_no + 1)
    return None


def fields(line: str, delimiter: str) -> list[str]:
    """A header line's fields, stripped (bytes that are no CSV text: split at each separator)."""
    return [c.strip() for c in split_line(line, delimiter, SPLIT)]


def _said(encoding: str) -> str:
    return "UTF-8" if encoding == UTF8 else encoding


def _remedy(line: bytes, encoding: str) -> str:
    """The setting that reads ``line``: a Windows export's ``data.encoding=cp1252``."""
    if encoding != WINDOWS:
        try:
            line.decode(WINDOWS)
            return f" (a Windows export? set data.encoding={WINDOWS}, or save the file as UTF-8)"
        except UnicodeDecodeError:
            pass
    return " (set data.encoding to the file's character set, or save the file as UTF-8)"


def text_lines(path: Path, encoding: str = UTF8) -> list[str]:
    """The lines of the text file ``path`` (a logger's export read whole: its header block and
    table; :func:`check_text` first), refused naming ``data.encoding`` where it does not decode."""
    raw = path.read_bytes()
    encoding = own(path, encoding)
    check_text(raw[:1 << 16], encoding, path)
    try:
        return raw.decode(text_codec(encoding)).splitlines()
    except UnicodeDecodeError:
        raise ContractError(f"file is not {encoding} text (a Windows export: data.encoding=cp1252)",
                            file=path) from None


def text_head(path, size: int = 256, suffixes: tuple[str, ...] = (".csv", ".txt")) -> str | None:
    """The first ``size`` bytes of ``path`` as Latin-1 text where it is a file with one of
    ``suffixes``, else None: what a logger's export is told apart by (its first line)."""
    if Path(path).suffix.lower() not in suffixes:
        return None
    try:
        with open(path, "rb") as f:
            return f.read(size).decode("latin-1")
    except OSError:
        return None
