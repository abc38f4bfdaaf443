# cablestudy: two commands on a fresh machine, `make study` and `make test`.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
CONFIG ?= configs/catenary-in-air.yaml
OUT ?= results

.PHONY: install study test figures bench docs reference lint clean

install: $(STAMP)

# Redone only when pyproject.toml changes. The numba kernels are compiled here, in
# parallel, so that neither the first study nor the tests wait for them.
$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[dev,peers]'
	$(BIN)/python -m compileall -q cablestudy  # bytecode read even where PYTHONDONTWRITEBYTECODE is set
	$(BIN)/cablestudy compile
	touch $(STAMP)

study: install
	$(BIN)/cablestudy run "$(CONFIG)" --out "$(OUT)"

# The suite runs on every core (pytest-xdist: `-n auto` is the number of cores;
# `make test TEST_WORKERS=N` chooses, 0 runs it in this one process). Each test file stays
# on one worker (`--dist loadfile`): the fixtures a file shares are built once, a file's
# tests keep their order, and the largest file is far under half of the suite.
TEST_WORKERS ?= auto
test: install
	$(BIN)/python -m pytest -q -n $(TEST_WORKERS) --dist loadfile tests

figures: install
	$(BIN)/cablestudy figures --results $(OUT) --out $(OUT)/figures --docs docs

bench: install
	$(BIN)/cablestudy bench --out $(OUT)/bench --readme docs/benchmarks.md --docs docs/bench

# the user guide as a MkDocs site in site/; strict: a broken link, a page missing from
# the nav or a stale key reference fails the build
docs: install
	$(BIN)/python -m cablestudy.docs_reference --check
	$(BIN)/mkdocs build --strict -d site

# regenerate docs/reference/keys.md from the study schema
reference: install
	$(BIN)/python -m cablestudy.docs_reference

lint: install
	$(BIN)/ruff check cablestudy tests benchmarks
	$(BIN)/ruff format --check cablestudy tests benchmarks

clean:
	rm -rf $(VENV) .pytest_cache build *.egg-info site
