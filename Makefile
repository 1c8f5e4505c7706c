# The two commands of the README: `make run` and `make test`. Each installs the Debian packages
# it needs (as root; otherwise prints the apt-get line), configures CMake, builds, then runs.
# Other targets: build, build-asan, test-release, test-asan, bench, format, clean.

PACKAGES := cmake g++ make libgtest-dev libbenchmark-dev libtinyobjloader-dev libcli11-dev \
            nlohmann-json3-dev libfmt-dev libcgal-dev
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
BUILD := build
BUILD_ASAN := build-asan
SCENE_DIR := $(BUILD)/out

.PHONY: run test deps build build-asan test-release test-asan bench format clean

run: build
	@./scripts/run-default.sh $(BUILD)/globalvis $(SCENE_DIR)

test: test-release test-asan

deps:
	@./scripts/ensure-packages.sh $(PACKAGES)

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release > $(BUILD).configure.log || (cat $(BUILD).configure.log; exit 1)
	@cmake --build $(BUILD) -j $(JOBS)

build-asan: deps
	@cmake -S . -B $(BUILD_ASAN) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGV_SANITIZE=ON -DGV_BUILD_BENCHMARKS=OFF > $(BUILD_ASAN).configure.log || (cat $(BUILD_ASAN).configure.log; exit 1)
	@cmake --build $(BUILD_ASAN) -j $(JOBS)

test-release: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

test-asan: build-asan
	@cd $(BUILD_ASAN) && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j $(JOBS)

bench: build
	@./$(BUILD)/globalvis_bench --benchmark_min_time=0.2

format:
	@clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) $(BUILD_ASAN) $(BUILD).configure.log $(BUILD_ASAN).configure.log
