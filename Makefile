# Thin wrapper: install what is missing, configure and build Release into build/, then act.
#   make run    build, then run the default example (results under out/)
#   make test   build, then the whole test suite through ctest
#   make bench  build, then the step-loop benchmark (particle-steps per second)
BUILD_DIR  ?= build
BUILD_TYPE ?= Release
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_ARGS ?=

# Debian 12 packages the build needs (compiler, CMake, Eigen, Catch2, Lua 5.4, readline, CLI11, VTK 9.1;
# OpenMP comes with g++), gnuplot for the plots, python3 for the tests that drive the console on a terminal.
PACKAGES = g++ make cmake pkg-config libeigen3-dev catch2 liblua5.4-dev libreadline-dev libcli11-dev \
           libvtk9-dev gnuplot-nox python3

.PHONY: all deps configure build run test sanitize bench clean

all: build

deps:
	@./scripts/install-deps.sh $(PACKAGES)

configure: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(CMAKE_ARGS) >/dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

run: build
	@mkdir -p out
	./$(BUILD_DIR)/seismpm scenarios/shaking_table.lua

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)
	@$(MAKE) --no-print-directory sanitize

# The program built with AddressSanitizer and UndefinedBehaviorSanitizer, over the fast tests that drive
# it with scripts (label "sanitize": examples, console, hostile scripts and files). Only the program is
# built there, not the unit-test binary, to keep CI short. Any report fails the test.
SANITIZE_DIR ?= build-sanitize
sanitize: deps
	@cmake -S . -B $(SANITIZE_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSEISMPM_SANITIZE=ON -DSEISMPM_BENCH=OFF >/dev/null
	@cmake --build $(SANITIZE_DIR) -j $(JOBS) --target seismpm
	cd $(SANITIZE_DIR) && ctest --output-on-failure -j $(JOBS) -L sanitize

# The step loop on every case (1 and 2 threads) with its ratio to bench/baseline.txt (the code before
# the speed work, measured in one sitting beside it: bench/compare.sh), then the memory per particle.
bench: build
	./$(BUILD_DIR)/bench/seismpm_bench --baseline bench/baseline.txt
	bench/memory.sh $(BUILD_DIR)/seismpm

clean:
	rm -rf $(BUILD_DIR)
