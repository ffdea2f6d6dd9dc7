# Thin wrapper: every target installs what is missing, configures (Release) and builds.
BUILD ?= build
# The sanitizer build: clang, AddressSanitizer + UndefinedBehaviorSanitizer, libFuzzer's coverage
# instrumentation; the fuzzers (fuzz/) and the whole test suite again, sanitized.
FUZZ_BUILD ?= build-fuzz
# -O2 and line tables, enough for every report's file and line. At -O1 the small math functions
# (dot products, clamps, array indexing) were not inlined under the instrumentation: the sanitized
# suite's tests summed 830 s at -O1 and 701 s at -O2 (docs/robustness.md, item 14).
FUZZ_OPT ?= -O2 -gline-tables-only -DNDEBUG
JOBS  ?= $(shell nproc)
# ccache (CMakeLists.txt, GLINT_CCACHE): paths inside the checkout are hashed relative to it, and
# the working folder not at all, so a fresh clone in another folder reuses what an earlier build
# compiled.
export CCACHE_BASEDIR ?= $(CURDIR)
export CCACHE_NOHASHDIR ?= 1
CMAKE_FLAGS ?=

.PHONY: all deps configure build demo test test-release test-sanitized test-blender fuzz bench bench-cycles bench-embree bench-volumes gallery sanitize clean

all: build

deps:
	scripts/install-deps.sh

$(BUILD)/build.ninja: | deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

configure: deps $(BUILD)/build.ninja

build: configure
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	$(BUILD)/apps/glint/glint render -o glint.png

# Every test: the release build's suite, then the sanitizer build's (the same suite under
# ASan+UBSan, and a regression run of every fuzzer over its corpus).
test: test-release test-sanitized

# The suite needs the test binaries (which pull in the command, its modules and the tools the tests
# run), not the benchmarks: those are built by `make build` and `make bench`.
TEST_TARGETS = glint_tests glint_tests_oiio

test-release: configure
	cmake --build $(BUILD) -j $(JOBS) --target $(TEST_TARGETS)
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The Blender add-on against Cycles, headless (docs/blender.md): not part of `make test`, since it
# installs Blender (about 300 MB from Debian, a few minutes on a fresh machine); about a minute (63 s here).
test-blender: configure
	GLINT_BENCH_DEPS=1 scripts/install-deps.sh
	cmake --build $(BUILD) -j $(JOBS) --target glint_python glint_cloud_vdb
	GLINT_PYTHON=$(CURDIR)/$(BUILD)/python/glint blender -b --factory-startup --python tests/blender/test_engine.py
	GLINT_PYTHON=$(CURDIR)/$(BUILD)/python/glint xvfb-run -a -s "-screen 0 1280x800x24" \
	  blender --factory-startup --python tests/blender/test_viewport.py

$(FUZZ_BUILD)/build.ninja: | deps
	CXX=clang++ cmake -S . -B $(FUZZ_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$(FUZZ_OPT)" \
	  -DGLINT_SANITIZE=address,undefined -DGLINT_FUZZ=ON -DGLINT_IPO=OFF -DGLINT_BUILD_BENCH=OFF

# The fuzzers, their seed corpora and the sanitized test suite, in $(FUZZ_BUILD)/.
fuzz: deps $(FUZZ_BUILD)/build.ninja
	cmake --build $(FUZZ_BUILD) -j $(JOBS)

sanitize: test-sanitized

test-sanitized: fuzz
	cd $(FUZZ_BUILD) && ctest --output-on-failure -j $(JOBS)

bench:
	GLINT_BENCH_DEPS=1 scripts/install-deps.sh
	$(MAKE) build
	bench/compare_povray.sh $(BUILD)

# The path tracer against Blender Cycles on the Cornell box (about 25 minutes on 2 cores).
bench-cycles:
	GLINT_BENCH_DEPS=1 scripts/install-deps.sh
	$(MAKE) build
	THREADS_HIGH=2 bench/compare_cycles.sh $(BUILD) 3

# Volumes beside Blender Cycles: the fog and the VDB cloud of bench/volumes/ (about 15 minutes).
bench-volumes:
	GLINT_BENCH_DEPS=1 scripts/install-deps.sh
	$(MAKE) build
	bench/compare_volumes.sh $(BUILD) fog 3
	bench/compare_volumes.sh $(BUILD) cloud 3

# glint's BVH beside Embree 3 (glint bench on four scenes, 1 and 2 threads; about 2 minutes).
bench-embree: build
	bench/compare_embree.sh $(BUILD) 5

gallery: build
	scripts/render-gallery.sh $(BUILD)

clean:
	rm -rf $(BUILD) $(FUZZ_BUILD)
