# propwhirl — every target sets itself up on a fresh machine (virtual environment in .venv).
#   make run       main analysis (wingtip-mounted propeller wing), plots in out/
#   make test      the whole test suite (long checks included: pytest marker `long`), then
#                  make test-nastran
#   make test-nastran  the NASTRAN tests (tests/nastran) in .venv-nastran, an environment of its
#                  own: pyNastran 1.4.1 needs numpy < 2 (~1.5 min and ~510 MB to build once), and
#                  there too the checks whose numbers depend on the platform's LAPACK
#                  (NUMPY1_TESTS: numpy 1.26 is supported as well as 2.x)
#   make test-fast the suite without the `long` checks
#   make generate  rebuild generated/ from the SymPy derivations
#   make bench     engine vs the thesis's fixed-grid sweep; rewrites the tables of docs/performance.md
#   make bench-map     the 50 x 50 wingtip map, warm-started reduced vs the default; rewrites its
#                      table of docs/performance.md
#   make bench-design  design-size models (reduced vs dense, size scaling, memory); rewrites its
#                  table of docs/performance.md (a few minutes)
#   make bench-nastran95  propwhirl and NASTRAN-95 side by side on issue 37's cases (CPU, critical
#                  speeds) in .venv-bench312: nastran95 needs Python >= 3.12 (pyenv's); rewrites
#                  its table of docs/performance.md
#   make docs      the documentation site in site/ (mkdocs, strict: a warning fails; the test suite builds it too)
#   make report    the example certification report in examples/certification/wingtip/ (HTML,
#                  its numbers, a screenshot, the PDF's pages as PNG); CAMPAIGN=... REPORT_DIR=...
#   make browser   the distribution's headless Chromium for the report's PDF and browser test
#                  (apt-get as root; said and skipped where it cannot be installed)
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
# One BLAS thread: the eigenproblems are small and parallelism is over cases.
export OPENBLAS_NUM_THREADS ?= 1
export OMP_NUM_THREADS ?= 1

.PHONY: run test test-fast test-nastran generate bench bench-design bench-map bench-nastran95 docs report \
	browser clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

# One stamp per set of extras; re-installed when pyproject.toml changes.
$(VENV)/.stamp-%: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -e ".[$(subst +,$(comma),$*)]"
	touch $@

comma := ,
# Every extra: make test, the benchmarks and make docs share one set-up (make docs after make
# test installs nothing again).
ALL := $(VENV)/.stamp-codegen+data+dlm+docs+tables+test+plots+toml+notebooks+distributed+progress+mdo+report

# The NASTRAN environment: pyNastran 1.4.1 needs numpy < 2, so the `nastran` extra is never one of
# ALL's (pip would drop the main environment to numpy 1.26); propwhirl, pyNastran and the extras
# tests/nastran needs, in one pip request (one resolution: numpy 1.26).  `notebooks` (nbclient,
# nbformat, ipykernel: matplotlib comes with pyNastran) runs examples/nastran_walkthrough.ipynb
# there; measured from scratch with a warm pip cache, two builds each on 2 shared cores at load
# 5-7: 55-72 s and 421 MB without it, 90-92 s and 513 MB with it (numpy 1.26.4 either way,
# pip check clean).
NASTRAN_VENV := .venv-nastran
NASTRAN_STAMP := $(NASTRAN_VENV)/.stamp-nastran+test+toml+tables+dlm+notebooks

$(NASTRAN_VENV)/bin/python:
	$(PYTHON) -m venv $(NASTRAN_VENV)

# The checks whose numbers depend on the platform's LAPACK (the names of repeated modes, a
# beam model's eigenvalues against its modal model's, old result files against today's), run
# on numpy 1.26 too.  The whole suite there (every extra and pyNastran, a 962 MB environment)
# passes — 4,314 passed, 2 skipped — but takes 1,294 s on 2 cores at load 4-9, as long again
# as the main run; this set takes ~35 s, and .venv-nastran has the extras it needs.
NUMPY1_TESTS := tests/analysis/test_mode_names_propellers.py tests/model/test_modal.py \
	tests/io/test_modal_files.py tests/test_result_protocol.py

$(NASTRAN_STAMP): pyproject.toml | $(NASTRAN_VENV)/bin/python
	$(NASTRAN_VENV)/bin/python -m pip install --quiet --disable-pip-version-check -e ".[nastran,test,toml,tables,dlm,notebooks]"
	touch $@

