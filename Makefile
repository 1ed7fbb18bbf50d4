# frictal — the two commands of the README.
#   make test       installs missing Debian packages, builds (release) and runs every test
#   make reproduce  installs, builds and runs the paper reproduction, writing under out/
#                   (QUICK=1 make reproduce: the CI-sized grids, about a minute)
#   make package    builds the Debian package (CLI, library, headers, CMake package, Python module)
#   make fuzz       libFuzzer harnesses (9), 10^6 executions each (RUNS=N); make fuzz-smoke: 10^4 (CI)
#   make docs       the documentation site into build/docs/html (Sphinx, notebooks executed; offline)
#   make bench      benchmarks and the whole-command table, A/B against the previous commit (QUICK=1)
JOBS ?= $(shell nproc)
# ccache (when installed) shares objects between build trees of this checkout (e.g. the pip build)
export CCACHE_BASEDIR := $(CURDIR)
BUILD ?= build/release
FRICTAL_BIN = $(shell scripts/frictal-path $(BUILD))

.PHONY: all deps configure build test docs reproduce package bench sanitize tsan-dem fuzz fuzz-smoke format stubs clean

all: build

deps:
	@bash scripts/install-deps

configure: deps
	cmake --preset release

build: configure
	cmake --build $(BUILD) -j $(JOBS)

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

package: build
	cd $(BUILD) && cpack -G DEB -B packages
	@ls -l $(BUILD)/packages/*.deb

docs: build
	/usr/bin/python3 scripts/docs/build.py --build $(BUILD) --out build/docs

reproduce: build
	bash scripts/reproduce $(FRICTAL_BIN) out

# make bench: the Google Benchmark programs, then every user-facing command (bench/commands.py) on
# this commit (B) against the previous one (A; BASELINE=REV for another, BASELINE=none for no A/B),
# each against the recorded table bench/results/commands.tsv (RECORD=1 replaces it with this run).
# QUICK=1: profiles up to 10^6 points and maps up to 512^2 (minutes; the full table takes about an
# hour on 2 cores, most of it the 2048^2 map prediction and report).
BASELINE ?= HEAD~1
bench: deps
	cmake --preset bench && cmake --build build/bench -j $(JOBS)
	bash bench/run-benchmarks build/bench
	/usr/bin/python3 bench/commands.py --build build/bench \
	  $(if $(filter none,$(BASELINE)),,--baseline $$(bash bench/build-baseline.sh $(BASELINE))) \
	  $(if $(QUICK),--max-points 1e6 --max-map 512) $(if $(filter 1,$(RECORD)),--record)

fuzz: deps
	FUZZ_RECORD=$(FUZZ_RECORD) bash scripts/fuzz $(or $(RUNS),1000000)

fuzz-smoke: deps
	bash scripts/fuzz 10000

format:
	bash scripts/check-format --fix

stubs: build
	PYTHONPATH=$(BUILD)/python /usr/bin/python3 scripts/gen_stubs.py > python/frictal/_core.pyi

sanitize: deps
	cmake --preset sanitize && cmake --build build/sanitize -j $(JOBS)
	ctest --test-dir build/sanitize --output-on-failure -j $(JOBS)

# ThreadSanitizer check of the DEM's worker team (engine sources only, ~30 s).
tsan-dem:
	scripts/tsan-dem

clean:
	rm -rf build out
