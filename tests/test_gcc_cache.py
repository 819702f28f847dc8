"""tests/gcc_cache.py: a unit compiled once per content in a run, never an object of other bytes.

A program of two units that include one header, as the exported ``compensator.c`` and
``stream.c`` do: built again from the cache it prints what a plain ``gcc`` build prints; a header
or a unit edited compiles again (the key holds every header's bytes and the unit's); a warning
as error fails as the plain command does and leaves no object behind.
"""

from __future__ import annotations

import shutil
import subprocess

import pytest

import gcc_cache

pytestmark = pytest.mark.skipif(shutil.which("gcc") is None, reason="no C compiler")
FLAGS = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-O2"]
UNITS = ["compensator.c", "stream.c"]
HEADER = "#define SCALE {scale}\nint scaled(int x);\n"
COMPENSATOR = '#include "compensator.h"\nint scaled(int x) { return SCALE * x; }\n'
STREAM = ('#include <stdio.h>\n#include "compensator.h"\n'
          'int main(void) { printf("%d %d\\n", SCALE, scaled(7)); return 0; }\n')


def _folder(root, name: str, scale: int = 3, compensator: str = COMPENSATOR):
    folder = root / name
    folder.mkdir()
    (folder / "compensator.h").write_text(HEADER.format(scale=scale))
    (folder / "compensator.c").write_text(compensator)
    (folder / "stream.c").write_text(STREAM)
    return folder


def _printed(program) -> str:
    return subprocess.run([str(program)], capture_output=True, text=True, check=True).stdout


@pytest.fixture
def objects(tmp_path):
    """A run's object folder of this test's own, the suite's put back after it."""
    kept = gcc_cache._folder
    gcc_cache.use(tmp_path / "objects")
    yield tmp_path / "objects"
    gcc_cache._folder = kept


def test_a_cached_build_prints_what_the_plain_build_prints(tmp_path, objects):
    plain = _folder(tmp_path, "plain")
    subprocess.run(["gcc", *FLAGS, *UNITS, "-o", "stream"], cwd=plain, check=True)
    first = gcc_cache.build(_folder(tmp_path, "first"), UNITS, FLAGS)
    assert len(list(objects.glob("*.o"))) == 2
    again = gcc_cache.build(_folder(tmp_path, "again"), UNITS, FLAGS)
    assert len(list(objects.glob("*.o"))) == 2                   # both units from the cache
    assert not (again.parent / "stream.o").exists()              # ... not compiled here
    assert _printed(plain / "stream") == _printed(first) == _printed(again) == "3 21\n"


def test_an_edited_header_or_unit_compiles_again(tmp_path, objects):
    gcc_cache.build(_folder(tmp_path, "three"), UNITS, FLAGS)
    # stream.c unchanged, its header not: a stream.o of SCALE 3 would print "3 35"
    assert _printed(gcc_cache.build(_folder(tmp_path, "five", scale=5), UNITS, FLAGS)) == "5 35\n"
    other = COMPENSATOR.replace("SCALE * x", "SCALE * x + 1")
    assert _printed(gcc_cache.build(_folder(tmp_path, "edited", compensator=other), UNITS,
                                    FLAGS)) == "3 22\n"
    assert len(list(objects.glob("*.o"))) == 5


def test_a_warning_as_error_fails_as_the_plain_build_and_keeps_nothing(tmp_path, objects):
    broken = COMPENSATOR.replace("{ return", "{ int unused; return")
    folder = _folder(tmp_path, "broken", compensator=broken)
    with pytest.raises(subprocess.CalledProcessError) as failed:
        gcc_cache.build(folder, UNITS, FLAGS)
    assert "unused" in failed.value.stderr.decode()
    assert not list(objects.glob("*.o")) and not (folder / "stream").exists()
    with pytest.raises(subprocess.CalledProcessError):             # and again: not cached
        gcc_cache.build(folder, UNITS, FLAGS)
