"""The commands of the README and the docs pages, run exactly as written, in a fresh copy of the
project.

Every fenced ``bash`` block of README.md and of each page of the docs site (:func:`pages`, in
the order of ``mkdocs.yml``'s ``nav``) is run, in order, by ``bash -euo pipefail`` from the root
of a scratch clone whose ``.venv`` is NOT activated (``PATH`` has no venv in it), unless an HTML
comment on the line before it says otherwise.  Each page runs in a clone of its own (one test per
page, so that xdist spreads them; the test process's one copy of the venv pointed at it); a docs
page's clone first gets what the README's ``make run`` leaves for the pages, the default dataset
(:data:`PREPARE`).  The directives:

- ``<!-- readme-test: skip — <reason> -->``: not run (a synopsis, the test suite itself, ...);
- ``<!-- readme-test: background <host>:<port> -->``: started in the background (a server);
  the next blocks run once the port accepts connections, and it is stopped at the end;
- ``<!-- readme-test: expect <regex> -->``: the block's output must match ``regex``;
- ``<!-- readme-test: file <path> -->`` before a ``yaml`` block: written to ``<path>``;
- ``<!-- readme-test: output -->`` before an unlabelled block: a table the last command block
  printed, every line of it (whitespace aside), not just one row.

A directive must stand on the line right before its block (one not attached to a block fails),
and shell blocks are ``bash`` (an ``sh``/``shell``/``console`` block would not be run: it fails).

So the README and the docs cannot drift from what the commands do: a renamed override, a moved
output or a command that needs an activated venv fails here.
"""

from __future__ import annotations

import os
import re
import resource
import shutil
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml

from conftest import ROOT

pytestmark = pytest.mark.slow

BLOCK = re.compile(r"(?:<!--[ \t]*readme-test:[ \t]*(?P<directive>[^\n]*?)[ \t]*-->[ \t]*\n)?"
                   r"^```(?P<lang>[\w-]*)[ \t]*\n(?P<body>.*?)^```[ \t]*$", re.S | re.M)
DIRECTIVE = re.compile(r"<!--\s*readme-test:")
KINDS = {"run", "skip", "background", "expect", "file", "output"}
UNRUN_SHELLS = {"sh", "shell", "console", "zsh", "shell-session"}


def readme_blocks(text: str) -> list[dict]:
    """The fenced blocks of ``text`` with their language and directive (kind, argument); an
    unlabelled block without a directive is prose (kind ``text``)."""
    blocks = []
    for m in BLOCK.finditer(text):
        directive = (m["directive"] or "").strip()
        kind, _, arg = directive.partition(" ")
        blocks.append({"lang": m["lang"], "body": m["body"], "arg": arg.strip(),
                       "kind": kind or ("run" if m["lang"] == "bash" else "text"),
                       "line": text[:m.start()].count("\n") + 1,
                       "directive_line": text[:m.start()].count("\n") + 1 if directive else None})
    return blocks


def unaccounted(text: str) -> list[str]:
    """What the README test would silently pass over: directives on no block, shell blocks it
    would not run, unknown directives, skips without a reason, output tables after no command."""
    blocks = readme_blocks(text)
    attached = {b["directive_line"] for b in blocks}
    problems = [f"line {n}: directive not on the line before a block"
                for n, line in enumerate(text.splitlines(), 1)
                if DIRECTIVE.search(line) and n not in attached]
    last_command = None
    for b in blocks:
        where = f"line {b['line']}"
        if b["lang"] in UNRUN_SHELLS:
            problems.append(f"{where}: a ```{b['lang']} block is never run: write ```bash")
        if b["kind"] not in KINDS | {"text"}:
            problems.append(f"{where}: unknown directive {b['kind']!r}")
        if b["kind"] == "skip" and not b["arg"]:
            problems.append(f"{where}: a skipped block needs a reason")
        if b["lang"] == "yaml" and b["kind"] not in ("file", "skip"):
            problems.append(f"{where}: yaml needs file/skip")
        if b["kind"] == "output" and (b["lang"] or last_command is None):
            problems.append(f"{where}: output goes on an unlabelled block after a command block")
        if b["lang"] == "bash" and b["kind"] in ("run", "expect"):   # skipped ones print nothing
            last_command = b["kind"]
    return problems


