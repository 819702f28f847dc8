"""The run's log file (thermocomp.base.log.run_log)."""

import logging
import shutil

from thermocomp.base.log import logger, run_log


class _Kept(logging.Handler):
    """The logger's records, whatever an earlier test's ``configure`` did to propagation."""

    def __init__(self):
        super().__init__(logging.WARNING)
        self.lines = []

    def emit(self, record):
        self.lines.append(record.getMessage())


def test_a_run_log_removed_under_the_run_does_not_fail_the_run(tmp_path):
    """A temp cleaner (or a hand's `rm -rf /tmp/thermocomp-log-*`) removed the run's log folder
    while it ran: copying the log into the out folder at the end raised FileNotFoundError and
    the run, its outputs written, exited 1.  Logging never kills a run: the copy is left out
    and said."""
    kept = _Kept()
    logger.addHandler(kept)
    try:
        with run_log(lambda: tmp_path) as path:
            logger.info("a line")
            shutil.rmtree(path.parent)
    finally:
        logger.removeHandler(kept)
    assert not (tmp_path / path.name).exists()
    assert any("removed while the run went on" in line for line in kept.lines)


def test_the_run_log_is_copied_into_the_out_folder(tmp_path):
    with run_log(lambda: tmp_path) as path:
        logger.info("a line the copy holds")
    assert "a line the copy holds" in (tmp_path / path.name).read_text()
    assert not path.parent.exists()
