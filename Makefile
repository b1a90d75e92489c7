# Two commands do all the set-up on a fresh machine:
#   make validate   creates .venv, installs mjpoincare, runs the default validation and prints the table
#   make test       creates .venv, installs mjpoincare with its dev tools, runs ruff and pytest
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: validate test bench gate clean

$(STAMP): pyproject.toml
	@$(PYTHON) -c 'import sys; sys.exit(0 if sys.version_info >= (3, 10) else "mjpoincare needs Python >= 3.10")'
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[dev]"
	touch $(STAMP)

validate: $(STAMP)
	$(BIN)/mjpoincare validate

test: $(STAMP)
	$(BIN)/ruff check src analysis tests
	$(BIN)/python -m pytest -q

bench: $(STAMP)
	$(BIN)/mjpoincare bench rimless-wheel

# Gate a MuJoCo upgrade (or check an older one): a separate venv with that MuJoCo, the regression tests
# (every scenario against its analytic values) and the default validation, saved as renders/gate-mujoco-V.json.
gate:
	@test -n "$(MUJOCO)" || { echo "usage: make gate MUJOCO=<version>   e.g. make gate MUJOCO=3.3.7"; exit 2; }
	$(PYTHON) -m venv .venv-mujoco-$(MUJOCO)
	.venv-mujoco-$(MUJOCO)/bin/python -m pip install --quiet --upgrade pip
	.venv-mujoco-$(MUJOCO)/bin/python -m pip install --quiet -e ".[dev]" "mujoco==$(MUJOCO)"
	.venv-mujoco-$(MUJOCO)/bin/python -m pytest -q -m mujoco
	.venv-mujoco-$(MUJOCO)/bin/mjpoincare validate --json renders/gate-mujoco-$(MUJOCO).json

clean:
	rm -rf $(VENV) .venv-mujoco-* build *.egg-info
