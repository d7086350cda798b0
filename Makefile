# dfrecon: the two commands a new user needs are `make demo` and `make test`.
# Everything else is here for developers. See README.md.

BUILD_DIR      ?= build
SANITIZE_DIR   ?= build-sanitize
FUZZ_DIR       ?= build-fuzz
JOBS           ?= $(shell nproc 2>/dev/null || echo 2)
# make fuzz runs the five fuzz targets one after the other, FUZZ_SECONDS in
# all, a fifth each (the last one the remainder); a target given 0 seconds is
# skipped.
FUZZ_SECONDS   ?= 600
FUZZ_SLICES_SECONDS   ?= $(shell echo $$(( $(FUZZ_SECONDS) / 5 )))
FUZZ_RTSTRUCT_SECONDS ?= $(shell echo $$(( $(FUZZ_SECONDS) / 5 )))
FUZZ_MESH_SECONDS     ?= $(shell echo $$(( $(FUZZ_SECONDS) / 5 )))
FUZZ_LABEL_SECONDS    ?= $(shell echo $$(( $(FUZZ_SECONDS) / 5 )))
FUZZ_BATCH_SECONDS    ?= $(shell echo $$(( $(FUZZ_SECONDS) - 4 * ($(FUZZ_SECONDS) / 5) )))
CMAKE_FLAGS    ?=
# CI sets CI=true: warnings become errors there.
ifeq ($(CI),true)
  CMAKE_FLAGS += -DDFRECON_WERROR=ON
endif

# PoCL caches compiled kernels; keep the cache in the build tree so it works
# without a usable HOME (as on CI).
export POCL_CACHE_DIR ?= $(CURDIR)/$(BUILD_DIR)/pocl-cache

.PHONY: setup setup-program build build-program test demo bench sanitize-test fuzz format \
	format-check clean

# Every package: the program's, then the tests', benchmarks' and tools'.
setup:
	@bash scripts/setup.sh

# Only what building and running the program needs.
setup-program:
	@bash scripts/setup.sh build

# The release build is clang with Ninja (CMakePresets.json: clang compiles
# the CGAL-heavy files 1.2-1.5x faster than gcc, and Ninja keeps both cores
# busy). A build/ configured by an older gcc or make setup forgets its
# CMake cache (cmake refuses to change either); its fixtures, vendored
# viewer and kernel cache stay.
RELEASE_CACHE_CHECK = if [ -f $(BUILD_DIR)/CMakeCache.txt ] && \
	  ! { grep -q '^CMAKE_GENERATOR:INTERNAL=Ninja$$' $(BUILD_DIR)/CMakeCache.txt && \
	      grep -q '^CMAKE_CXX_COMPILER:[A-Z]*=.*clang++$$' $(BUILD_DIR)/CMakeCache.txt; }; then \
	  rm -rf $(BUILD_DIR)/CMakeCache.txt $(BUILD_DIR)/CMakeFiles; fi

# Everything: the program, its libraries, the tests and the benchmarks.
build: setup
	@$(RELEASE_CACHE_CHECK)
	@cmake --preset release -DDFRECON_TESTS=ON -DDFRECON_BENCH=ON $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD_DIR) -j $(JOBS)

# The program alone (and the libraries it links), in the same build folder:
# no test, benchmark or fixture.
build-program: setup-program
	@$(RELEASE_CACHE_CHECK)
	@cmake --preset release -DDFRECON_TESTS=OFF -DDFRECON_BENCH=OFF $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target dfrecon

# ctest runs one test more than there are cores: a test that waits on a
# browser's timer or on Slurm's daemons leaves its core idle otherwise.
# (Not under the sanitizers, where no test waits: there a third test only
# slowed the other two.)
TEST_JOBS      ?= $(shell echo $$(( $(JOBS) + 1 )))

# The tests need the program and the test programs, not the benchmarks
# (dfrecon-bench: a minute of CI's 20; `make bench` and `make build` build it).
test: setup
	@$(RELEASE_CACHE_CHECK)
	@cmake --preset release -DDFRECON_TESTS=ON -DDFRECON_BENCH=OFF $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD_DIR) -j $(JOBS)
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(TEST_JOBS)

demo: build-program
	@bash scripts/demo.sh $(BUILD_DIR)/bin/dfrecon

# The benchmarks' own data (a head CT's structures) only here: the tests
# need none of it.
bench: build
	@bash scripts/setup.sh bench
	@$(BUILD_DIR)/bin/dfrecon-bench all

