"""``data.bits`` (extension, lab83): a PLC status word decoded into the 0/1 states it packs.

A controller logs ``Status`` (uint16) whose bit 0 says the machine is on, bit 1 the spindle
running, bit 2 the coolant on: read as one number it is a meaningless level to a linear model
(5 is not "more" than 4).  ``data.bits: {Status: {0: machine_on, 1: spindle_on}}`` reads each
declared bit as a state column of its own (``S_machine_on``, 0 or 1), the word itself no input.
Nothing is decoded without the declaration: ``init`` says where a column looks like a bit field
(:func:`looks_like_bits`) and proposes the key, never writes it.

Refused (exit 2): a declaration that is no mapping of bits 0-63 to names (the key named), a word
the file does not hold or whose value is no whole number >= 0 (file, column, row), a bit's name
that is a column's already (file, column).
"""

from __future__ import annotations

import re
from collections.abc import Mapping

import numpy as np
import pandas as pd
import pyarrow as pa

from .contract import ContractError

KEY = "data.bits"
STATE = "S_"
MOST_BITS = 64                 # a 64-bit word's: a bit past 63 is no PLC word's
_NAME = re.compile(r"^[A-Za-z]\w*$")
FEW_VALUES = 16                # a bit field: at most this many distinct words...
FEW_BITS = 4                   # ...each a sum of at most this many powers of two


def parsed(value) -> dict[str, dict[int, str]]:
    """``data.bits`` checked: ``{the word's header: {bit: state name}}``; a ContractError
    naming the key else."""
    value = value or {}
    if not hasattr(value, "items"):
        raise ContractError(f"{KEY} must map a status word's header to its bits' names, e.g. "
                            f"{{Status: {{0: machine_on, 1: spindle_on}}}}, got {value!r}")
    out: dict = {}
    for header, bits in value.items():
        key = f"{KEY}.{header}"
        if not hasattr(bits, "items") or not bits:
            raise ContractError(f"{key} must map bit numbers to state names, e.g. "
                                f"{{0: machine_on}}, got {bits!r}")
        named: dict = {}
        for bit, name in bits.items():
            if isinstance(bit, bool) or not re.fullmatch(r"\d+", str(bit).strip()) or int(
                    str(bit)) >= MOST_BITS:
                raise ContractError(f"{key}: bit {bit!r} is no bit of a word (0-{MOST_BITS - 1})")
            if not isinstance(name, str) or not _NAME.match(name):
                raise ContractError(f"{key}.{bit}: {name!r} is no state name (letters, digits "
                                    "and _, a letter first)")
            named[int(str(bit))] = name
        out[str(header)] = named
    names = [n for bits in out.values() for n in bits.values()]
    twice = next((n for n in names if names.count(n) > 1), None)
    if twice is not None:
        raise ContractError(f"{KEY}: {twice!r} names two bits")
    return out


def decoded(columns: dict, renamed: dict, bits: Mapping, path) -> dict:
    """``columns`` (contract names -> arrays) with each declared word replaced by its bits'
    0/1 state columns (a missing word: missing bits, repaired as any gap); ``renamed`` (raw ->
    contract) updated in place.  ContractError naming file, column and row on a bad word."""
    for header, named in bits.items():
        name = renamed.get(header, header if header in columns else None)
        if name is None or name not in columns:
            _not_read(header, path)
        word = columns.pop(name).to_numpy(zero_copy_only=False).astype(float)
        renamed.pop(header, None)
        for state, on in _bits(word, header, named, set(columns) | set(renamed), path).items():
            columns[state] = pa.chunked_array([pa.array(on, from_pandas=True)])
    return columns


def decoded_frame(df, bits: Mapping, headers: Mapping, source):
    """A stream's frame (contract names; ``headers``: contract -> the row's own header) with
    each declared word replaced by its bits' states, as a file's are (:func:`decoded`)."""
    for header, named in bits.items():
        name = next((n for n, raw in headers.items() if raw == header),
                    header if header in df.columns else None)
        if name is None or name not in df.columns:
            _not_read(header, source)
        word = pd.to_numeric(df[name], errors="coerce").to_numpy(float)
        states = _bits(word, header, named, set(df.columns) - {name}, source)
        df = df.drop(columns=name).assign(**states)
    return df