# Chromium and its chromedriver from the distribution (Debian: chromium, chromium-driver) for the
# report's PDF and its browser test.  Installed with apt-get where we are root; elsewhere a clear
# message, and the browser tests skip naming what is missing.
browser:
	@if command -v chromium >/dev/null 2>&1 && command -v chromedriver >/dev/null 2>&1; then :; \
	elif [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	  echo "installing the headless browser: apt-get install chromium chromium-driver"; \
	  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
	    chromium chromium-driver >/dev/null) || echo "could not install chromium with apt-get: \
	the report's browser tests will be skipped"; \
	else echo "no chromium and chromedriver, and no apt-get as root to install them: \
	install your distribution's chromium and chromium-driver (the report's browser tests skip)"; fi

generate: $(VENV)/.stamp-codegen
	$(BIN)/python -m derivations.generate --out generated

test: $(ALL) browser $(NASTRAN_STAMP)
	$(BIN)/python -m pytest -q
	$(NASTRAN_VENV)/bin/python -m pytest -q tests/nastran $(NUMPY1_TESTS)

test-nastran: $(NASTRAN_STAMP)
	$(NASTRAN_VENV)/bin/python -m pytest -q tests/nastran $(NUMPY1_TESTS)

test-fast: $(ALL) browser
	$(BIN)/python -m pytest -q -m "not long"

# BENCH_MD=path writes the tables elsewhere; BENCH_ARGS e.g. "--repeats 1 --no-variants"
BENCH_MD ?= docs/performance.md
bench: $(ALL)
	$(BIN)/python benchmarks/engine_vs_fixed_grid.py --markdown $(BENCH_MD) $(BENCH_ARGS)

# BENCH_MD as above; BENCH_DESIGN_ARGS e.g. "--quick" (no dense 100-element / 12-propeller run)
bench-design: $(ALL)
	$(BIN)/python benchmarks/design_size.py --markdown $(BENCH_MD) $(BENCH_DESIGN_ARGS)

# BENCH_MD as above; BENCH_MAP_ARGS e.g. "--n 10" or "--reference sample" (100 reference points)
bench-map: $(ALL)
	$(BIN)/python benchmarks/map_speed.py --markdown $(BENCH_MD) $(BENCH_MAP_ARGS)

# NASTRAN-95 side by side (benchmarks/nastran95_side_by_side.py): the nastran95 package needs
# Python >= 3.12, the main environment is 3.11, so an environment of its own with a 3.12
# interpreter (PYTHON312=...; default pyenv's newest 3.12, else python3.12 on the PATH), propwhirl
# and the extras the benchmark needs.  Never part of make test.  BENCH_N95_ARGS e.g. "--quick"
# or "--only goland4x7,goland8x14".  There .venv-bench312/bin/python -m pytest
# tests/benchmarks/test_nastran95_decks.py also runs its NASTRAN-95 check (skipped elsewhere).
BENCH312 := .venv-bench312
PYTHON312 ?= $(or $(lastword $(sort $(wildcard $(HOME)/.pyenv/versions/3.12*/bin/python))),$(shell command -v python3.12))
$(BENCH312)/.stamp-bench: pyproject.toml
	@test -n "$(PYTHON312)" || { echo "make bench-nastran95 needs a Python >= 3.12 interpreter \
	(pyenv install 3.12, or PYTHON312=/path/to/python3.12): nastran95 requires it"; exit 1; }
	test -x $(BENCH312)/bin/python || $(PYTHON312) -m venv $(BENCH312)
	$(BENCH312)/bin/python -m pip install --quiet --disable-pip-version-check -e ".[dlm,tables,toml,test,nastran95]"
	touch $@

bench-nastran95: $(BENCH312)/.stamp-bench
	OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 $(BENCH312)/bin/python \
	  benchmarks/nastran95_side_by_side.py --markdown $(BENCH_MD) $(BENCH_N95_ARGS)

# Material for MkDocs prints an end-of-life banner on every build; NO_MKDOCS_2_WARNING silences it.
docs: $(ALL)
	NO_MKDOCS_2_WARNING=1 $(BIN)/mkdocs build --strict -d site

# The example report (make report CAMPAIGN=examples/other.toml REPORT_DIR=examples/certification/other)
CAMPAIGN ?= examples/wingtip_campaign.toml
REPORT_DIR ?= examples/certification/wingtip
report: $(ALL) browser
	$(BIN)/python examples/certification/make_report.py $(CAMPAIGN) $(REPORT_DIR)

run: $(VENV)/.stamp-data+dlm+plots+tables+toml
	$(BIN)/propwhirl run --out out

clean:
	rm -rf $(VENV) $(NASTRAN_VENV) $(BENCH312) out build site src/*.egg-info .pytest_cache .hypothesis
