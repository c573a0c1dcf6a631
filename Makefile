# fusion-book: `make book` builds the HTML book, `make test` runs every test.
# Both start from a fresh clone: they create .venv and install everything first.

PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
LOCK   := requirements.lock
NOTEBOOKS := $(sort $(wildcard notebooks/*.ipynb))
# `make lock` resolves with this uv release, for every platform and Python >= this one.
UV_VERSION  := 0.13.9
LOCK_PYTHON := 3.11

# The notebook kernel must be the venv's Python, whatever the caller's PATH.
export PATH := $(CURDIR)/$(BIN):$(PATH)
export PYDEVD_DISABLE_FILE_VALIDATION := 1
# One BLAS thread per process: the notebooks and test workers already run one per core, and two BLAS threads per
# process on two cores oversubscribe them (results do not depend on it: tests/test_threads.py).
export OPENBLAS_NUM_THREADS ?= 1
export OMP_NUM_THREADS ?= 1
export MKL_NUM_THREADS ?= 1

.PHONY: all book test notebooks lock stability clean distclean help

all: book

help:
	@echo "make book       build the HTML book into _build/html (warnings are errors, nitpicky)"
	@echo "make test       unit tests, the book built with -W -n, nbval on every notebook"
	@echo "make notebooks  re-execute the notebooks in place, for committing"
	@echo "                (some only: make notebooks NOTEBOOKS=notebooks/05_covariance_intersection.ipynb)"
	@echo "make lock       re-resolve requirements.lock from pyproject.toml (PyPI access)"
	@echo "make stability  re-derive every stochastic status under 5 fresh seeds and at 10x runs, on Dask"
	@echo "                (STABILITY_ARGS=\"--scheduler tcp://host:8786\" for a cluster; --runs-factor, --workers)"
	@echo "make clean      remove _build; make distclean also removes .venv"

# The exact versions of requirements.lock, then the package itself without resolving anything.
$(STAMP): pyproject.toml $(LOCK)
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -r $(LOCK)
	$(BIN)/python -m pip install --quiet --no-deps -e .
	touch $(STAMP)

# Regenerate the lock from pyproject.toml (runtime and dev dependencies), with uv installed
# into a throwaway venv: one set of versions for every platform and Python >= $(LOCK_PYTHON).
# Then `make test` (which reinstalls from the new lock) and `make notebooks` if outputs moved.
lock:
	@tools=$$(mktemp -d) && trap 'rm -rf "$$tools"' EXIT && \
	$(PYTHON) -m venv "$$tools" && \
	"$$tools/bin/python" -m pip install --quiet uv==$(UV_VERSION) && \
	"$$tools/bin/uv" pip compile pyproject.toml --extra dev --universal --fork-strategy fewest \
	  --python-version $(LOCK_PYTHON) --custom-compile-command "make lock" --quiet -o $(LOCK)
	@echo "wrote $(LOCK): run make test"

# Executes every notebook, one per core (tools/execute_notebooks.py, into the jupyter-cache under
# _build that the build reads; jupyter-book alone would run them one after the other), and builds the HTML with
# Sphinx on every core (tools/build_book.py: jupyter-book's command has no -j).
book: $(STAMP)
	$(BIN)/python tools/execute_notebooks.py _build/.jupyter_cache $(NOTEBOOKS)
	$(BIN)/python tools/build_book.py . --builder html -W -n --keep-going

# Unit and property tests, the book built from the committed outputs with -W -n (with or
# without Chromium: tests/test_book_build.py), then nbval re-executes every notebook and
# compares outputs.
test: $(STAMP)
	$(BIN)/python -m pytest

# The reseeding sweep (fusion/book/stability.py): every stochastic record's evidence, every reading, under
# fresh seeds and the primary at 10x the runs, on Dask (a LocalCluster here; --scheduler ADDRESS for a
# cluster). Writes book/ledger/stability.json, which `make test` checks covers the current records.
STABILITY_ARGS ?=
stability: $(STAMP)
	$(BIN)/python -m fusion.book.stability $(STABILITY_ARGS)

# Re-execute the notebooks in place so their stored outputs follow from the code.
# Timing metadata is off (it would invalidate the book's execution cache).
notebooks: $(STAMP)
	$(BIN)/jupyter nbconvert --to notebook --execute --inplace \
	  --ExecutePreprocessor.record_timing=False \
	  --ExecutePreprocessor.timeout=600 \
	  --ClearMetadataPreprocessor.enabled=True \
	  --ClearMetadataPreprocessor.preserve_cell_metadata_mask=tags \
	  --ClearMetadataPreprocessor.preserve_nb_metadata_mask=kernelspec \
	  --ClearMetadataPreprocessor.preserve_nb_metadata_mask=language_info \
	  $(NOTEBOOKS)

clean:
	rm -rf _build

distclean: clean
	rm -rf $(VENV) *.egg-info
