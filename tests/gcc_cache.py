"""The exported C compiled once per content in a test process: the export tests build hundreds of
``stream`` programs, ~0.6 s of the compiler's CPU each (~2 s with the sensor monitor's code), and
many are the same sources built again (a test's module compiles the C ``thermocomp export`` wrote
and then the C of the same model in process; ``stream.c`` is the same driver for every model).

:func:`build` compiles each translation unit of a folder (``compensator.c``, ``stream.c``, ...)
as ``gcc <flags> -c``, exactly what ``gcc <flags> a.c b.c -o stream`` does unit by unit, and links
the objects as that command does.  An object is kept under the key of everything its compilation
reads: the compiler's identity (``gcc --version``), the flags, the unit's bytes and those of every
header in the folder (the units include ``compensator.h`` only; every ``*.h`` is in the key, so a
header edited or added compiles the units again).  A unit whose key was built before (the same
driver with the same header, the same model's code) is not compiled again: its warnings as errors
were none then and are none now.  A failed compilation raises as the plain command does and
keeps nothing.

The objects live in one folder per test run (:func:`use`: conftest puts it under pytest's base
temporary folder, shared by xdist's workers, written by atomic renames), so a run starts with no
object: nothing carries over from a run of other code.
"""

from __future__ import annotations

import functools
import hashlib
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

_folder: Path | None = None


def use(folder: Path) -> None:
    """Keep the compiled objects in ``folder`` (made if missing)."""
    global _folder
    folder.mkdir(parents=True, exist_ok=True)
    _folder = folder


@functools.cache
def _compiler(cc: str) -> bytes:
    """What names the compiler build: its ``--version`` text (release and target)."""
    return subprocess.run([cc, "--version"], capture_output=True, check=True).stdout


def _key(cc: str, flags: list[str], unit: Path, headers: list[Path]) -> str:
    digest = hashlib.sha256(_compiler(cc))
    digest.update("\0".join(flags).encode())
    for path in (unit, *headers):
        digest.update(b"\0" + path.name.encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()


def _object(cc: str, flags: list[str], folder: Path, unit: str, headers: list[Path]) -> Path:
    """``unit``'s object file, from the cache or compiled (``cc <flags> -c unit``)."""
    kept = _folder / f"{_key(cc, flags, folder / unit, headers)}.o"
    if kept.exists():
        return kept
    made = folder / f"{Path(unit).stem}.o"
    subprocess.run([cc, *flags, "-c", unit, "-o", made.name], cwd=folder, check=True,
                   capture_output=True)
    fd, tmp = tempfile.mkstemp(dir=_folder, suffix=".tmp")
    os.close(fd)
    shutil.copyfile(made, tmp)
    os.replace(tmp, kept)          # atomic: another worker never reads half an object
    return made


def build(folder: Path, units: list[str], flags: list[str], program: str = "stream",
          libs: tuple[str, ...] = ("-lm",), cc: str = "gcc") -> Path:
    """``cc <flags> <units> <libs> -o <program>`` in ``folder``, each unit compiled once per
    content in this run (see the module's docstring); the program's path."""
    if _folder is None:            # no run's folder (a module used outside pytest): plain
        subprocess.run([cc, *flags, *units, *libs, "-o", program], cwd=folder, check=True,
                       capture_output=True)
        return folder / program
    headers = sorted(folder.glob("*.h"))
    objects = [_object(cc, flags, folder, u, headers) for u in units]
    subprocess.run([cc, *flags, *map(str, objects), *libs, "-o", program], cwd=folder,
                   check=True, capture_output=True)
    return folder / program
