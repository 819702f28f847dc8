"""A file read through the temporary UTF-8 CSV file it is converted to (a workbook's sheet:
:mod:`.workbook`; a UTF-16 text: :mod:`.utf16`): a message or a warning about the temporary file
names the file the lab gave instead."""

from __future__ import annotations

import logging
import re
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

from ...base.log import logger
from .contract import ContractError

_LINE = re.compile(r"\bline (\d+)")


@contextmanager
def named_as(temp: Path, where: str, located: Callable[[ContractError], ContractError],
             unit: str = "line", line_of: Callable[[int], int] | None = None) -> Iterator[None]:
    """Within the block, a :class:`ContractError` raised is ``located(exc)``, and a log record
    naming ``temp`` names ``where`` instead, its ``line N`` as ``<unit> N`` (a sheet's row;
    ``line_of(N)``: the file's line where the temporary file's lines are not its own)."""
    renamed = _Renamed(temp, where, unit, line_of or (lambda n: n))
    logger.filters.insert(0, renamed)      # (before log.said_once's: it compares what is read)
    try:
        yield
    except ContractError as exc:
        raise located(exc) from None
    finally:
        logger.removeFilter(renamed)


def at_file(exc: ContractError, temp: Path, path: Path) -> ContractError:
    """``exc`` about the temporary file ``temp`` as about the lab's ``path`` (its lines its own);
    any other error as it is."""
    if exc.file is None or Path(exc.file) != temp:
        return exc
    return ContractError(exc.reason.replace(str(temp), str(path)), file=path, column=exc.column,
                         row=exc.row, line=exc.line, sheet=exc.sheet)


class _Renamed(logging.Filter):
    def __init__(self, temp: Path, where: str, unit: str, line_of: Callable[[int], int]):
        super().__init__()
        self.temp, self.where, self.unit, self.line_of = str(temp), where, unit, line_of

    def filter(self, record: logging.LogRecord) -> bool:
        text = record.getMessage()
        if self.temp in text:
            record.msg = _LINE.sub(lambda m: f"{self.unit} {self.line_of(int(m.group(1)))}",
                                   text.replace(self.temp, self.where))
            record.args = ()
        return True
