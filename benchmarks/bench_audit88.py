"""audit88: the README and every page of docs/ followed literally on a fresh clone (a log; findings below).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_audit88.py docs ROOT
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_audit88.py commands ROOT
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_audit88.py families ROOT OUT

``docs``: the checks a reader makes by eye, over README.md and docs/**.md of the project at
``ROOT``: every ``group=option`` the pages name (``a,b`` a sweep, ``a|b`` a list that should
be whole; the groups a lab or ``diagnose`` writes options into, ``data``, ``sim``,
``experiment``, left out) against ``conf/<group>/``; every dotted config key a code span names
against the config and the arguments of the objects it builds (``_target_``); every relative
link and its anchor; every ``thermocomp`` stage against the commands synopsis of outputs.md.
One line per finding; the dotted names that are no config key are listed apart, to be read (on
d76bdde2 all 16 are an output's key, ``compensator.json``'s ``monitor.rounding``, a MATLAB
struct's field or cli.md's typo on purpose).

``commands``: every ``thermocomp <stage> ...`` the pages name in a code span (232 on
d76bdde2, 50 distinct once placeholders are dropped), composed by ``thermocomp <stage> <its
overrides> --cfg job``: its exit status where it is not 0, and the typos of the docs' own
examples (``run model=nosuch --cfg job``, ``init --cfg job <file>``, ``run +diagnose.alpah=0.05``)
with what they say.

``families``: ``thermocomp run data=fl_thermal model=<family>`` for every family on the 90/10
cut and on the authors' 60/20/20 split (``data.split_order=[train,test,val]
data.test_fraction=0.2 data.val_fraction=0.2``), ``track=false plots=none``, into ``OUT``:
test MAE per channel and the means of MAE and RMSE, to hold against README's table and
own-data.md's (CPU user + sys per run).

The bar of an audit (written into this docstring after findings 1-8 had been found on main,
before findings 9-15 and before any bench command ran on the branch: said): every command of the
README and of every docs page runs as written, or is a finding; every figure a page states for a
command it gives is the run's, to the digit printed; every option / key a page names is one the
code knows, every key the code knows is in docs/cli.md (or data-format.md for data.*); every
link and anchor resolves; ``mkdocs build --strict`` passes. KEPT where every finding is mended
on the branch with a test that fails on d76bdde2 (code: tests/shell/test_audit88.py; a doc claim
a test can check: tests/test_docs.py) and the pages' own commands still pass; a finding left is
listed as such.

What was run (2026-12-04, d76bdde2 cloned into /tmp/audit88/clone, main's venv behind
``.venv/bin/*`` wrappers with PYTHONPATH on the clone's src, ``make install`` a no-op by its
stamps; 2 cores shared by seven sessions, load 4-9):

(0) README: ``make run``'s two commands print its table to the digit (E_X / E_Y / E_Z 0.75 /
1.42 / 5.80 µm, Rsd SM 0.72 / 1.38 / 5.46); ``run data=fl_thermal`` E_ch5 3.05 (the expect),
mean RMSE 4.06, before 16.7: as written. ``mkdocs build --strict``: passes (1.2 s). Every
relative link and anchor of README and docs/ resolves (README's anchors into docs/ too, which
mkdocs does not check); no docs page links outside docs/. Every key of the composed config
(465 leaves over every group option) is in cli.md (data.* in data-format.md; ``model.estimator.*``
/ ``sim.generator.*`` as the objects' arguments): none missing.

(1) ``families`` (seed-free: the measured record): all 14 rows of own-data.md's table and
README's to the digit: 90/10 RMSE mean mlr 4.06, pcr 6.48, arx 4.81, lagbank 4.78, hammerstein
2.95, lstm 2.96, auto 2.48; 60/20/20 MAE mean 9.18 / 3.17 / 10.96 / 3.08 / 2.48 / 9.07 / 2.12,
every channel as printed. CPU (s, loaded): 2.4 / 2.4 / 2.6 / 3.6 / 6.3 / 42.2 / 38.0 on 90/10
(the page: 2.4 / 2.7 / 2.9 / 3.9 / 6.8 / 41.3 / 35.4), 60/20/20 2.5 / 2.5 / 2.5 / 3.1 / 4.0 /
15.9 / 10.5 (2.3 / 2.3 / 2.8 / 3.2 / 3.6 / 15.3 / 9.8).

(2) The pages' command blocks (what tests/test_readme.py runs, here in one clone, in nav order):
outputs, simulation (my_column: 2 campaigns, 2402 rows, E_X 2.78 -> 0.47 µm: as written),
sweeps (the 4-job sweep, compare, promote twice: v1 @champion, then "no new version"),
monitoring (its table to the digit), diagnose, own-data: every block exit 0, every expect and
output table matched.

Findings (state on fix/audit88):

1. data-format.md told ``adapt=bias`` (exit 2: "unknown adapt 'bias'; options ...: default");
   the key is ``adapt.method=bias``. MENDED (doc); tests/test_docs.py
   ``test_a_group_option_the_docs_name_is_one_the_group_has`` fails on main.
2. outputs.md's "every stage takes" list ``model=mlr|pcr|arx|arx_rf|lstm`` left out lagbank,
   hammerstein, auto. MENDED; ``test_a_list_of_a_groups_options_names_them_all`` fails on main.
3. ``thermocomp train --help`` listed ``model=...|hammerstein``, no ``auto``. MENDED (code,
   commands.py); test_audit88 ``test_train_help_names_every_model_family`` fails on main.
4. outputs.md's synopsis ("one subcommand per stage") left out ``init`` and ``rows``. MENDED;
   ``test_the_synopsis_of_the_commands_names_every_stage`` fails on main.
5. cli.md's example of a group a command does not read, ``thermocomp serve model=arx``, is
   not refused (serve composes the model group: it serves a run's model.pkl); the example is
   now ``compare model=arx`` with its message. MENDED;
   ``test_the_cli_references_example_of_a_group_not_read_is_what_the_command_says`` runs it
   and fails on main.
6. ``thermocomp <stage> --cfg job`` (how outputs.md and cli.md say to see what a command
   composes) with a mistyped key or option: Hydra's multi-line message and
   "HYDRA_FULL_ERROR", exit 1 (a bug, by the exit statuses: the contract says 2 for bad
   config). Its overrides are now composed first as a run's are: one line, exit 2, the
   closest option / key. MENDED (cli.py); test_audit88 (3 typos) fails on main.
7. ``thermocomp init --cfg job <file>`` (and ``rows``) took ``job`` as the file
   (``data.path=job``) and stopped on argparse's usage. MENDED (cli.py
   ``_positional_path``: a Hydra flag's word is the flag's); test_audit88 fails on main.
8. ``thermocomp run +diagnose.alpah=0.05`` (cli.md's typo, on a command that does not read
   diagnose) said "did you mean 'diagnose.alpha'?", which run then refuses. Now it says the
   closest key is of a group run does not read. MENDED (overrides.explain); test_audit88
   fails on main.
9. diagnose.md's door table (its first commands, run as written) said E_Z ``6.25 -> 1.07``,
   CV ``6.54 -> 0.87``, three effects (the door's lag at 3600 s and its raw signal); the run
   prints ``6.25 -> 1.02``, ``6.54 -> 0.92``, two effects (the door's lag at 7200 s); run twice
   (two clones, load 4-9): the same. E_Y's family-wise p said 0.00017, the run 0.00005 (1/20001).
   MENDED: the table now the run's and marked ``readme-test: output``, so the page's test
   checks it (tests/test_readme.py ``docs/diagnose.md`` passes on the branch, 134 s; main's
   table against the same output: the E_Z line missing).
10. layout.md described a flat ``src/thermocomp/`` (stats, iso10791, evaluation, plots,
    deploy ... side by side); the code is four layers (base, core, apps, shell). MENDED;
    ``test_the_layout_names_every_layer_and_package_of_the_source`` fails on main.
11. index.md's table left out two pages of the nav (measured/monitoring.md,
    measured/diagnose.md) and said every command of the pages is run (those a comment skips
    are not). MENDED; ``test_the_home_page_links_every_page_of_the_site`` fails on main.
12. install.md said ``make run`` calls ``make install``; it installs the core alone
    (``$(CORE)``), and the skip's reason said the README's ``make run`` ran it. MENDED;
    ``test_the_make_targets_said_to_install_every_extra_do`` (against the Makefile) fails on main.
13. to-the-machine.md's ``thermocomp rows`` example gave ``hydra.searchpath=[file://init/conf]``:
    found from the project root only (typed in /tmp: "unknown data 'spindle_test'"); every other
    page writes ``$PWD``. MENDED; ``test_a_config_searchpath_the_docs_give_is_absolute`` fails on
    main.
14. cli.md ("every command, override group, output file and key") named none of the command's
    own flags: ``-q`` / ``--quiet``, ``-v`` / ``--verbose``, ``--version`` / ``-V``, ``-h`` (nor
    that ``thermocomp`` alone exits 2). MENDED (extension section);
    ``test_every_flag_of_the_command_is_in_the_cli_reference`` fails on main.
15. models.md's table on the default data, every row re-run as written: all to the digit but
    ``lstm``'s (page 0.73 / 0.28, 1.34 / 0.53, 5.36 / 2.35, after 0.76 / 1.40 / 5.63, one-step
    0.58 / 0.58 / 1.05; run 0.74 / 0.29, 1.33 / 0.53, 5.34 / 2.46, 0.78 / 1.39 / 5.63, 0.59 / 0.58 /
    1.05, twice, two clones: the network trains on one thread, seeded); the row dates from
    2026-11-28, before stop 64's cheaper LSTM training. MENDED (doc); no test: the row is a
    measured table (an LSTM run per CI job for one row was not judged worth it).

An existing test changed: tests/shell/test_cli.py's case ``run +diagnose.alpah=0.05`` asserted
the hint finding 8 removes; it now asks the hint of ``diagnose``, which reads the group.

Checked and as written (no finding): the DVC study (dvc.md: ``dvc repro`` twice, the second
"Data and pipelines are up to date", ``dvc metrics show`` the headline table); the skipped
to-the-machine route (``run model=arx`` -> ``export`` C -> ``cc`` -> ``./stream``, its check
pack ``sh check/check.sh``: 13 campaigns within tolerance; ``export`` of the champion as ST);
evaluation.md's E_P95 figures (E_Z 39 -> 9.8 µm at 4 h, 2.4 -> 3.8 at 5 min); models.md's table
on the default data (every row but lstm's, finding 15) and evaluation.md's ATI columns (ATI,
coldest, warmest, one model: 0.76 / 0.26 ... 5.46 / 2.60); the OPC UA route with
``adapt.method=bias`` (twin + connect, 8 campaigns, 588 samples: compensated RMS 0.710 / 1.275 /
3.769 µm = ``replay adapt.method=bias``); ``export.format=onnx`` refused; sweeps.md's skipped
``serve`` of the champion and its ``curl``: C_X / C_Y / C_Z -0.36114180990146894 /
-0.15504600462203655 / -3.1013423131717808, the exported C's first row of K03 to the last digit;
a record of my own, fresh seed 9221 (``simulate sim=swiss_lathe_door seed=9221`` written as
own-data.md's lab export): ``init`` asks for the error column, then for the sample period, each
naming the key, then writes a config whose printed ``next:`` runs: test RMSE 3.3572 µm, equal to
the page's hand-written ``lab.yaml`` on the same files.

``commands`` (each ~2.5 min wall at load 4-9, the composing subprocesses' CPU not counted by
its CPU line): on d76bdde2 50 distinct commands, 4 not exit 0: ``rows <file>`` (README),
``init <file>``, ``init data.sample_period_s=15`` (cli.md) exit 2 with argparse's usage ("invalid
choice: 'data.path=job'": finding 7), ``run experiment=diagnosed`` (the folder diagnose writes
first) exit 1, Hydra's trace (finding 6); its typo lines: ``run model=nosuch --cfg job`` exit 1,
18 lines; ``run nosuch.key=1 --cfg job`` exit 1, 7 lines; ``init --cfg job --package data
<file>`` exit 2, 9 lines of usage; ``run +diagnose.alpah=0.05`` "did you mean 'diagnose.alpha'?".
On the branch 51 distinct, 3 not exit 0, each exit 2 in one line: ``run model=nosuch`` and
``compare model=arx`` (cli.md's examples of a refusal, on purpose) and ``run
experiment=diagnosed`` ("unknown experiment 'diagnosed'; options ..."); the typo lines: exit 2
one line each, ``init --cfg job --package data <file>`` exit 0 printing ``path: <file>``, the
alpah typo "the closest, diagnose.alpha: thermocomp run does not read the diagnose group".
``docs``: 4 findings on d76bdde2 (1, 2, 4 twice), 0 on the branch (2.0 s CPU each).

Not findings (checked): every path a code span names exists or is an output; hydra.cc the one
external link (not fetched: no network).

Left: a relative ``hydra.searchpath`` is read from the current folder (Hydra's), where every
other relative path is the project root's (outputs.md): rooting it as ``hydra.sweep.dir`` is
(``base/paths.rooted_override``) is a code change not made here; tests/shell/test_cli_shell.py
``test_launcher_without_venv_fails_clearly_before_anything`` fails on main as on the branch in
these worktrees (exit 127 where it expects 0: the launcher finds no ``thermocomp`` in this
environment), the environment's, not a finding of this audit.
"""

