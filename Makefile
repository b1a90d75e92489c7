# Two commands do all the set-up on a fresh machine:
#   make validate   creates .venv-core, installs mjpoincare alone (its core dependencies) from the lock, runs the default
#                   validation and prints the table
#   make test       creates .venv, installs mjpoincare with every extra and its dev tools from the lock, runs ruff and
#                   pytest in TEST_WORKERS (2) pytest-xdist workers (the other targets below use that .venv too)
# The lock (requirements/lock.txt) pins every dependency for every Python >= 3.10 and platform (uv's universal
# resolution); uv (its locked version, bootstrapped by pip) installs through it as constraints, so CI and a new user
# get the versions the suite was tested on.
#   make lock         regenerate requirements/lock.txt from pyproject.toml
#   make test-latest  the tests against the newest versions pyproject.toml allows (finds dependency drift)
#   make margins      the regression gate's margin table: every check's form (gated, watched, declared miss), error,
#                     spread over the environments this machine emulates (every OpenBLAS kernel the CPU runs crossed
#                     with numpy's dispatch levels, one BLAS thread, each in its own process), under seed, threads,
#                     starts x(1+1e-12) and x(1+1e-9) and
#                     the oldest numpy/scipy allowed, and resolution, into docs/results/gate/ (JSON and page); then
#                     docs/results/discrimination.md (each check's distance to its rival physics against what it lets
#                     through)
#   make baseline     the gate's regression baseline (docs/results/gate/baseline.json): every gate check's error and
#                     resolution (its spread over the environments make margins measured and the rounding
#                     perturbations); refuses when an error left that measurement's range (run make margins first)
#   make power        the gate's power (docs/results/gate-power.md): physics changes of known size planted into each
#                     scenario's default gate case, and which checks catch them by tolerance and by the baseline
#   make results         every scenario's default validation at each preset into docs/results/json/, then its pages
#   make papers       every result of the papers (000-003) run in MuJoCo: mjpoincare reproduce at the fast preset (with
#                     the figures' plots) and the accurate one, PAPER_WORKERS jobs at once, into docs/results/papers/json/,
#                     then docs/results/papers/*.md; papers-render: the pages only (no simulation)
#   make results-render  re-render docs/results/*.md from the committed JSON (no simulation), and the friction
#                     biped's ladder (docs/results/ladders/compass-biped-friction/README.md) from its validations
#   make backends     the backends' findings: every scenario on MuJoCo C, MJX (x64, float32) and MuJoCo Warp, one process
#                     per run (resumable), into docs/results/backends/; PRESETS, BATCH (the batch setting), MAPS (the
#                     friction wheel's basin map, MAPS x MAPS starts, and mu sweep, MAPS values; 0 = none), SCALING
#                     (batch sizes to time a batched step at), WORKERS
#   make releases     the MuJoCo release history: asks the package index which releases exist (the oldest admitted,
#                     the newest patch of each minor line, every patch of the newest), then one nox session (noxfile.py,
#                     uv) per release the page lacks, RELEASE_WORKERS at a time, resumable, into
#                     docs/results/releases/json/, then docs/results/mujoco-releases.md
#   make releases-render  re-render docs/results/mujoco-releases.md from the committed JSON (no simulation)
#   make bisect LOW=3.17.0 HIGH=4.0.0 CHECK=rimless-wheel/eigenvalue [PRESET=fast]   the first patch release between
#                     two releases where a check really changes (beyond its spread)
#   make tune         the preset search: continue each stored study (renders/tune/SCENARIO.db, Optuna) of TUNE_SCENARIOS
#                     to TUNE_TRIALS trials per target preset, export it to docs/results/tune/json/ with its front's
#                     plot, then render docs/results/tune/SCENARIO.md
#   make tune-render  re-render docs/results/tune/*.md from the committed JSON (no simulation)
#   make engines      the wheels on MuJoCo C beside Drake's MultibodyPlant under each contact approximation (resumable)
#                     into docs/results/engines/json/, then docs/results/engines/README.md; engines-render: the page only
#   make gpu-check    the same at a GPU's sizes (both presets, batches of 4096, 64 x 64 basin map, 64 mu values, batch
#                     sizes 1 to 16384) into docs/results/backends-gpu/; on a CPU: make gpu-check BATCH=8 MAPS=2 ...
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
CORE := .venv-core
CORE_STAMP := $(CORE)/.installed
LOCK := requirements/lock.txt
#: The locked uv, which installs the lock into .venv and .venv-core (pip bootstraps it): the same pins as pip would
#: install, resolved and installed in a fraction of pip's time. --compile-bytecode writes the .pyc files at install
#: time, as pip does: without them every Python process compiles scipy & co. again where the environment sets
#: PYTHONDONTWRITEBYTECODE (containers often do), about a second per process.
UV_VERSION := $(shell sed -n 's/^uv==//p' $(LOCK))
LATEST := .venv-latest

