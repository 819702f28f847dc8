"""The benches' one command line (benchmarks/_cli.py): ``python benchmarks/X.py COMMAND ARG...``.

A bench that takes a command prints its docstring (its usage) and exits 2 when the command is
missing, unknown or given words that do not fit it, and runs nothing then.  Every such bench is
imported in one child process (the benches put their folders on ``sys.path`` and set environment
variables as they import) and its ``main([])`` called there; no bench's own work is run.
"""

from __future__ import annotations

import io
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"

# the benches whose first word is a command (converted to _cli.run_commands on stop 70)
COMMAND_BENCHES = (
    "bench_acc107", "bench_acc112", "bench_adapt112", "bench_adapt112b", "bench_amb94", "bench_anchor66",
    "bench_ati106", "bench_ati106b", "bench_ati90",
    "bench_audit100", "bench_audit103", "bench_audit105", "bench_audit106", "bench_audit107",
    "bench_audit107b", "bench_audit107c", "bench_audit86", "bench_audit86b", "bench_audit87", "bench_audit88",
    "bench_audit88b", "bench_audit89", "bench_audit91", "bench_audit93", "bench_audit94", "bench_audit95",
    "bench_audit96", "bench_audit96b", "bench_audit97", "bench_audit98", "bench_audit99", "bench_auto101",
    "bench_auto105", "bench_auto105b", "bench_auto106", "bench_auto106b", "bench_auto106c", "bench_auto106d",
    "bench_auto106e", "bench_auto107", "bench_auto107b", "bench_auto70", "bench_auto73", "bench_auto74",
    "bench_auto76", "bench_auto80", "bench_auto81b", "bench_auto82", "bench_auto82b", "bench_auto84",
    "bench_auto84b", "bench_auto84c", "bench_auto85", "bench_auto85b", "bench_auto85c", "bench_auto86",
    "bench_auto86b", "bench_auto87", "bench_auto87b", "bench_auto87c", "bench_auto87d", "bench_auto88",
    "bench_auto88b", "bench_auto89", "bench_auto91", "bench_auto92", "bench_auto92b", "bench_auto92c",
    "bench_auto93", "bench_auto93b", "bench_auto93c", "bench_auto93d", "bench_auto94", "bench_auto94b",
    "bench_auto94c", "bench_auto95", "bench_auto95b", "bench_auto95c", "bench_auto96", "bench_auto96b",
    "bench_auto97", "bench_auto98", "bench_auto98b", "bench_auto99", "bench_auto_ati58", "bench_auto_hmc59",
    "bench_auto_hmc60", "bench_auto_vtl60", "bench_autoati75", "bench_autocheck65", "bench_autodiag100",
    "bench_autodiag99", "bench_autodiag99b", "bench_autofb72", "bench_autoloss68", "bench_automore69",
    "bench_autorep65", "bench_autorule69", "bench_badin96", "bench_bar91", "bench_bar91b", "bench_between73",
    "bench_between74", "bench_bits85", "bench_blame105", "bench_blame95", "bench_blame95b", "bench_blame96",
    "bench_blocks68", "bench_c111",
    "bench_cadence72", "bench_cadence74", "bench_cascade81", "bench_catman70",
    "bench_cdrop77", "bench_cflags100", "bench_ci100", "bench_ci100b", "bench_ci100c", "bench_ci101",
    "bench_ci101b", "bench_ci101c", "bench_ci102a", "bench_ci102b", "bench_ci102c", "bench_ci102d",
    "bench_ci102e", "bench_ci102f", "bench_ci102g", "bench_ci102h", "bench_ci102i", "bench_ci102j",
    "bench_ci104a", "bench_ci104b", "bench_ci104d", "bench_ci104f", "bench_ci104g", "bench_ci104h",
    "bench_ci108a", "bench_ci108b", "bench_ci108c", "bench_ci108d", "bench_ci108e", "bench_ci109a",
    "bench_ci109b", "bench_ci109c", "bench_ci109d", "bench_ci98", "bench_ci99", "bench_ci99b", "bench_cin103",
    "bench_clamp74", "bench_clamp75", "bench_clamp78", "bench_clean69", "bench_clockset71", "bench_cmon76",
    "bench_cmon80", "bench_cmon82", "bench_cmon82b", "bench_cmon82c", "bench_cmon83", "bench_cmon84",
    "bench_cmon85", "bench_cmon86", "bench_cmon87", "bench_cmon88", "bench_cmon89", "bench_cmon89b",
    "bench_cmon91", "bench_cmon92", "bench_cmon92b", "bench_cmon93", "bench_cmon94", "bench_con109",
    "bench_con111", "bench_con112",
    "bench_connect72", "bench_cvpick69", "bench_data101", "bench_data103", "bench_data86", "bench_data86b",
    "bench_data87", "bench_data88", "bench_data88b", "bench_data89", "bench_data89b", "bench_data90",
    "bench_data91", "bench_data92", "bench_data92b", "bench_data93", "bench_data94", "bench_data95",
    "bench_dates85", "bench_dep100", "bench_dep100b", "bench_dep101", "bench_dep103", "bench_dep105",
    "bench_dep105b", "bench_dep105c", "bench_dep105d", "bench_dep106", "bench_dep106b", "bench_dep107",
    "bench_dep107b", "bench_dep107c", "bench_dep108", "bench_dep108b", "bench_dep108c", "bench_dep108d",
    "bench_dep108e", "bench_dep108f", "bench_dep109", "bench_dep93", "bench_dep95", "bench_dep98",
    "bench_dep98b", "bench_dep99", "bench_dep99b", "bench_deploy73", "bench_deploy87", "bench_deploy88",
    "bench_deploy89", "bench_derive71", "bench_diag100", "bench_diag101", "bench_diag103", "bench_diag103b",
    "bench_diag105", "bench_diag106", "bench_diag106b", "bench_diag106c", "bench_diag106d", "bench_diag106e",
    "bench_diag106f", "bench_diag107", "bench_diag107b", "bench_diag107c", "bench_diag107d", "bench_diag108",
    "bench_diag108b", "bench_diag109", "bench_diag111", "bench_diag111d", "bench_diag112", "bench_diag112b",
    "bench_diag112c", "bench_diag112d", "bench_diag112e",
    "bench_diag70", "bench_diag73", "bench_diag74",
    "bench_diag75", "bench_diag76", "bench_diag77", "bench_diag81b", "bench_diag81c", "bench_diag82",
    "bench_diag82b", "bench_diag82c", "bench_diag82d", "bench_diag82e", "bench_diag82f", "bench_diag82g",
    "bench_diag83",
    "bench_diag83b", "bench_diag84", "bench_diag84b", "bench_diag85", "bench_diag85b", "bench_diag86",
    "bench_diag86b", "bench_diag87", "bench_diag87b", "bench_diag87c", "bench_diag88", "bench_diag88b",
    "bench_diag88c", "bench_diag88d", "bench_diag89", "bench_diag89b", "bench_diag89c", "bench_diag89d",
    "bench_diag91", "bench_diag91b", "bench_diag91c", "bench_diag92", "bench_diag92b", "bench_diag92c",
    "bench_diag92d", "bench_diag92e", "bench_diag93", "bench_diag93b", "bench_diag94", "bench_diag94b",
    "bench_diag94c", "bench_diag95", "bench_diag95b", "bench_diag95c", "bench_diag95d", "bench_diag96",
    "bench_diag96b", "bench_diag97", "bench_diag98", "bench_diagfault65", "bench_diagfault72",
    "bench_diagpower67", "bench_diagref65", "bench_drift74", "bench_dup99", "bench_effects99", "bench_env92",
    "bench_env92b", "bench_env93", "bench_env93b", "bench_env94", "bench_env94b", "bench_env94c",
    "bench_fault70", "bench_faults71", "bench_freeze83", "bench_freeze83b", "bench_freeze83c",
    "bench_freeze84", "bench_freeze90", "bench_freeze91", "bench_freeze92", "bench_freezeu100",
    "bench_fresh69", "bench_gate71", "bench_gate77", "bench_guard111", "bench_guard111b", "bench_guard112",
    "bench_guard112b", "bench_guard112c", "bench_guard112d", "bench_guard95", "bench_guard96", "bench_ham98",
    "bench_initlag67", "bench_iso67", "bench_jig68", "bench_jump94", "bench_jump94b", "bench_kelvin97",
    "bench_keysight70", "bench_lab83", "bench_lagwithin68", "bench_margin67", "bench_mon101", "bench_mon103",
    "bench_mon103b", "bench_mon103c", "bench_mon103d", "bench_mon105", "bench_mon105b", "bench_mon105c",
    "bench_mon105d", "bench_mon105e", "bench_mon106", "bench_mon106b", "bench_mon106c", "bench_mon107",
    "bench_mon71", "bench_mon72", "bench_mon73", "bench_mon74", "bench_mon75", "bench_mon77", "bench_mon81",
    "bench_mon81g", "bench_mon82", "bench_mon82b", "bench_mon82c", "bench_mon82d", "bench_mon83",
    "bench_mon83b", "bench_mon83c", "bench_mon83d", "bench_mon84", "bench_mon84b", "bench_mon84c",
    "bench_mon84d", "bench_mon85", "bench_mon85b", "bench_mon86", "bench_mon86b", "bench_mon87",
    "bench_mon88", "bench_mon89", "bench_mon89b", "bench_mon91b", "bench_mon97", "bench_mon97b",
    "bench_mon98", "bench_mon98b", "bench_mon98c", "bench_monb92", "bench_monb92b", "bench_monb93",
    "bench_monb93b", "bench_monb94", "bench_moretest68", "bench_names96", "bench_names97", "bench_names97b",
    "bench_nested63", "bench_notes100", "bench_packflags100", "bench_pair70", "bench_pair82", "bench_pde66",
    "bench_pen0b69", "bench_perf106", "bench_perf87", "bench_perf87b", "bench_perf88", "bench_planted69",
    "bench_planted72", "bench_power78", "bench_qr103", "bench_qr103b", "bench_quiet93", "bench_quiet93b",
    "bench_quiet94", "bench_quiet94b", "bench_quiet94c", "bench_range73", "bench_range77", "bench_rate71",
    "bench_rate83", "bench_refusals100", "bench_remeasure62", "bench_restart98", "bench_review95",
    "bench_review96", "bench_rigdiag70", "bench_settle95", "bench_settle96", "bench_speedsq68", "bench_st100",
    "bench_st100b", "bench_st101", "bench_st102", "bench_st102b", "bench_st103", "bench_st103b",
    "bench_st103c", "bench_st105", "bench_st105b", "bench_st106", "bench_st106b", "bench_st106c",
    "bench_st107", "bench_st107b", "bench_st107c", "bench_st108", "bench_st108b", "bench_st108c",
    "bench_st108d", "bench_st109", "bench_st109b", "bench_st111",
    "bench_st111b", "bench_st111c", "bench_st112", "bench_st112b", "bench_st93", "bench_st93b",
    "bench_st94", "bench_st94b",
    "bench_st95", "bench_st95b", "bench_st96", "bench_st96b", "bench_st97", "bench_st97b", "bench_st97c",
    "bench_st97d", "bench_st98", "bench_st98b", "bench_st99", "bench_st99b", "bench_st99c", "bench_stable67",
    "bench_step93", "bench_step93b", "bench_step99", "bench_stranger63", "bench_stranger64",
    "bench_stranger65", "bench_stranger66", "bench_stranger68", "bench_stranger69", "bench_stranger74",
    "bench_stranger75", "bench_stranger76", "bench_stranger77", "bench_stranger78", "bench_stranger80",
    "bench_stranger81", "bench_stranger82", "bench_stranger82b", "bench_stranger83", "bench_stranger84",
    "bench_stwires100", "bench_sub71", "bench_swap99", "bench_sweepdvc63", "bench_trace112", "bench_twins98",
    "bench_twolog70",
    "bench_verify82", "bench_volfleet63", "bench_volstranger66", "bench_wires100", "bench_wires99",
    "bench_within67", "bench_zerocheck67", "bench_zerofew67", "bench_zerofold68",
)