from __future__ import annotations

import json
import re
import shlex
import subprocess
import sys
from pathlib import Path

import yaml
from _cli import made_folder, run_commands

FAMILIES = ("mlr", "pcr", "arx", "lagbank", "hammerstein", "lstm", "auto")
SPLITS = {"90/10": [], "60/20/20": ["data.split_order=[train,test,val]", "data.test_fraction=0.2",
                                     "data.val_fraction=0.2"]}
USER_GROUPS = ("hydra", "data", "sim", "experiment")     # options a lab, init or diagnose write


def _pages(root: Path) -> list[Path]:
    return [root / "README.md", *sorted((root / "docs").rglob("*.md"))]


def _leaves(node, prefix: str = "") -> set[str]:
    out = set()
    if isinstance(node, dict):
        for key, value in node.items():
            out |= {prefix + str(key), *_leaves(value, f"{prefix}{key}.")}
    return out


def _known_keys(root: Path) -> set[str]:
    """Every key of every group option, and the arguments of the objects built from ``_target_``."""
    import importlib
    import inspect

    def arguments(node, prefix: str, out: set[str]) -> None:
        if not isinstance(node, dict):
            return
        if node.get("_target_"):
            module, _, name = node["_target_"].rpartition(".")
            built = getattr(importlib.import_module(module), name)
            out |= {prefix + p for p in inspect.signature(built).parameters}
        for key, value in node.items():
            arguments(value, f"{prefix}{key}.", out)

    known: set[str] = set()
    for group in (p for p in (root / "conf").iterdir() if p.is_dir() and p.name != "hydra"):
        for option in group.glob("*.yaml"):
            node = yaml.safe_load(option.read_text()) or {}
            node.pop("defaults", None)
            prefix = "" if "@package _global_" in option.read_text() else f"{group.name}."
            known |= _leaves(node, prefix)
            arguments(node, prefix, known)
    common = yaml.safe_load((root / "conf" / "common.yaml").read_text())
    common.pop("hydra", None)
    return known | _leaves(common)


