# Thin wrapper: every target installs what is missing, configures (Release) and builds.
BUILD ?= build
JOBS  ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all deps configure build demo test bench bench-cycles bench-embree bench-volumes gallery sanitize clean

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

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

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

# Every test under AddressSanitizer + UndefinedBehaviorSanitizer (clang), in build-asan/.
sanitize:
	GLINT_SANITIZE_DEPS=1 scripts/install-deps.sh
	CXX=clang++ cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DGLINT_SANITIZE=address,undefined -DGLINT_IPO=OFF -DGLINT_BUILD_BENCH=OFF
	cmake --build build-asan -j $(JOBS)
	cd build-asan && UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 ctest --output-on-failure -j $(JOBS)

gallery: build
	scripts/render-gallery.sh $(BUILD)

clean:
	rm -rf $(BUILD) build-asan