OLDEST := .venv-oldest

PRESETS ?= fast
BATCH ?= 0
MAPS ?= 0
SCALING ?=
WORKERS ?= 1
RELEASE_WORKERS ?= 2
#: pytest-xdist workers of make test; --dist loadgroup keeps each gate case's tests (and its cached run) on one.
TEST_WORKERS ?= 2
PAPER_WORKERS ?= 2
PRESET ?= fast
TUNE_SCENARIOS ?= rimless-wheel rimless-wheel-friction slotted-skate rimless-wheel-3d compass-biped compass-biped-friction
TUNE_TRIALS ?= 16
BACKENDS_OUT ?= docs/results/backends

.PHONY: validate test test-latest lock margins baseline power results results-render papers papers-render backends gpu-check bench gate \
	clean releases releases-render bisect tune tune-render engines engines-render

PYTHON_CHECK := $(PYTHON) -c 'import sys; sys.exit(0 if sys.version_info >= (3, 10) else "mjpoincare needs Python >= 3.10")'

$(STAMP): pyproject.toml $(LOCK)
	@$(PYTHON_CHECK)
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet "uv==$(UV_VERSION)"
	$(BIN)/uv pip install --quiet --compile-bytecode --python $(BIN)/python --constraint $(LOCK) -e ".[dev,peers,mjx,warp]"
	touch $(STAMP)

$(CORE_STAMP): pyproject.toml $(LOCK)
	@$(PYTHON_CHECK)
	$(PYTHON) -m venv $(CORE)
	$(CORE)/bin/python -m pip install --quiet "uv==$(UV_VERSION)"
	$(CORE)/bin/uv pip install --quiet --compile-bytecode --python $(CORE)/bin/python --constraint $(LOCK) -e .
	touch $(CORE_STAMP)

validate: $(CORE_STAMP)
	$(CORE)/bin/mjpoincare validate

test: $(STAMP)
	$(BIN)/ruff check src analysis models tests docs/scripts noxfile.py
	$(BIN)/python -m pytest -q -n $(TEST_WORKERS) --dist loadgroup
	$(BIN)/nox -s oldest

test-latest:
	$(PYTHON) -m venv $(LATEST)
	$(LATEST)/bin/python -m pip install --quiet --upgrade pip
	$(LATEST)/bin/python -m pip install --quiet --upgrade --upgrade-strategy eager -e ".[dev]"
	$(LATEST)/bin/python -m pip list --format freeze | grep -iE '^(mujoco|numpy|scipy|dm-control)=='
	$(LATEST)/bin/python -m pytest -q

margins: $(STAMP)
	$(PYTHON) -m venv $(OLDEST)
	$(OLDEST)/bin/python -m pip install --quiet --upgrade pip
	$(OLDEST)/bin/python -m pip install --quiet "numpy==1.26.4" "scipy==1.11.4" -e .
	-$(OLDEST)/bin/mjpoincare margins --base-only --json renders/margins-oldest.json
	$(BIN)/mjpoincare margins --compare renders/margins-oldest.json --json docs/results/gate/margins.json; \
		status=$$?; $(BIN)/python -m mjpoincare.pages.gate_page && $(BIN)/python -m mjpoincare.pages.discrimination_page && exit $$status

baseline: $(STAMP)
	$(BIN)/python -m mjpoincare.pages.gate_baseline

power: $(STAMP)
	$(BIN)/mjpoincare power --json docs/results/gate/power.json --workers $(WORKERS); \
		status=$$?; $(BIN)/python -m mjpoincare.pages.gate_power_page && exit $$status

results: $(STAMP)
	$(BIN)/python -m mjpoincare.pages.results_pages

