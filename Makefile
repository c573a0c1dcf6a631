# fusion-book: `make book` builds the HTML book, `make test` runs every test.
# Both start from a fresh clone: they create .venv and install everything first.

PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
NOTEBOOKS := $(sort $(wildcard notebooks/*.ipynb))

# The notebook kernel must be the venv's Python, whatever the caller's PATH.
export PATH := $(CURDIR)/$(BIN):$(PATH)
export PYDEVD_DISABLE_FILE_VALIDATION := 1

.PHONY: all book test notebooks clean distclean help

all: book

help:
	@echo "make book       build the HTML book into _build/html (warnings are errors)"
	@echo "make test       unit tests + nbval on every notebook"
	@echo "make notebooks  re-execute the notebooks in place, for committing"
	@echo "make clean      remove _build; make distclean also removes .venv"

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[dev]'
	touch $(STAMP)

# Executes every notebook (into the jupyter-cache under _build) and builds the HTML.
book: $(STAMP)
	$(BIN)/jupyter-book build . --builder html -W --keep-going

# Unit and property tests, then nbval re-executes every notebook and compares outputs.
test: $(STAMP)
	$(BIN)/python -m pytest

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
