"""The project's error types: every one a ``ValueError``; the CLI maps them to exit status 2.

Core packages (models, select, denoise, metrics, diagnose, deploy) raise
:class:`ParameterError` for an estimator parameter outside its allowed values
(scikit-learn's convention: a ``ValueError``) and :class:`ContractError` for data
that breaks the contract.  The shell raises :class:`ConfigError` for a config key
it cannot use.  Anything else that escapes a command is a bug (exit status 1).
"""

from __future__ import annotations

import difflib
import os


def closest(word: str, options, n: int = 1) -> list[str]:
    """The ``n`` options closest to a mistyped ``word``, closest first (the "did you mean" of
    an error message)."""
    return difflib.get_close_matches(str(word), [str(o) for o in options], n=n, cutoff=0.6)


def config_file_form(section: str, entry: str) -> str:
    """How to give a config entry the command line cannot take (a map's key with spaces,
    brackets or letters beyond ASCII: Hydra's grammar reads it by no quoting): the file's lines
    and how to pass it.  (notes100: the hint named the config ``thermocomp init`` writes, which
    ``init``, refusing the file, had not written.)"""
    return (f"myconf/{section}/mine.yaml with the two lines 'defaults: [default]' and "
            f"\"{entry}\", then pass \"hydra.searchpath=[file://$PWD/myconf]\" {section}=mine "
            f"(or put it in the {section} config `thermocomp init` writes)")


class ThermocompError(ValueError):
    """Bad input or bad configuration: exit status 2 with the one-line message."""


class ParameterError(ThermocompError):
    """An estimator/denoiser/selector parameter outside its allowed values (names the parameter)."""


class ConfigError(ThermocompError):
    """A config value outside what the pipeline accepts; the message names the key."""


class FallbackWarning(UserWarning):
    """A model fell back to a simpler one its data support (ATI with too few ambient levels):
    news on a run's training data; by design where a model sees one campaign alone (the mutual
    prediction matrix), which ignores it."""


class ContractError(ThermocompError):
    """Input that breaks the data contract.

    The message is one line naming the file, the column and the row (1-based
    data row, header excluded) wherever they are known, and the row's ``line`` in a CSV
    file (1-based, what a lab's editor shows: above it a preamble, the header, a unit row,
    blank lines) where it is known: ``line 13 (data row 9)``.  In a workbook's ``sheet`` the
    ``line`` is the sheet's row, as Excel numbers it: ``sheet 'Messung', row 13 (data row 9)``.
    """

    def __init__(self, message: str, file: str | os.PathLike | None = None,
                 column: str | None = None, row: int | None = None, line: int | None = None,
                 sheet: str | None = None):
        self.reason, self.file, self.column, self.row, self.line = message, file, column, row, line
        self.sheet = sheet
        where = [f"file {file}" if file is not None else None,
                 f"sheet {sheet!r}" if sheet is not None else None,
                 f"column {column!r}" if column is not None else None,
                 position(row, line, "line" if sheet is None else "row")]
        where = ", ".join(w for w in where if w)
        super().__init__(f"{where}: {message}" if where else message)


class TooFewSamples(ContractError):
    """A model given fewer rows than its fit needs (a record, or a validation fold of it, too
    short); the message keeps scikit-learn's ``n_samples=`` wording."""


def position(row: int | None, line: int | None = None, unit: str = "line") -> str | None:
    """``line 13 (data row 9)``, ``data row 9`` or ``line 13``: where a message points in a file
    (``unit="row"``: a sheet's row, ``row 13 (data row 9)``)."""
    if line is not None:
        return f"{unit} {line}" + (f" (data row {row})" if row is not None else "")
    return None if row is None else f"data row {row}"


def listed(names, most: int = 5) -> str:
    """``a, b, c and 4 more``: the first ``most`` of ``names`` in a one-line message."""
    names = [str(n) for n in names]
    return ", ".join(names[:most]) + (f" and {len(names) - most} more" if len(names) > most else "")
