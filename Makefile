# Two commands do all the set-up on a fresh machine:
#   make validate   creates .venv, installs mjpoincare, runs the default validation and prints the table
#   make test       creates .venv, installs mjpoincare with its dev tools, runs ruff and pytest
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: validate test bench clean

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

clean:
	rm -rf $(VENV) build *.egg-info