def docs(root: str) -> None:
    """The findings a reader makes by eye (see the module docstring)."""
    base = Path(root).resolve()
    sys.path.insert(0, str(base / "tests"))
    from test_docs import _heading_anchors, _links

    groups = sorted(p.name for p in (base / "conf").iterdir() if p.is_dir() and p.name not in USER_GROUPS)
    options = {g: {p.stem for p in (base / "conf" / g).glob("*.yaml")} for g in groups}
    choice = re.compile(r"(?:^|(?<=[\s`'\"]))(%s)=([\w|,]+)" % "|".join(groups), re.M)
    known = _known_keys(base)
    every = "|".join(p.name for p in (base / "conf").iterdir() if p.is_dir() and p.name != "hydra")
    dotted = re.compile(r"^[+~]{0,2}((?:%s)(?:\.[A-Za-z_]\w*)+)" % every)
    free = ("data.columns.", "data.split_overrides.", "sim.generator.effect_params.", "design.studies.",
            "data.bits.", "data.units.", "data.derive.")
    outputs = (".json", ".csv", ".md", ".pkl", ".sig", ".py")
    found = unsure = 0
    for page in _pages(base):
        text, rel = page.read_text(), page.relative_to(base)
        for m in choice.finditer(text):
            line = text[:m.start()].count("\n") + 1
            named = re.split(r"[|,]", m[2])
            unknown = [o for o in named if o not in options[m[1]] and o not in ("null", "nosuch")]
            left = options[m[1]] - set(named) if "|" in m[2] else set()
            for what in [f"{m[1]}={o}: no such option" for o in unknown] + (
                    [f"{m[0]}: leaves out {sorted(left)}"] if left else []):
                print(f"{rel}:{line}: {what}")
                found += 1
        prose = re.sub(r"```.*?```", lambda b: "\n" * b[0].count("\n"), text, flags=re.S)
        for m in re.finditer(r"`([^`\n]+)`", prose):
            for word in re.split(r"[\s,;()\[\]{}'\"]+", m[1]):
                key = dotted.match(word)
                if key and key[1] not in known and not key[1].startswith(free) \
                        and not key[1].endswith(outputs):
                    print(f"{rel}:{prose[:m.start()].count(chr(10)) + 1}: {key[1]}: not a config key (read: "
                          "an output's key, a module, a typo on purpose?)")
                    unsure += 1
        for target in _links(text):
            if target.startswith(("http://", "https://", "mailto:")):
                continue
            path, _, anchor = target.partition("#")
            linked = (page.parent / path).resolve() if path else page
            if not linked.exists():
                print(f"{rel}: link {target}: no such file")
                found += 1
            elif anchor and linked.suffix == ".md" and anchor not in _heading_anchors(linked.read_text()):
                print(f"{rel}: link {target}: no such heading")
                found += 1
    outputs_page = (base / "docs" / "outputs.md").read_text()
    synopsis = re.search(r"a synopsis.*?```bash\n(.*?)```", outputs_page, re.S)[1]
    from thermocomp.shell.stages import STAGES
    for stage in STAGES:
        if not re.search(rf"^thermocomp (\w+ \| )*{stage}\b", synopsis, re.M):
            print(f"docs/outputs.md: the synopsis lacks `thermocomp {stage}`")
            found += 1
    print(f"{found} finding(s); {unsure} dotted name(s) no config key, to read")