def words_decoded(frame: pd.DataFrame, bits: Mapping) -> pd.DataFrame:
    """A served block under the lab's headers with each declared word it holds replaced by its
    bits' states (:func:`decoded_frame`; bits85: the declaration travels with the model, as
    its column names do); a block giving the bits as columns of their own is left as it is.
    A bad word: a ContractError naming the column and the block's row (no file)."""
    held = {h: named for h, named in (bits or {}).items() if h in frame.columns}
    for header, named in held.items():      # (one input under two columns, as to_contract's)
        both = [STATE + n for n in named.values() if STATE + n in frame.columns]
        if both:
            raise ContractError(f"column {header!r}: the block gives the status word and its "
                                f"bit {both[0]} both ({KEY}.{header}): send one of them")
    try:
        return decoded_frame(frame, held, {}, None) if held else frame
    except ContractError as exc:
        where = f"column {exc.column!r}" + (f", data row {exc.row} of the block" if exc.row else "")
        raise ContractError(f"{where}: {exc.reason}") from None


def _not_read(header: str, path) -> None:
    raise ContractError(f"{KEY} declares {header!r} a status word, and no column of that header "
                        "is read (a column data.roles ignores is not; give it a role, e.g. "
                        "data.roles.state)", file=path, column=header)


def _bits(word: np.ndarray, header: str, named: Mapping, taken: set, path) -> dict:
    """``{S_<name>: 0/1 (NaN where the word is missing)}`` of the word's declared bits."""
    bad = np.isfinite(word) & ((word < 0) | (word != np.round(word)) | (word >= 2.0 ** 63))
    if bad.any():
        at = int(np.argmax(bad))
        raise ContractError(f"value {word[at]:g} is no whole number >= 0: no status word "
                            f"({KEY}.{header})", file=path, column=header, row=at + 1)
    clash = next((n for n in named.values() if STATE + n in taken or n in taken), None)
    if clash is not None:
        raise ContractError(f"{KEY}.{header}: the state {clash!r} ({STATE}{clash}) is a "
                            "column's already: name the bit otherwise", file=path, column=header)
    whole = np.where(np.isfinite(word), word, 0).astype(np.uint64)
    return {STATE + state: np.where(np.isfinite(word), ((whole >> np.uint64(bit)) & np.uint64(1))
                                    .astype(float), np.nan)
            for bit, state in named.items()}


def looks_like_bits(values: np.ndarray) -> list[int] | None:
    """The bits a column of whole numbers >= 0 sets, where it looks like a status word: at
    least three distinct words, at most :data:`FEW_VALUES`, each a sum of at most
    :data:`FEW_BITS` powers of two, one of two or more, and not every number of a range (a
    count, a gear: 0-5); None else."""
    finite = values[np.isfinite(values)]
    if not finite.size or (finite < 0).any() or (finite != np.round(finite)).any() or (
            finite >= 2.0 ** 63).any():
        return None
    words = np.unique(finite).astype(np.uint64)
    if not 3 <= words.size <= FEW_VALUES:
        return None
    counts = [bin(int(w)).count("1") for w in words]
    # (every whole number of a range, 0-5: a count or a gear's, no word's bits)
    if max(counts) > FEW_BITS or not any(c >= 2 for c in counts) or (
            int(words[-1] - words[0]) + 1 == words.size):
        return None
    union = int(np.bitwise_or.reduce(words))
    return [b for b in range(MOST_BITS) if union >> b & 1]


def proposed(header: str, values: np.ndarray) -> str | None:
    """What ``init`` says of a state column ``header`` whose ``values`` look like a status word
    (:func:`looks_like_bits`): the key to declare, the names left to the lab; None else."""
    bits = looks_like_bits(values)
    if bits is None:
        return None
    words = np.unique(values[np.isfinite(values)]).astype(np.uint64)
    shown = ", ".join(str(int(w)) for w in words[:6]) + (", ..." if words.size > 6 else "")
    key = ", ".join(f"{b}: <name>" for b in bits)
    return (f"{header!r} holds {words.size} whole numbers ({shown}), each a sum of few powers "
            f"of two (bits {', '.join(map(str, bits))} set): a PLC's status word? read as one "
            f"number state, its levels meaningless to a linear model; {KEY}={{{header}: "
            f"{{{key}}}}} reads each bit as a 0/1 state (not written: what each bit says is "
            "the PLC's)")
