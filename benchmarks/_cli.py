"""The command line of the benches that take a command: ``python benchmarks/X.py COMMAND ARG...``.

A bench names its commands, each a function of the command's words in order, and hands them to
:func:`run_commands`; the usage it prints is the bench's own docstring.
"""

from __future__ import annotations

import inspect
from pathlib import Path
from typing import Callable, TextIO

from cpu import cpu_seconds


def run_commands(doc: str | None, commands: dict[str, Callable], argv: list[str], *,
                 cpu: TextIO | None = None) -> int:
    """Run ``commands[argv[0]](*argv[1:])`` and return 0 (what the command returns is not a status:
    a command that has one exits with it).  Where ``argv`` is empty, its first word names no
    command or the words after it do not fit the command's parameters: print ``doc`` (the usage)
    and return 2, nothing run.  ``cpu``: the stream that gets the command's CPU line (user + sys
    of this process while it ran; None: no line)."""
    command = commands.get(argv[0]) if argv else None
    if command is None or not _fits(command, argv[1:]):
        print(doc)
        return 2
    start = cpu_seconds()
    command(*argv[1:])
    if cpu is not None:
        print(f"CPU s (user + sys) of this process: {cpu_seconds() - start:.1f}", file=cpu)
    return 0


def _fits(command: Callable, words: list[str]) -> bool:
    try:
        inspect.signature(command).bind(*words)
    except TypeError:
        return False
    return True


def seed_list(word: str) -> list[int]:
    """The seeds ``word`` names: ``7996-8010``, ``7701,7705`` or both (``7701-7703,7710``)."""
    out = []
    for part in word.split(","):
        lo, _, hi = part.partition("-")
        out += list(range(int(lo), int(hi or lo) + 1))
    return out


def made_folder(word: str) -> Path:
    """The folder ``word`` names, resolved, made where it is missing (a command that writes there)."""
    folder = Path(word).resolve()
    folder.mkdir(parents=True, exist_ok=True)
    return folder


def project_root(word: str, conf: Path | None = None) -> Path:
    """The scratch project root ``word`` names, for the stages a command runs in this process:
    made where missing, ``conf`` (default: the measured tree's ``conf/``, the one beside the
    ``thermocomp`` on ``PYTHONPATH``) linked in where no ``conf`` is, ``THERMOCOMP_ROOT`` set to
    it.  What an earlier command wrote there is kept: a command that must start clean removes its
    own output (review95: ``bench_mon88``'s root was made anew, and a second command into the same
    ROOT deleted the first's output -- jump94b's ``trace-main.json`` under ``healthy``; review96:
    bench_audit89's ``healthy`` and the one-command sweeps of audit86b, auto86b, deploy87/88,
    deployed_as_scored59 and export_atiprod65 the same)."""
    import os

    import thermocomp

    root = made_folder(word)
    if not (root / "conf").exists():
        (root / "conf").symlink_to(conf or Path(thermocomp.__file__).resolve().parents[2] / "conf")
    os.environ["THERMOCOMP_ROOT"] = str(root)
    return root