# The tests again under AddressSanitizer + UndefinedBehaviorSanitizer, with
# LeakSanitizer. use_tls=0: scanning thread-local storage makes LSan's tracer
# crash on a bogus dynamic-TLS range in this process mix (tests/lsan.supp
# says more); suppressions (tests/lsan.supp, tests/ubsan.supp) name
# third-party code only.
#
# clang (its sanitizers find more, and it compiles this code in half gcc's
# time with them) and Ninja (which starts a target's files before the
# libraries it links are done: 98 % of both cores busy, 70 % with make). A
# build-sanitize/ left by an older gcc or make configuration is made anew.
sanitize-test: setup
	@if [ -f $(SANITIZE_DIR)/CMakeCache.txt ] && \
	  ! grep -q '^CMAKE_GENERATOR:INTERNAL=Ninja$$' $(SANITIZE_DIR)/CMakeCache.txt; then \
	  rm -rf $(SANITIZE_DIR); fi
	@cmake --preset sanitize $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(SANITIZE_DIR) -j $(JOBS)
	@cd $(SANITIZE_DIR) && POCL_CACHE_DIR=$(CURDIR)/$(BUILD_DIR)/pocl-cache \
	  ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:use_tls=0:print_suppressions=0 \
	  UBSAN_OPTIONS=print_stacktrace=1:suppressions=$(CURDIR)/tests/ubsan.supp ctest --output-on-failure -j $(JOBS)

# libFuzzer on the .slices parser, the RTSTRUCT reader, the mesh readers,
# the label-volume readers and the batch manifest, batch record and label
# table parsers, for FUZZ_SECONDS in all (docs/fuzzing.md). One process
# each: one core. libFuzzer reads -max_total_time=0 as "no limit", so a
# target given 0 seconds is not started at all.
FUZZ_FLAGS = -rss_limit_mb=2048 -timeout=10
fuzz: setup
	@cmake --preset fuzz >/dev/null
	@cmake --build $(FUZZ_DIR) -j $(JOBS) --target fuzz_slices_parser fuzz_rtstruct fuzz_mesh \
	  fuzz_label_volume fuzz_batch_texts
	@mkdir -p $(FUZZ_DIR)/corpus $(FUZZ_DIR)/crashes $(FUZZ_DIR)/corpus-rtstruct \
	  $(FUZZ_DIR)/crashes-rtstruct $(FUZZ_DIR)/crashes-mesh $(FUZZ_DIR)/crashes-label \
	  $(FUZZ_DIR)/corpus-batch $(FUZZ_DIR)/crashes-batch
	@cp -n examples/*.slices tests/data/fuzz/*.slices $(FUZZ_DIR)/corpus/ 2>/dev/null || true
	@cp -n tests/data/fuzz-rtstruct/* tests/data/fuzz-rtstruct-regressions/* \
	  $(FUZZ_DIR)/corpus-rtstruct/ 2>/dev/null || true
	@scripts/fuzz_corpus.sh mesh $(FUZZ_DIR)/corpus-mesh tests/data/fuzz-mesh/* \
	  tests/data/fuzz-mesh-regressions/*
	@scripts/fuzz_corpus.sh label $(FUZZ_DIR)/corpus-label tests/data/fuzz-label/* \
	  tests/data/fuzz-label-regressions/*
	@cp -n tests/data/fuzz-batch/* tests/data/fuzz-batch-regressions/* \
	  $(FUZZ_DIR)/corpus-batch/ 2>/dev/null || true
	[ $(FUZZ_SLICES_SECONDS) -le 0 ] || $(FUZZ_DIR)/bin/fuzz_slices_parser \
	  -max_total_time=$(FUZZ_SLICES_SECONDS) $(FUZZ_FLAGS) -artifact_prefix=$(FUZZ_DIR)/crashes/ \
	  $(FUZZ_DIR)/corpus
	[ $(FUZZ_RTSTRUCT_SECONDS) -le 0 ] || $(FUZZ_DIR)/bin/fuzz_rtstruct \
	  -max_total_time=$(FUZZ_RTSTRUCT_SECONDS) $(FUZZ_FLAGS) -max_len=8192 \
	  -artifact_prefix=$(FUZZ_DIR)/crashes-rtstruct/ $(FUZZ_DIR)/corpus-rtstruct
	[ $(FUZZ_MESH_SECONDS) -le 0 ] || $(FUZZ_DIR)/bin/fuzz_mesh \
	  -max_total_time=$(FUZZ_MESH_SECONDS) $(FUZZ_FLAGS) -max_len=8192 \
	  -artifact_prefix=$(FUZZ_DIR)/crashes-mesh/ $(FUZZ_DIR)/corpus-mesh
	[ $(FUZZ_LABEL_SECONDS) -le 0 ] || $(FUZZ_DIR)/bin/fuzz_label_volume \
	  -max_total_time=$(FUZZ_LABEL_SECONDS) $(FUZZ_FLAGS) -max_len=8192 \
	  -artifact_prefix=$(FUZZ_DIR)/crashes-label/ $(FUZZ_DIR)/corpus-label
	[ $(FUZZ_BATCH_SECONDS) -le 0 ] || $(FUZZ_DIR)/bin/fuzz_batch_texts \
	  -max_total_time=$(FUZZ_BATCH_SECONDS) $(FUZZ_FLAGS) -max_len=8192 \
	  -artifact_prefix=$(FUZZ_DIR)/crashes-batch/ $(FUZZ_DIR)/corpus-batch

format:
	@clang-format -i $$(git ls-files --cached --others --exclude-standard '*.cpp' '*.hpp' '*.cl')

format-check:
	@clang-format --dry-run --Werror $$(git ls-files --cached --others --exclude-standard '*.cpp' '*.hpp' '*.cl')

clean:
	rm -rf $(BUILD_DIR) $(SANITIZE_DIR) $(FUZZ_DIR)