# Run in the child: per bench, main([])'s status and what it printed, and, for every usage line of
# its docstring (``X.py WORD ARG ...``; ``[...]`` optional, ``...`` more of the same), whether
# WORD is a command the words after it fit (the commands seen as the bench hands them over).
PROBE = r'''
import contextlib, importlib, io, json, re, shlex, sys
sys.path.insert(0, sys.argv[1])
try:
    import _cli
except ModuleNotFoundError:
    _cli = None
seen = {}
if _cli is not None:
    handed = _cli.run_commands

    def recording(doc, commands, argv, **kwargs):
        seen["commands"] = commands
        return handed(doc, commands, argv, **kwargs)
    _cli.run_commands = recording

out = {}
for name in sys.argv[2:]:
    seen.clear()
    try:
        module = importlib.import_module(name)
    except ModuleNotFoundError as exc:          # an optional extra the bench needs
        out[name] = {"skip": str(exc)}
        continue
    printed = io.StringIO()
    try:
        with contextlib.redirect_stdout(printed):
            status = module.main([])
    except BaseException as exc:
        status = f"{type(exc).__name__}: {exc}"[:200]
    doc, usage = module.__doc__ or "", []
    for line in doc.splitlines():
        found = re.search(re.escape(name) + r"\.py\s+(.*)", line)
        words = [w for w in shlex.split(re.sub(r"\[[^\]]*\]", "", found.group(1).split("#")[0]))
                 if w != "..."] if found else []
        if words:
            command = seen.get("commands", {}).get(words[0])
            usage.append([line.strip(), command is not None and _cli._fits(command, words[1:])])
    out[name] = {"status": status, "printed": printed.getvalue(), "doc": doc, "usage": usage}
print(json.dumps(out))
'''


