# The two commands of the README: `make run` and `make test`. Each installs the Debian packages
# it needs (as root; otherwise prints the apt-get line), configures CMake, builds, then runs.
# Other targets: build, build-asan, test-release, test-asan, bench, bench-scenes, format, clean.

PACKAGES := cmake g++ make libgtest-dev libbenchmark-dev libtinyobjloader-dev libcli11-dev \
            nlohmann-json3-dev libfmt-dev libcgal-dev libembree-dev libtbb-dev libpng-dev \
            libassimp-dev libjemalloc-dev pkg-config nodejs chromium
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
BUILD := build
BUILD_ASAN := build-asan
SCENE_DIR := out

FUZZ_SECONDS ?= 60

.PHONY: run test deps build build-asan test-release test-asan bench bench-scenes fuzz format clean

run: build
	@./scripts/run-default.sh $(BUILD)/globalvis $(SCENE_DIR)

test: test-release test-asan

# nodejs: the machine's Node.js 20 (playwright-core needs >= 20; Debian 12's own is 18).
# The viewer's npm packages (three, esbuild, playwright-core; pinned by web/package-lock.json) are
# installed by `npm ci` whenever the lock is newer than web/node_modules.
deps:
	@./scripts/ensure-packages.sh $(PACKAGES)
	@command -v npm > /dev/null || ./scripts/ensure-packages.sh npm
	@[ web/node_modules/.package-lock.json -nt web/package-lock.json ] || (cd web && npm ci --no-audit --no-fund)

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

# The whole pipeline on the office size sweep and the small shared Quake maps, every result
# checked, into docs/BENCHMARKS.md's bench section. BENCH_ARGS=--quick: ~40 s; the default set
# ~3 min (E1M1-edited-ents runs into its 60 s budgets).
BENCH_ARGS ?=
bench-scenes: build
	@./$(BUILD)/globalvis bench $(BENCH_ARGS) --update-docs docs/BENCHMARKS.md

# libFuzzer on the input readers (clang + libclang-rt-14-dev): the OBJ importer, the Quake .prt
# reader and the .map parser, FUZZ_SECONDS each; FUZZ_TARGET=prt_file_fuzz (say) runs one. Seeds
# in fuzz/corpus/<obj|prt|map>/; each corpus grows in build-fuzz/corpus/<target>/.
FUZZ_TARGET ?= obj_import_fuzz prt_file_fuzz map_file_fuzz
fuzz: deps
	@./scripts/ensure-packages.sh clang libclang-rt-14-dev
	@cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGV_FUZZ=ON > build-fuzz.configure.log || (cat build-fuzz.configure.log; exit 1)
	@cmake --build build-fuzz -j $(JOBS) --target $(FUZZ_TARGET)
	@for t in $(FUZZ_TARGET); do \
	  seeds=fuzz/corpus/$${t%%_*}; \
	  mkdir -p build-fuzz/corpus/$$t && { cp -n $$seeds/* build-fuzz/corpus/$$t/ || true; } && \
	  ./build-fuzz/$$t -max_total_time=$(FUZZ_SECONDS) -max_len=4096 build-fuzz/corpus/$$t || exit 1; \
	done

format:
	@clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) $(BUILD_ASAN) build-fuzz *.configure.log
