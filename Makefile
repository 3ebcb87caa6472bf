# propwhirl — every target sets itself up on a fresh machine (virtual environment in .venv).
#   make run       main analysis (wingtip-mounted propeller wing), plots in out/
#   make test      the whole test suite (long checks included: pytest marker `long`)
#   make test-fast the suite without the `long` checks
#   make generate  rebuild generated/ from the SymPy derivations
#   make bench     engine vs the thesis's fixed-grid sweep; rewrites the tables of docs/performance.md
#   make bench-map     the 50 x 50 wingtip map, warm-started reduced vs the default; rewrites its
#                      table of docs/performance.md
#   make bench-design  design-size models (reduced vs dense, size scaling, memory); rewrites its
#                  table of docs/performance.md (a few minutes)
#   make docs      the documentation site in site/ (mkdocs, strict: a warning fails; the test suite builds it too)
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
# One BLAS thread: the eigenproblems are small and parallelism is over cases.
export OPENBLAS_NUM_THREADS ?= 1
export OMP_NUM_THREADS ?= 1

.PHONY: run test test-fast generate bench bench-design bench-map docs clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

# One stamp per set of extras; re-installed when pyproject.toml changes.
$(VENV)/.stamp-%: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -e ".[$(subst +,$(comma),$*)]"
	touch $@

comma := ,
# Every extra: make test, the benchmarks and make docs share one set-up (make docs after make
# test installs nothing again).
ALL := $(VENV)/.stamp-codegen+data+dlm+docs+tables+test+plots+toml+notebooks+distributed+progress+mdo

generate: $(VENV)/.stamp-codegen
	$(BIN)/python -m derivations.generate --out generated

test: $(ALL)
	$(BIN)/python -m pytest -q

test-fast: $(ALL)
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

# Material for MkDocs prints an end-of-life banner on every build; NO_MKDOCS_2_WARNING silences it.
docs: $(ALL)
	NO_MKDOCS_2_WARNING=1 $(BIN)/mkdocs build --strict -d site

run: $(VENV)/.stamp-data+dlm+plots+tables+toml
	$(BIN)/propwhirl run --out out

clean:
	rm -rf $(VENV) out build site src/*.egg-info .pytest_cache .hypothesis