def missing_lines(table: str, output: str) -> list[str]:
    """The lines of ``table`` that are no line of ``output`` (runs of spaces compared as one)."""
    printed = {" ".join(line.split()) for line in output.splitlines()}
    return [line for line in table.splitlines() if line.strip() and " ".join(line.split()) not in printed]


def pages() -> list[Path]:
    """README.md, then the docs site's pages in the order of ``mkdocs.yml``'s ``nav``."""
    def flat(nav) -> list[str]:
        items = nav if isinstance(nav, list) else [nav]
        out = []
        for item in items:
            value = next(iter(item.values())) if isinstance(item, dict) else item
            out += flat(value) if isinstance(value, list) else [value]
        return out

    nav = yaml.safe_load((ROOT / "mkdocs.yml").read_text())["nav"]
    return [ROOT / "README.md", *(ROOT / "docs" / page for page in flat(nav))]


def all_blocks() -> list[dict]:
    """The blocks of every page of :func:`pages`, in order, each with its ``page``."""
    return [{**b, "page": page.relative_to(ROOT)} for page in pages()
            for b in readme_blocks(page.read_text())]


def _project_files() -> list[Path]:
    """Tracked and untracked, not ignored files: what a clone of the working tree would hold."""
    out = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "-z"], cwd=ROOT,
                         capture_output=True, text=True, check=True).stdout
    return [Path(p) for p in out.split("\0") if p and (ROOT / p).is_file()]


def page_venv(dest: Path) -> Path:
    """A copy of this venv at ``dest`` (hard links of its files) whose scripts run its own python,
    for the pages' copies of the project (:func:`fresh_clone` points it at one's ``src``).

    Copied once per test process, not per page: ``cp -al`` of its ~80,000 files cost 2.3 s of CPU
    a page.  The pages of a process run one after another; no command of theirs installs (the
    stamps below say the install is done, as after ``make install``)."""
    venv = Path(sys.prefix)
    # the folder itself: a worktree's .venv may be a link to another checkout's venv, whose
    # scripts and editable install `cp -al` of the link would have the rewrites below change
    real = venv.resolve()
    subprocess.run(["cp", "-al", str(real), str(dest)], check=True)
    # the scripts name the venv they were installed in: point them at the copy's, so its python
    # runs (and so the src its editable install names); `activate` quotes it whole
    moves = [(f"{v}{end}".encode(), f"{dest}{end}".encode())
             for v in dict.fromkeys((venv, real)) for end in ("/", '"')]
    for script in (dest / "bin").iterdir():
        if script.is_symlink() or not script.is_file():
            continue
        data = script.read_bytes()
        if any(old in data[:4096] for old, _ in moves):
            for old, new in moves:
                data = data.replace(old, new)
            script.unlink()  # hard link: write a new file, never the original's inode
            script.write_bytes(data)
            script.chmod(0o755)
    # the copied files keep their times, so `make` sees the install as current
    for name in (".installed-core", ".installed"):     # in make's order: the core first
        stamp = dest / name
        stamp.unlink(missing_ok=True)
        stamp.touch()
    return dest