@pytest.fixture(scope="module")
def probed(tmp_path_factory) -> dict:
    """Every command bench's ``main([])`` and usage lines, from one child process."""
    run = subprocess.run([sys.executable, "-c", PROBE, str(BENCHMARKS), *COMMAND_BENCHES],
                         capture_output=True, text=True, cwd=tmp_path_factory.mktemp("benches"))
    assert run.returncode == 0, run.stderr[-3000:]
    return json.loads(run.stdout.splitlines()[-1])


def _cli():
    sys.path.insert(0, str(BENCHMARKS))
    try:
        import _cli
    finally:
        sys.path.remove(str(BENCHMARKS))
    return _cli


@pytest.mark.parametrize("name", COMMAND_BENCHES)
def test_a_bench_without_a_command_prints_its_usage_and_returns_2(probed, name):
    got = probed[name]
    if "skip" in got:
        pytest.skip(got["skip"])
    assert got["doc"].strip(), f"{name} has no docstring to print"
    assert got["status"] == 2
    assert got["printed"] == got["doc"] + "\n"


@pytest.mark.parametrize("name", COMMAND_BENCHES)
def test_every_command_line_a_bench_documents_is_one_of_its_commands(probed, name):
    got = probed[name]
    if "skip" in got:
        pytest.skip(got["skip"])
    assert got["usage"], f"{name}'s docstring shows no command line"
    assert [line for line, fits in got["usage"] if not fits] == []


