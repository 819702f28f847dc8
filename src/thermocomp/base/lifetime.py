"""Worker processes that cannot outlive the process that started them.

A worker waiting on its task queue never learns that its parent was SIGKILLed (every worker
holds the queue's write end, so no end of file comes): figure workers stayed blocked in
``Queue.get`` for ever, joblib's (loky) in theirs, each holding its memory.

- :func:`die_with_parent`: the initializer of a forked pool
(:class:`~thermocomp.core.figures.plots.FigurePool`);
  on Linux the kernel kills the worker (``PR_SET_PDEATHSIG``: immediate, nothing to poll; it
  follows the forking *thread*, and such a pool forks from the caller's), elsewhere
  :func:`end_with_parent`.
- :func:`parallel`: ``joblib.Parallel`` whose loky workers run :func:`end_with_parent` (loky
  may start workers from its own threads, so the kernel's signal could come while the parent
  lives: a thread watches the parent instead, once a second).
- :func:`watch_parent`: the same watch, armed from inside a task (a sweep job in a local
  launcher's worker), only when the process named is this one's parent.
- :func:`end_local_workers`: loky's reusable workers stopped (a sweep's, when it ends).
- :func:`collect_less`: the garbage collector's thresholds of a process of the project's own.
- :func:`end_left_threads`: what a SIGTERM or Ctrl-C left of a library's threads, ended with
  the console command's process.
"""

from __future__ import annotations

import ctypes
import gc
import os
import signal
import sys
import threading
import time

PR_SET_PDEATHSIG = 1     # linux/prctl.h
_watched: set[int] = set()


def die_with_parent(parent: int) -> None:
    """Initializer of a forked worker of ``parent``: it is killed when ``parent`` dies."""
    try:
        armed = ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL) == 0
    except (OSError, AttributeError):   # no prctl: not Linux
        armed = False
    if not armed:
        end_with_parent(parent)
    elif os.getppid() != parent:        # the parent died before the signal was armed
        os._exit(1)


def end_with_parent(parent: int) -> None:
    """Initializer of a worker started by ``parent``: it exits once ``parent`` is gone."""
    if os.getppid() != parent:          # already gone
        os._exit(1)
    watch_parent(parent)


def watch_parent(parent: int) -> None:
    """Exit this process once its parent ``parent`` is gone; nothing when ``parent`` is not its
    parent (a task run in the parent itself, by threads, or on another node)."""
    if parent in _watched or os.getppid() != parent:
        return
    _watched.add(parent)
    threading.Thread(target=_watch, args=(parent,), daemon=True, name="watch-parent").start()


def _watch(parent: int) -> None:
    while os.getppid() == parent:
        time.sleep(1.0)
    os._exit(1)


def parallel(n_jobs, **kwargs):
    """``joblib.Parallel(n_jobs, **kwargs)`` whose worker processes end with this process
    (the initializer reaches loky's workers; the sequential and thread backends ignore it)."""
    from joblib import Parallel

    return Parallel(n_jobs=n_jobs, initializer=end_with_parent, initargs=(os.getpid(),), **kwargs)



# A thread a signal left that has not ended this long after the command: it never will (below)
LEFT_THREADS_GRACE_S = 5.0


def end_left_threads(code: int, grace_s: float | None = None) -> None:
    """End what a SIGTERM or Ctrl-C left of a library's threads in this process, a console
    command's whose command that signal ended (status ``code``), so that the process ends.

    The signal is raised as an exception wherever the main thread is (files.signals_raise), so
    it can land inside ``Thread.start()`` of a ThreadPoolExecutor's first worker (``start`` waits
    for the new thread to run: on a loaded machine, a while), which MLflow starts to download a
    registered model: the worker runs, but ``concurrent.futures`` never registered it, so nothing
    wakes it at exit and the interpreter waited for it for ever (``thermocomp serve`` SIGTERMed as
    it starts, CI at stop 65: its handler already gone, the next SIGTERM killed it).  Every
    executor still referenced is shut down (its queued work cancelled, its idle workers woken);
    a non-daemon thread still running :data:`LEFT_THREADS_GRACE_S` (``grace_s``) later (another
    primitive the exception left held) ends with the process: the atexit handlers run, the
    streams are flushed, then ``os._exit(code)``.  Nothing when no such thread runs."""
    from concurrent.futures import ThreadPoolExecutor

    def left():
        return [t for t in threading.enumerate()
                if t.is_alive() and not t.daemon and t is not threading.current_thread()]

    if not left():
        return
    for obj in gc.get_objects():    # type(): no __class__ of a proxy is looked up
        if issubclass(type(obj), ThreadPoolExecutor):
            obj.shutdown(wait=False, cancel_futures=True)
    deadline = time.monotonic() + (LEFT_THREADS_GRACE_S if grace_s is None else grace_s)
    for t in left():
        t.join(max(deadline - time.monotonic(), 0.0))
    stuck = left()
    if not stuck:
        return                      # the interpreter ends as always
    import atexit

    print(f"thermocomp: {len(stuck)} thread(s) left running after the signal "
          f"({', '.join(t.name for t in stuck)}): ended with the process", file=sys.stderr)
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            pass
    os._exit(code)


def end_local_workers() -> None:
    """Stop loky's reusable workers (a joblib launcher's, when a sweep ends).  loky keeps them for
    the next ``Parallel`` in this process, with the environment of their start: a second sweep in
    the same process (a notebook, a test) ran its jobs under the first one's parent run id (a run
    its store does not have: every job failed) and its failed-jobs folder (deleted)."""
    loky = sys.modules.get("joblib.externals.loky.reusable_executor")
    # (its module's private global: get_reusable_executor() would start an executor to stop)
    executor = getattr(loky, "_executor", None)
    if executor is not None:
        executor.shutdown(wait=True)


# The cyclic garbage collector's thresholds for a command's process (Python's: 700, 10, 10).  Such
# a process makes millions of objects it keeps (the libraries it imports: pandas, sklearn, SciPy,
# MLflow) and few cycles it drops; at 700 allocations a young collection, and the full ones walk
# what was kept again and again (`thermocomp run` on the short default study: 5.5 -> 4.8 s of CPU
# tracked, 3.7 -> 3.4 untracked; a test process collecting the suite: 3.4 -> 1.05 s in the
# collector).  Cycles still go, after 10,000 allocations instead of 700.
GC_THRESHOLDS = (10_000, 10, 10)


def collect_less() -> None:
    """The collector's thresholds of :data:`GC_THRESHOLDS`, for a process of the project's own
    (the console command, a test process): never set by a library call of
    :func:`thermocomp.shell.cli.main`."""
    gc.set_threshold(*GC_THRESHOLDS)