def project_copy(dest: Path) -> Path:
    """A copy of the working tree at ``dest``, committed once in a git repository of its own: what
    each page's copy (:func:`fresh_clone`) is a copy of.

    Made once per test process: copying the ~1,600 files and committing them (git hashes and
    compresses ~20 MB) cost 0.6-0.7 s of CPU a page; ``cp -a`` of the made copy costs less."""
    for rel in _project_files():
        (dest / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(ROOT / rel, dest / rel)
    # src's byte code, as `make install` leaves it (compileall): without it a page's first
    # command compiled the package again (0.6 s); times kept, so a stale file is compiled anew
    for pyc in (ROOT / "src").rglob("__pycache__/*.pyc"):
        (dest / pyc.relative_to(ROOT)).parent.mkdir(exist_ok=True)
        shutil.copy2(pyc, dest / pyc.relative_to(ROOT))
    subprocess.run(["git", "init", "-q"], cwd=dest, check=True)
    subprocess.run(["git", "add", "-A"], cwd=dest, check=True)
    subprocess.run(["git", "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "clone"],
                   cwd=dest, check=True)
    return dest


def fresh_clone(dest: Path, venv: Path, project: Path) -> Path:
    """A copy of ``project`` (:func:`project_copy`: the working tree, committed) whose ``.venv`` is
    ``venv`` (:func:`page_venv`), its editable install pointed at the copy's ``src``, so nothing
    of it runs from this checkout or from another page's copy."""
    # every file a copy of its own (times kept), never a link: a page's commands write there
    subprocess.run(["cp", "-a", f"{project}/.", str(dest)], check=True)
    (dest / ".venv").symlink_to(venv)
    for pth in venv.glob("lib/python*/site-packages/__editable__.thermocomp-*.pth"):
        pth.unlink()        # a hard link the first time: a new file, never the original's inode
        pth.write_text(f"{dest / 'src'}\n")
    # the venv serves every page of the process: this page's commands must run this copy
    root = subprocess.run([str(dest / ".venv/bin/python"), "-c", "from thermocomp.base.paths "
                           "import project_root; print(project_root())"], env=_user_env(dest),
                          capture_output=True, text=True, check=True).stdout.strip()
    assert Path(root) == dest.resolve(), f"the copy's venv runs the project at {root}, not {dest}"
    return dest


# Not a new user's either: PYTHONDONTWRITEBYTECODE (set where CI runs) made every command of a
# page compile its whole import stack again, the venv being installed without byte code (uv):
# `thermocomp simulate` 6.1 s CPU against 2.1 s with byte code, `thermocomp run` 23 s against 12.
# Unset, the first command of a page writes it, into the page's copy alone (the venv's folders
# are the copy's own, its files hard links that a write replaces, never changes).
NOT_A_USERS = ("THERMOCOMP_", "MLFLOW_", "VIRTUAL_ENV", "PYTEST", "DVC_", "PYTHONPATH",
               "PYTHONDONTWRITEBYTECODE")


def _user_env(home: Path) -> dict:
    """A shell as a new user has it: no venv on PATH, no project variables (:data:`NOT_A_USERS`)."""
    path = os.pathsep.join(p for p in os.environ["PATH"].split(os.pathsep)
                           if not p.startswith(sys.prefix))
    # PYTHONPATH too: one pointed at a checkout's src would run (and write to) that checkout
    env = {k: v for k, v in os.environ.items() if not k.startswith(NOT_A_USERS)}
    return {**env, "PATH": path, "HOME": str(home), **ONE_CPU}


# A user's machine of one CPU: a joblib sweep's `n_jobs=-1` (hydra/launcher=joblib) is then one job
# at a time in the command's process (as in test_dvc_metrics' sweep). Beside the other xdist worker, two
# loky workers each importing the stack and opening the store gain no time and cost CPU:
# docs/sweeps.md's sweep (4 jobs then; 2 since ci102d) 25-31 s of CPU on two, 17.6 s on one (a
# joblib sweep on two workers is tests/shell/test_sweep.py's).
ONE_CPU = {"LOKY_MAX_CPU_COUNT": "1"}


def test_a_pages_shell_has_no_project_variables_and_writes_byte_code(monkeypatch, tmp_path):
    for name in ("PYTHONDONTWRITEBYTECODE", "PYTHONPATH", "THERMOCOMP_TRACKING_URI", "VIRTUAL_ENV"):
        monkeypatch.setenv(name, "1")
    monkeypatch.setenv("PATH", os.pathsep.join([f"{sys.prefix}/bin", "/usr/bin"]))
    monkeypatch.delenv("PYTHONPYCACHEPREFIX", raising=False)
    env = _user_env(tmp_path)
    assert not {"PYTHONDONTWRITEBYTECODE", "PYTHONPATH", "THERMOCOMP_TRACKING_URI",
                "VIRTUAL_ENV"} & set(env)
    assert env["PATH"] == "/usr/bin" and env["HOME"] == str(tmp_path)
    assert env["LOKY_MAX_CPU_COUNT"] == "1"
    # what the pages' commands then do: a module imported once is not compiled again
    (tmp_path / "probe.py").write_text("x = 1\n")
    subprocess.run([sys.executable, "-c", "import probe"], cwd=tmp_path, env=env, check=True)
    assert list((tmp_path / "__pycache__").glob("probe.*.pyc"))


def _wait_port(host: str, port: int, proc: subprocess.Popen, timeout: float = 180) -> None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise AssertionError(f"background command exited with {proc.returncode}")
        with socket.socket() as s:
            if s.connect_ex((host, port)) == 0:
                return
        time.sleep(0.5)
    raise AssertionError(f"nothing listens on {host}:{port} after {timeout} s")


def test_readme_blocks_are_all_accounted_for():
    for page in pages():
        problems = unaccounted(page.read_text())
        assert not problems, f"{page.relative_to(ROOT)}: {problems}"
    blocks = all_blocks()
    assert sum(b["kind"] != "skip" and b["lang"] == "bash" for b in blocks) >= 8
    # a page with commands outside the nav would never be run
    listed = set(pages())
    unlisted = [p.name for p in (ROOT / "docs").rglob("*.md")
                if p not in listed and readme_blocks(p.read_text())]
    assert not unlisted, f"docs pages with commands but not in mkdocs.yml's nav: {unlisted}"


# What the README's `make run` leaves that the pages' commands read (the default dataset): in
# each page's copy before its commands, so the pages run apart (xdist spreads them).  The
# README's page, first in a test process, leaves it (its `make run` runs this very command:
# `$(BIN)/thermocomp simulate`); else the first page of the process runs it.  The next ones get
# a copy of what it wrote (the simulator is deterministic: the same files, byte for byte, in
# every copy; the README's data/ after its page and a PREPARE's were compared whole, ci108a).
PREPARE = ".venv/bin/thermocomp simulate"
DATA = Path("data")     # where PREPARE writes; what the README's page wrote there is handed on


def runnable_pages() -> list[Path]:
    """The pages of :func:`pages` with a block to run or to write."""
    return [page for page in pages()
            if any(b["kind"] not in ("skip", "text") for b in readme_blocks(page.read_text()))]


def _children_cpu() -> float:
    """CPU seconds (user + system) of the ended child processes: a block's cost on a loaded
    machine, where its wall time says little."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _files(clone: Path) -> dict[Path, tuple[int, int]]:
    """Size and time of every file of ``clone`` but its venv, git and byte code: what a command
    wrote is the difference before/after."""
    found = {}
    for folder, dirs, names in os.walk(clone):
        dirs[:] = [d for d in dirs if d not in (".venv", ".git", "__pycache__")]
        for name in names:
            st = (Path(folder) / name).stat()
            found[(Path(folder) / name).relative_to(clone)] = (st.st_size, st.st_mtime_ns)
    return found


@pytest.fixture(scope="session")
def venv(tmp_path_factory) -> Path:
    """The pages' venv (:func:`page_venv`), one per test process."""
    return page_venv(tmp_path_factory.mktemp("venv") / ".venv")


@pytest.fixture(scope="session")
def project(tmp_path_factory) -> Path:
    """The working tree committed (:func:`project_copy`), one per test process."""
    return project_copy(tmp_path_factory.mktemp("project"))


@pytest.fixture(scope="session")
def prepared(tmp_path_factory) -> Path:
    """The files :data:`PREPARE` wrote in the first page's copy, for the next pages' copies."""
    return tmp_path_factory.mktemp("prepared")


def prepare(clone: Path, env: dict, log: list[str], kept: Path) -> None:
    """:data:`PREPARE` in ``clone``: run there if ``kept`` is empty (then what it wrote is kept),
    else a copy of what it (or the README's `make run`, :func:`keep_written`) wrote (file times
    kept, as a copy of the first clone's)."""
    if any(kept.iterdir()):
        shutil.copytree(kept, clone, dirs_exist_ok=True)
        log.append(f"--- (prepared) {PREPARE}: a copy of what it wrote in an earlier page's copy")
        return
    before = _files(clone)
    run_blocks([{"kind": "run", "lang": "bash", "body": PREPARE + "\n", "arg": "", "line": 0,
                 "page": "(prepared)"}], clone, env, log)
    keep_written(clone, before, kept)


def keep_written(clone: Path, before: dict, kept: Path, under: Path | None = None) -> None:
    """Copy into ``kept`` the files of ``clone`` (``under`` it only, if given) that are new or
    changed since ``before`` (:func:`_files`)."""
    for rel, stamp in _files(clone).items():
        if before.get(rel) != stamp and (under is None or under in rel.parents):
            (kept / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(clone / rel, kept / rel)


def run_blocks(blocks: list[dict], clone: Path, env: dict, log: list[str]) -> None:
    """Run ``blocks`` (one page's, in order) in ``clone`` as their directives say."""
    background, output = [], ""
    try:
        for b in blocks:
            where = f"{b['page']} line {b['line']}"
            if b["kind"] == "output":
                missing = missing_lines(b["body"], output)
                assert not missing, f"{where}: not printed by the command before it: {missing}\n{output}"
                continue
            if b["kind"] in ("skip", "text"):
                continue
            if b["lang"] == "yaml":
                target = clone / b["arg"]
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_text(b["body"])
                continue
            if b["kind"] == "background":
                host, port = b["arg"].rsplit(":", 1)
                proc = subprocess.Popen(["bash", "-c", b["body"]], cwd=clone, env=env,
                                        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                        start_new_session=True)
                background.append(proc)
                _wait_port(host, int(port), proc)
                continue
            start, cpu = time.monotonic(), _children_cpu()
            proc = subprocess.run(["bash", "-euo", "pipefail", "-c", b["body"]], cwd=clone,
                                  env=env, capture_output=True, text=True, timeout=1200)
            output = proc.stdout + proc.stderr
            log.append(f"--- {where} ({time.monotonic() - start:.1f} s wall, "
                       f"{_children_cpu() - cpu:.1f} s CPU)\n{b['body']}{output[-3000:]}")
            assert proc.returncode == 0, f"{where} failed ({proc.returncode}):\n{b['body']}\n{output}"
            if b["kind"] == "expect":
                assert re.search(b["arg"], output), f"{where}: no match for {b['arg']!r}\n{output}"
    finally:
        for proc in background:
            os.killpg(proc.pid, signal.SIGTERM)
            proc.wait(timeout=30)


# CI's `make test` runs the README's page (the stranger's first commands, `make run` among them);
# the docs pages' walks (15-33 s of wall each under 3 workers, ~6 % of the suite's) are `full`:
# in `make test`, test_docs checks statically that every key a page sets is one a config has
# (test_a_key_the_docs_set_is_one_a_config_has), every group option and flag it names exists, and
# the commands they run are the README's and the ones the shell tests run on small data.
def _page_param(page: Path):
    if page == ROOT / "README.md":
        return pytest.param(page, id="README.md")
    return pytest.param(page, id=str(page.relative_to(ROOT)), marks=pytest.mark.full(
        reason="a docs page run as written; in make test: README.md's page and test_docs' static "
               "checks of the keys, groups and flags it names"))


@pytest.mark.parametrize("page", [_page_param(page) for page in runnable_pages()])
def test_page_commands_as_written(page, tmp_path, venv, project, prepared):
    """One page's commands in a fresh copy of their own; a docs page's copy holds the default
    dataset first (:data:`PREPARE`), as the README's `make run` leaves it."""
    start, cpu = time.monotonic(), _children_cpu()
    clone = fresh_clone(tmp_path / "clone", venv, project)
    log = [f"--- (fresh clone) ({time.monotonic() - start:.1f} s wall, {_children_cpu() - cpu:.1f} s CPU "
           "of its commands)"]
    home = tmp_path / "home"
    home.mkdir()
    env = _user_env(home)
    blocks = [{**b, "page": page.relative_to(ROOT)} for b in readme_blocks(page.read_text())]
    try:
        if page != ROOT / "README.md":
            prepare(clone, env, log, prepared)
            run_blocks(blocks, clone, env, log)
        else:
            before = _files(clone)
            run_blocks(blocks, clone, env, log)
            if not any(prepared.iterdir()):   # its `make run` simulated the default dataset
                keep_written(clone, before, prepared, under=DATA)
    finally:
        (tmp_path / "readme_run.log").write_text("\n".join(log))
    assert not (clone / "mlflow.db").exists(), "a command left a stray ./mlflow.db"