def _thermocomp(root: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "thermocomp", *args], capture_output=True, text=True,
                          cwd=root)


def _overrides_of(words: list[str]) -> tuple[str, ...]:
    """The overrides of a command the docs name, placeholders (``<dir>``, ``…``) and a sweep's
    lists left out, an optional one (``[key=value]``) as given."""
    kept = []
    for word in words[1:]:
        word = word[1:-1] if word.startswith("[") and word.endswith("]") else word
        placeholder = any(s in word for s in ("<", "…", "...", "|", "DIR", "ROOT/"))
        swept = "-m" in words and "," in word.partition("=")[2] and "[" not in word
        if "=" in word and not word.startswith("-") and not placeholder and not swept:
            kept.append(word)
    return tuple(kept)


def commands(root: str) -> None:
    """Every ``thermocomp`` command the pages name in a code span, composed with ``--cfg job``."""
    base = Path(root).resolve()
    seen, failed = set(), 0
    for page in _pages(base):
        text = page.read_text()
        for m in re.finditer(r"`((?:\.venv/bin/)?thermocomp [a-z]+[^`\n]*)`", text):
            try:
                words = shlex.split(m[1])[1:]
            except ValueError:
                continue
            stage = words[0]
            kept = _overrides_of(words)
            if (stage, kept) in seen:
                continue
            seen.add((stage, kept))
            ran = _thermocomp(base, stage, *kept, "--cfg", "job")
            if ran.returncode:
                failed += 1
                said = (ran.stderr.strip().splitlines() or [""])[-1]
                print(f"{page.relative_to(base)}:{text[:m.start()].count(chr(10)) + 1}: exit "
                      f"{ran.returncode}: {stage} {' '.join(kept)}: {said[:200]}")
    print(f"{len(seen)} distinct commands composed, {failed} not exit 0")
    record = base / "datasets" / "fl_thermal" / "spindle_test.csv"
    for args in (["run", "model=nosuch", "--cfg", "job"], ["run", "nosuch.key=1", "--cfg", "job"],
                 ["init", "--cfg", "job", "--package", "data", str(record)],
                 ["run", "+diagnose.alpah=0.05"], ["compare", "model=arx"], ["train", "--help"]):
        ran = _thermocomp(base, *args)
        lines = (ran.stderr.strip() or ran.stdout.strip()).splitlines()
        telling = next((ln for ln in lines if 'model=' in ln or 'error' in ln or 'path' in ln), lines[-1])
        print(f"{' '.join(args)}: exit {ran.returncode}, {len(lines)} line(s): {telling[:220]}")