def test_every_bench_that_dispatches_by_run_commands_is_probed():
    # run_commands itself, or through lab_matrix.main / bench_ci101c.measured (which call it)
    calls = ("run_commands(", "lab_matrix.main(", "measured(__doc__")
    using = {p.stem for p in BENCHMARKS.glob("bench_*.py") if any(c in p.read_text() for c in calls)}
    assert using == set(COMMAND_BENCHES)


def test_the_first_word_picks_the_command_and_the_rest_are_its_arguments_in_order(capsys):
    cli, calls = _cli(), []
    commands = {"pair": lambda first, second: calls.append(("pair", first, second)),
                "many": lambda *words: calls.append(("many", *words))}
    assert cli.run_commands("usage", commands, ["pair", "a", "b"]) == 0
    assert cli.run_commands("usage", commands, ["many"]) == 0
    assert cli.run_commands("usage", commands, ["many", "x", "y", "z"]) == 0
    assert calls == [("pair", "a", "b"), ("many",), ("many", "x", "y", "z")]
    assert capsys.readouterr().out == ""


@pytest.mark.parametrize("argv", [[], ["nope"], ["pair", "a"], ["pair", "a", "b", "c"], ["a", "pair"]])
def test_a_missing_unknown_or_unfitting_command_prints_the_usage_returns_2_and_runs_nothing(capsys, argv):
    cli, calls = _cli(), []
    commands = {"pair": lambda first, second: calls.append((first, second))}
    assert cli.run_commands("Usage: X.py pair A B", commands, argv, cpu=sys.stdout) == 2
    assert capsys.readouterr().out == "Usage: X.py pair A B\n"
    assert calls == []


