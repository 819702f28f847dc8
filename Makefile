# Two commands do all set-up: `make run` and `make test` (each creates .venv when missing).
PY      ?= python3
VENV    := .venv
BIN     := $(VENV)/bin
STAMP   := $(VENV)/.installed
CORE    := $(VENV)/.installed-core

.PHONY: run test test-all install docs benchmark clean team-test

# Each install step says what it does and how long it took; pip shows its own progress bars.
STEP = @step() { echo "[install] $$1 ..."; s=$$(date +%s); shift; "$$@" || exit $$?; \
	echo "[install] done in $$(( $$(date +%s) - s )) s"; }; step

# uv installs, pip only bootstraps it: a clean clone's `make install` took 157 s CPU (313 s wall)
# with pip, 58 s CPU (176 s wall under four times the load) with uv, the same versions (downloads
# in parallel; torch's wheel alone 7.5 s). uv does not read pip's configuration: the wheel folders
# pip is given (`find-links`: this machine's CPU torch) are passed on, so both take the same torch.
# --compile-bytecode: uv writes no .pyc (pip did), and where PYTHONDONTWRITEBYTECODE is set (as on
# these machines) none is ever written: every process compiled sklearn, MLflow, SciPy ... again
# (`thermocomp run`: 14.0 -> 8.7 s CPU with them compiled; the suite starts hundreds of processes).
UV      := $(BIN)/uv pip install --compile-bytecode --python $(BIN)/python
LINKS    = $$(for l in $$($(BIN)/python -m pip config get global.find-links 2>/dev/null); do \
	printf -- '--find-links %s ' "$$l"; done)

# The core (pip install -e .) is what `make run` needs; `make install` / `make test` add every
# extra (.[test]: lstm, pipeline, scale, team, docs + pytest, ruff); see docs/install.md.
$(CORE): pyproject.toml requirements.lock
	$(STEP) "virtual environment $(VENV)" sh -c 'test -x $(BIN)/python || $(PY) -m venv $(VENV)'
	$(STEP) "pip and uv" $(BIN)/python -m pip install --progress-bar on --upgrade "pip>=24" "uv==0.13.9"
	$(STEP) "thermocomp, the core" $(UV) $(LINKS) -c requirements.lock -e .
	$(STEP) "thermocomp's byte code" $(BIN)/python -m compileall -q src   # editable: not uv's
	touch $(CORE)

$(STAMP): $(CORE)
	# torch first and alone: the CPU wheel of exactly this version is on disk.
	$(STEP) "torch (CPU)" $(UV) $(LINKS) torch==2.13.0
	$(STEP) "the extras and the test tools" $(UV) $(LINKS) -c requirements.lock -e ".[test]"
	touch $(STAMP)

install: $(STAMP)

run: $(CORE)
	$(BIN)/thermocomp simulate
	$(BIN)/thermocomp run

# 3 workers (pytest-xdist) on CI's 2 cores, a module's tests on one: its fixtures built once
# (tests/conftest.py: the long ones first).  A third worker takes the CPU the other two leave while
# they wait (servers starting, OPC UA and twin clocks, signals, sockets: ~6 % of the cores in the
# last idle 2-worker run measured, 14:18 wall and 1557 s CPU with the install; 3 workers on an idle
# fresh clone: 13:32 wall, pytest 12:27, 1477 s CPU).  One BLAS/OpenMP
# thread per process: workers each running a BLAS pool of one thread per core oversubscribe the cores and
# spin (test_calibrate + test_volumetric_run on 2 workers: 153 -> 119 s user CPU, 223 -> 101 s
# wall on a machine with other load).
TEST_WORKERS := 3
TEST_THREADS := OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1

# `make test` (CI's) leaves out the tests marked `full`: what tests in it already cover (each
# names them; the cases outside a cross product's covering set: tests/covering.py); `make test-all`
# runs every test.
test: $(STAMP)
	$(TEST_THREADS) $(BIN)/python -m pytest -q -n $(TEST_WORKERS) --dist loadfile -m "not full"

test-all: $(STAMP)
	$(TEST_THREADS) $(BIN)/python -m pytest -q -n $(TEST_WORKERS) --dist loadfile

docs: $(STAMP)
	$(BIN)/mkdocs build --strict   # the docs site -> site/ (`$(BIN)/mkdocs serve` to browse)

benchmark: $(STAMP)
# A bench that needs its arguments (a folder, a command) prints its docstring and exits 2:
# listed and skipped; any other failure stops the target.
	for b in benchmarks/bench_*.py; do echo "== $$b"; $(BIN)/python $$b; rc=$$?; \
	  if [ $$rc -eq 2 ]; then echo "   (needs arguments: its docstring above)"; elif [ $$rc -ne 0 ]; then exit $$rc; fi; done

# Team scale: PostgreSQL + MLflow server on loopback, the server-backed tests, both stopped again.
team-test: $(STAMP)
	trap '.ci/team-server stop' EXIT; team_env=$$(.ci/team-server start) && eval "$$team_env" && THERMOCOMP_REQUIRE_SERVER=1 $(BIN)/python -m pytest -q tests/shell/test_team.py

clean:
	rm -rf $(VENV) outputs reports models data/interim data/raw site
