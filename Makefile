# The two commands of the README, and the ones behind them.
#   make demo   install deps, build, write the sample HNIs, their reports and renders, and three
#               converted OBJ samples (two buildings, a street as a city) beside their meshes, under out/
#   make test   install deps, build, run the whole test suite (ctest) and a short fuzz run
#   make bench  run the benchmarks (Release build)
#   make fuzz   run the libFuzzer target longer: make fuzz FUZZ_SECONDS=600
#   make core-check   build the core alone (optional modules off) and check what it links
BUILD ?= build
CORE_BUILD ?= build-core
FUZZ_BUILD ?= build-fuzz
JOBS ?= $(shell nproc)
FUZZ_SECONDS ?= 600
FUZZ_SMOKE_SECONDS ?= 30
OUT ?= out

.PHONY: deps build test demo bench fuzz fuzz-build fuzz-smoke core-check clean

deps:
	@./scripts/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DNUT_WERROR=ON > /dev/null
	@cmake --build $(BUILD) -j $(JOBS)

test: build
	@ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)
	@$(MAKE) --no-print-directory core-check
	@$(MAKE) --no-print-directory fuzz-smoke

core-check: deps
	@./scripts/check-core-build.sh $(CORE_BUILD)

demo: build
	@./scripts/demo.sh $(BUILD) $(OUT)

bench: build
	@./scripts/bench.sh $(BUILD)

fuzz-build: deps
	@cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DNUT_BUILD_FUZZ=ON -DNUT_BUILD_BENCH=OFF \
	  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
	  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined" > /dev/null
	@cmake --build $(FUZZ_BUILD) -j $(JOBS) --target hni_fuzz fuzz_seeds
	@mkdir -p $(FUZZ_BUILD)/corpus
	@$(FUZZ_BUILD)/tests/fuzz_seeds $(FUZZ_BUILD)/corpus

fuzz-smoke: fuzz-build
	@echo "fuzz: hni_fuzz for $(FUZZ_SMOKE_SECONDS) s" >&2
	@$(FUZZ_BUILD)/tests/hni_fuzz -max_total_time=$(FUZZ_SMOKE_SECONDS) -print_final_stats=1 \
	  -artifact_prefix=$(FUZZ_BUILD)/ $(FUZZ_BUILD)/corpus 2>&1 | grep -E "^(stat::number_of_executed_units|==|SUMMARY)|ERROR" >&2 || true
	@! ls $(FUZZ_BUILD)/crash-* $(FUZZ_BUILD)/leak-* $(FUZZ_BUILD)/timeout-* 2>/dev/null

fuzz: fuzz-build
	@$(FUZZ_BUILD)/tests/hni_fuzz -max_total_time=$(FUZZ_SECONDS) -print_final_stats=1 \
	  -artifact_prefix=$(FUZZ_BUILD)/ $(FUZZ_BUILD)/corpus

clean:
	rm -rf $(BUILD) $(CORE_BUILD) $(FUZZ_BUILD) $(OUT)