papers: $(STAMP)
	-$(BIN)/mjpoincare reproduce --preset fast --workers $(PAPER_WORKERS) --json docs/results/papers/json/fast.json \
		-o docs/results/papers/figures
	-$(BIN)/mjpoincare reproduce --preset accurate --workers $(PAPER_WORKERS) \
		--json docs/results/papers/json/accurate.json
	$(BIN)/python -m mjpoincare.pages.papers_page

papers-render: $(STAMP)
	$(BIN)/python -m mjpoincare.pages.papers_page

results-render: $(STAMP)
	$(BIN)/python -m mjpoincare.pages.results_pages --render-only
	$(BIN)/python -m mjpoincare.pages.ladder_page

tune: $(STAMP)
	set -e; for s in $(TUNE_SCENARIOS); do for t in accurate fast; do \
	  $(BIN)/mjpoincare tune $$s --target $$t --trials $(TUNE_TRIALS) --resume \
	    --json docs/results/tune/json/$$s-$$t.json --plot docs/results/tune/$$s-$$t.png; done; done
	$(BIN)/python -m mjpoincare.commands.tune_pages

tune-render: $(STAMP)
	$(BIN)/python -m mjpoincare.commands.tune_pages

backends: $(STAMP)
	$(BIN)/python -m mjpoincare.pages.backend_findings all --presets $(PRESETS) --batch $(BATCH) --maps $(MAPS) \
		--scaling $(SCALING) --workers $(WORKERS) --out $(BACKENDS_OUT)

engines: $(STAMP)
	$(BIN)/python -m mjpoincare.pages.engine_findings all --workers $(WORKERS) --out docs/results/engines

engines-render: $(STAMP)
	$(BIN)/python -m mjpoincare.pages.engine_findings render docs/results/engines

releases: $(STAMP)
	$(BIN)/python -m mjpoincare.gate.releases matrix --workers $(RELEASE_WORKERS)
	$(BIN)/python -m mjpoincare.gate.releases render

releases-render: $(STAMP)
	$(BIN)/python -m mjpoincare.gate.releases render

bisect: $(STAMP)
	@test -n "$(LOW)" -a -n "$(HIGH)" -a -n "$(CHECK)" || { echo "usage: make bisect LOW=3.17.0 HIGH=4.0.0 CHECK=rimless-wheel/eigenvalue [PRESET=fast]"; exit 2; }
	$(BIN)/python -m mjpoincare.gate.releases bisect $(LOW) $(HIGH) --check $(CHECK) --preset $(PRESET)

gpu-check: PRESETS = fast accurate
gpu-check: BATCH = 4096
gpu-check: MAPS = 64
gpu-check: SCALING = 1 16 256 4096 16384
gpu-check: BACKENDS_OUT = docs/results/backends-gpu
gpu-check: backends

lock: $(STAMP)
	$(BIN)/python -m pip install --quiet uv
	$(BIN)/uv pip compile pyproject.toml --extra dev --extra peers --extra mjx --extra warp --universal --python-version 3.10 --quiet -o $(LOCK)

bench: $(STAMP)
	$(BIN)/mjpoincare bench rimless-wheel

# Gate a MuJoCo upgrade (or check an older one): a separate venv with that MuJoCo, the regression tests
# (every scenario against its analytic values, and the seam's self-tests), the rollout seam's tests and the default
# validation, saved as renders/gate-mujoco-V.json.
gate:
	@test -n "$(MUJOCO)" || { echo "usage: make gate MUJOCO=<version>   e.g. make gate MUJOCO=3.3.7"; exit 2; }
	$(PYTHON) -m venv .venv-mujoco-$(MUJOCO)
	.venv-mujoco-$(MUJOCO)/bin/python -m pip install --quiet --upgrade pip
	.venv-mujoco-$(MUJOCO)/bin/python -m pip install --quiet -e ".[dev]" "mujoco==$(MUJOCO)"
	.venv-mujoco-$(MUJOCO)/bin/python -m pytest -q -m mujoco
	.venv-mujoco-$(MUJOCO)/bin/python -m pytest -q tests/test_rollout_seam.py
	.venv-mujoco-$(MUJOCO)/bin/mjpoincare validate --json renders/gate-mujoco-$(MUJOCO).json

clean:
	rm -rf $(VENV) $(CORE) $(LATEST) $(OLDEST) .venv-mujoco-* .nox build *.egg-info