def test_the_cpu_line_goes_to_the_stream_asked_after_the_command():
    cli, stream = _cli(), io.StringIO()
    assert cli.run_commands("usage", {"say": lambda: print("said", file=stream)}, ["say"],
                           cpu=stream) == 0
    said, line = stream.getvalue().splitlines()
    assert said == "said"
    assert re.fullmatch(r"CPU s \(user \+ sys\) of this process: \d+\.\d", line)


def test_a_command_s_folder_is_made_and_resolved(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    folder = _cli().made_folder("a/b")
    assert folder == (tmp_path / "a" / "b").resolve() and folder.is_dir()
    assert _cli().made_folder("a/b") == folder          # there already: the same folder


def test_a_commands_project_root_keeps_what_an_earlier_command_wrote(tmp_path, monkeypatch):
    # before (review95): bench_mon88's ``_root`` (bar91, freeze90, mon89/89b, mon91b, monb92,
    # quiet93b, step93/93b, jump94/94b) made ROOT anew: jump94b's ``healthy`` deleted the
    # ``trace-main.json`` its ``trace`` had written there
    import thermocomp

    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("THERMOCOMP_ROOT", "elsewhere")
    root = _cli().project_root("a/root")
    assert root == (tmp_path / "a" / "root").resolve() and root.is_dir()
    conf = Path(thermocomp.__file__).resolve().parents[2] / "conf"
    assert (root / "conf").resolve() == conf.resolve()
    assert os.environ["THERMOCOMP_ROOT"] == str(root)
    (root / "trace-main.json").write_text("{}")              # the first command's output
    assert _cli().project_root("a/root") == root                # the second command's root
    assert (root / "trace-main.json").read_text() == "{}" and (root / "conf").is_symlink()


def test_a_project_root_links_the_conf_a_bench_names(tmp_path, monkeypatch):
    # review96: the benches that linked their own tree's conf (audit86b, auto86b, deploy88,
    # deployed_as_scored59, audit89) keep it through project_root
    monkeypatch.setenv("THERMOCOMP_ROOT", "elsewhere")
    conf = tmp_path / "bench-tree" / "conf"
    conf.mkdir(parents=True)
    root = _cli().project_root(str(tmp_path / "root"), conf)
    assert (root / "conf").resolve() == conf.resolve()


def test_audit89s_healthy_keeps_what_its_faults_command_wrote(tmp_path):
    # before (review96): bench_audit89's ``healthy`` made ROOT anew (``_root(fresh=True)``),
    # deleting what another command had written there
    run = subprocess.run([sys.executable, str(BENCHMARKS / "bench_review96.py"), "keep",
                          str(tmp_path / "root")], capture_output=True, text=True, cwd=tmp_path)
    assert run.returncode == 0, run.stderr[-2000:]
    assert "faults.json kept" in run.stdout and ": MET" in run.stdout
    assert (tmp_path / "root" / "faults.json").read_text() == "{}"
