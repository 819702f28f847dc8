"""Atomic writes, the one JSON writer and folder digests (thermocomp.base.files, thermocomp.base.jsonsafe)."""

import json
import shutil
import stat

import numpy as np
import pytest

from thermocomp.base.files import atomic_dir, atomic_write_bytes, folder_digest, write_json
from thermocomp.base.jsonsafe import json_safe


def _mode(path):
    return stat.S_IMODE(path.stat().st_mode)


def test_json_safe_turns_numpy_and_non_finite_values_into_plain_json():
    obj = {"a": np.float64(1.5), "nan": float("nan"), "inf": -np.inf, np.int64(3): np.int32(7),
           "arr": np.array([[1.0, np.nan], [np.inf, 2.0]]), "t": (np.bool_(True), "x", None)}
    clean = json_safe(obj)
    assert clean == {"a": 1.5, "nan": None, "inf": None, 3: 7, "arr": [[1.0, None], [None, 2.0]],
                     "t": [True, "x", None]}
    assert type(clean["a"]) is float and type(clean[3]) is int and type(clean["t"][0]) is bool
    json.dumps(clean, allow_nan=False)          # would raise on any value left over
    assert json_safe(np.float32(np.nan)) is None and json_safe(2) == 2


def test_write_json_cleans_writes_readable_file_and_leaves_no_temp(tmp_path):
    path = write_json(tmp_path / "sub" / "r.json", {"x": np.float64("nan"), "y": [np.int64(2)]})
    assert json.loads(path.read_text()) == {"x": None, "y": [2]}
    assert _mode(path) == 0o644
    assert [p.name for p in path.parent.iterdir()] == ["r.json"]


def test_a_failed_write_keeps_the_previous_file(tmp_path):
    path = write_json(tmp_path / "r.json", {"v": 1})
    with pytest.raises(TypeError):
        write_json(path, {"v": object()})       # not JSON: refused, not half written
    assert json.loads(path.read_text()) == {"v": 1}
    atomic_write_bytes(path, b"\x00\x01")
    assert path.read_bytes() == b"\x00\x01" and [p.name for p in tmp_path.iterdir()] == ["r.json"]


def test_atomic_dir_swaps_in_a_whole_folder_or_nothing(tmp_path):
    dest = tmp_path / "out"
    with atomic_dir(dest) as tmp:
        (tmp / "a.txt").write_text("1")
    assert _mode(dest) == 0o755 and (dest / "a.txt").read_text() == "1"
    with pytest.raises(RuntimeError), atomic_dir(dest) as tmp:
        (tmp / "b.txt").write_text("2")
        raise RuntimeError("stage failed")
    assert sorted(p.name for p in dest.iterdir()) == ["a.txt"]
    assert [p.name for p in tmp_path.iterdir()] == ["out"]
    with atomic_dir(dest) as tmp:
        (tmp / "b.txt").write_text("2")
    assert sorted(p.name for p in dest.iterdir()) == ["b.txt"]


def test_folder_digest_sees_names_bytes_and_subfolders_not_the_location(tmp_path):
    a = tmp_path / "a"
    (a / "sub").mkdir(parents=True)
    (a / "x.csv").write_text("1,2\n")
    (a / "sub" / "y.parquet").write_bytes(b"\x00PAR")
    ref = folder_digest(a)
    assert folder_digest(shutil.copytree(a, tmp_path / "elsewhere")) == ref
    (a / "sub" / "y.parquet").write_bytes(b"\x00PAS")
    changed = folder_digest(a)
    (a / "sub" / "y.parquet").rename(a / "y.parquet")
    moved = folder_digest(a)
    assert len({ref, changed, moved}) == 3


def test_a_signal_inside_a_deferred_block_is_raised_at_its_end_not_inside():
    import signal

    from thermocomp.base.files import Terminated, signals_raise

    reached = []
    with pytest.raises(Terminated) as caught:
        with signals_raise() as signals:
            with signals.deferred():
                signal.raise_signal(signal.SIGTERM)
                reached.append("after the signal")   # the block is not cut
            reached.append("after the block")        # never: the signal is raised on leaving
    assert reached == ["after the signal"] and caught.value.code == 128 + signal.SIGTERM
    with pytest.raises(Terminated):                  # outside a deferred block: at once
        with signals_raise():
            signal.raise_signal(signal.SIGTERM)
            reached.append("never")
    assert reached == ["after the signal"]


def test_the_retried_signal_does_not_cut_the_deferred_close_of_a_run():
    """CI, stop 44: a SIGINT'd run stayed RUNNING.  The signal raised KeyboardInterrupt; 0.5 s
    later, while the run was being closed in a deferred block, the retry timer raised it again
    inside an ``except`` of the store's own code (where the propagating interrupt is not the
    exception being handled) and cut the close in two."""
    import signal
    import time

    from thermocomp.base.files import signals_raise

    closed = []
    with pytest.raises(KeyboardInterrupt):
        with signals_raise(sigint=True) as signals:
            try:
                signal.raise_signal(signal.SIGINT)
            finally:
                with signals.deferred():
                    end = time.monotonic() + 1.5          # three retry periods
                    while time.monotonic() < end:
                        try:
                            raise ValueError("the store's own, handled")
                        except ValueError:
                            time.sleep(0.01)
                    closed.append(True)
    assert closed == [True]
