# Thin wrapper: every target installs what is missing, configures (Release) and builds.
BUILD ?= build
JOBS  ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all deps configure build demo test bench gallery clean

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
	@echo "wrote glint.png"

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench:
	GLINT_BENCH_DEPS=1 scripts/install-deps.sh
	$(MAKE) build
	bench/compare_povray.sh $(BUILD)

gallery: build
	scripts/render-gallery.sh $(BUILD)

clean:
	rm -rf $(BUILD)
