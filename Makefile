# Thin wrapper around CMake. `make verify` runs the suite; `make check` runs the tests.
BUILD ?= build
TYPE ?= Release
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all deps build check verify report cases bench sanitize clean

all: build

deps:
	@scripts/install-deps

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=$(TYPE) $(CMAKE_FLAGS) > /dev/null
	@scripts/run-logged build $(BUILD)/build.log cmake --build $(BUILD) -j $(JOBS)

check: build
	@echo "check: running the tests (about 2 minutes on 2 cores; full output in $(BUILD)/ctest.log)"
	@scripts/run-logged test $(BUILD)/ctest.log ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS) --timeout 600

verify: build
	@scripts/verify $(BUILD); status=$$?; scripts/report $(BUILD); exit $$status

report: build
	@scripts/report $(BUILD)

cases: build
	@scripts/verify $(BUILD) --cases

bench: build
	@scripts/bench $(BUILD)

sanitize:
	@$(MAKE) check BUILD=build-sanitize TYPE=Sanitize

clean:
	rm -rf build build-sanitize
