"""Figure saving (atomic, readable) and drawing in worker processes (issue 11)."""

import os

import matplotlib.pyplot as plt
import numpy as np
import pytest

from thermocomp.core.figures.plots import FigurePool, residual_plot, save_figure


def _residual_args(k: int, folder):
    t = np.arange(120) * 60.0
    y = np.sin(t / 1800.0 + k) * (k + 1)
    return t, y, 0.9 * y, "E_Z", f"K{k}", folder / f"residual_K{k}_E_Z.png"


def test_pool_draws_in_workers_the_same_files_as_in_process(tmp_path):
    (tmp_path / "pool").mkdir()
    (tmp_path / "here").mkdir()
    with FigurePool(workers=2) as pool:
        for k in range(4):
            pool.submit(residual_plot, *_residual_args(k, tmp_path / "pool"))
        pool.submit(os.getpid)  # any picklable callable: it runs in a worker, not here
    assert pool.paths[:4] == [_residual_args(k, tmp_path / "pool")[-1] for k in range(4)]
    assert pool.paths[4] != os.getpid()
    with FigurePool(workers=0) as here:
        for k in range(4):
            here.submit(residual_plot, *_residual_args(k, tmp_path / "here"))
    for drawn, local in zip(pool.paths[:4], here.paths):
        assert drawn.read_bytes() == local.read_bytes() and drawn.read_bytes()[:4] == b"\x89PNG"
        assert drawn.stat().st_mode & 0o777 == 0o644
    assert sorted(p.name for p in (tmp_path / "pool").iterdir()) == sorted(p.name for p in pool.paths[:4])


def test_an_error_in_a_worker_is_raised_by_the_pool(tmp_path):
    t, y, yhat, target, cid, path = _residual_args(0, tmp_path)
    with pytest.raises(ValueError):
        with FigurePool(workers=2) as pool:
            pool.submit(residual_plot, t, y, yhat[:-5], target, cid, path)  # lengths differ
    assert list(tmp_path.iterdir()) == []  # nothing half-written


def test_a_failed_save_keeps_the_previous_figure_and_no_temp_file(tmp_path):
    path = tmp_path / "f.png"
    save_figure(plt.figure(), path)
    before = path.read_bytes()
    fig = plt.figure()

    def broken(f, **kwargs):
        f.write(b"\x89PNG half a figure")
        raise OSError("disk full")

    fig.savefig = broken
    with pytest.raises(OSError):
        save_figure(fig, path)
    assert path.read_bytes() == before
    assert [p.name for p in tmp_path.iterdir()] == ["f.png"]
    assert not plt.fignum_exists(fig.number)  # closed all the same