def families(root: str, out: str) -> None:
    """Every family on fl_thermal, both splits: test MAE per channel, mean MAE and RMSE, CPU."""
    base, folder = Path(root).resolve(), made_folder(out)
    for split, extra in SPLITS.items():
        for family in FAMILIES:
            job = folder / f"{split.replace('/', '')}_{family}"
            timed = subprocess.run(["/usr/bin/time", "-f", "%U %S", sys.executable, "-m", "thermocomp", "-q",
                                    "run", "data=fl_thermal", f"model={family}", *extra, "track=false",
                                    "plots=none", f"out={job}"], capture_output=True, text=True, cwd=base)
            cpu = sum(map(float, timed.stderr.strip().splitlines()[-1].split()))
            targets = json.loads((job / "metrics.json").read_text())["targets"]
            mae = [targets[t]["test"]["mae"] for t in sorted(targets)]
            rmse = [targets[t]["test"]["rmse"] for t in sorted(targets)]
            channels = " / ".join(f"{x:.2f}" for x in mae)
            print(f"{split} {family}: MAE {channels}, mean {sum(mae) / len(mae):.2f}; "
                  f"RMSE mean {sum(rmse) / len(rmse):.3f}; CPU {cpu:.1f} s", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"docs": docs, "commands": commands, "families": families}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
