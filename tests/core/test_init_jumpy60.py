"""A number that is no temperature, proposed as one by `init` (session 60,
benchmarks/bench_new_machines60.py: the six-spindle lathe's gateway tags the gauged part with its
spindle, ``probe.spindle`` 1-6): read as °C, silently.  `init` now warns where a tenth of a
proposed temperature's steps are 1 K or more, naming the setting."""

from __future__ import annotations

from thermocomp.shell.cli import main


def _record(path, rows=120):
    lines = ["time,T_motor_raw,spindle,dX [um]"]
    for i in range(rows):
        motor = 20 + min(i, 8) * 0.6 + 0.01 * (i % 3)     # a warm-up: 0.6 K a step, 8 steps
        lines.append(f"{60 * i},{motor:.2f},{i % 6 + 1},{0.1 * i:.1f}")
    path.write_text("\n".join(lines) + "\n")
    return path


def test_init_warns_of_a_proposed_temperature_that_jumps_like_an_index(tmp_path, capsys):
    path = _record(tmp_path / "ms6.csv")
    assert main(["init", str(path), "data.test_fraction=0.25", f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "warning: 'spindle' is proposed as a temperature" in said
    assert "data.roles.state=['spindle']" in said
    assert "'T_motor_raw' is proposed" not in said            # a warm-up is no index
