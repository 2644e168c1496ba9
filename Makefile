# The two commands of the README, and the ones behind them.
#   make demo   install deps, build, write the sample HNIs, their reports and renders, and three
#               converted OBJ samples (two buildings, a street as a city) beside their meshes, under out/
#   make test   install deps, build, run the whole test suite (ctest) and a short fuzz run
#   make bench  run the benchmarks (Release build)
#   make bench-quick   every benchmark once on small inputs, then the pinned ratios against their
#               baselines (bench/pinned_ratios.json): fails when one fell past its margin
#   make fuzz   run one libFuzzer target longer: make fuzz TARGET=obj_fuzz FUZZ_SECONDS=600
#               (targets: hni_fuzz, the default, obj_fuzz, glb_fuzz, city_fuzz, render_fuzz, grammar_fuzz;
#               docs/INPUT.md)
#   make core-check   build the core alone (optional modules off) and check what it links
#   make test-sanitize   build the whole suite with AddressSanitizer + UBSan and run it
#   make test-thread     build the tests of the parallel code with ThreadSanitizer and run them
BUILD ?= build
CORE_BUILD ?= build-core
SANITIZE_BUILD ?= build-asan
THREAD_BUILD ?= build-tsan
FUZZ_BUILD ?= build-fuzz
JOBS ?= $(shell nproc)
FUZZ_SECONDS ?= 600
TARGET ?= hni_fuzz
# make test's fuzz run: hni_fuzz for FUZZ_SMOKE_SECONDS, each other target for
# FUZZ_SMOKE_OTHER_SECONDS: 30 + 5 x 10 = 80 s in all.
FUZZ_SMOKE_SECONDS ?= 30
FUZZ_SMOKE_OTHER_SECONDS ?= 10
FUZZ_TARGETS = hni_fuzz obj_fuzz glb_fuzz city_fuzz render_fuzz grammar_fuzz
# Per target: dictionary and input size cap (the OBJ seeds reach 50 KB).
FUZZ_FLAGS_obj_fuzz = -dict=tests/fuzz/obj.dict -max_len=65536
FUZZ_FLAGS_city_fuzz = -dict=tests/fuzz/city.dict
FUZZ_FLAGS_grammar_fuzz = -dict=tests/fuzz/grammar.dict
FUZZ_FLAGS_glb_fuzz = -dict=tests/fuzz/glb.dict
# $(call fuzz-run,TARGET,SECONDS): the target over its generated seeds (where it writes what it
# finds), its hand-made inputs and its regressions; a unit running over 10 s counts as a hang.
fuzz-run = $(FUZZ_BUILD)/tests/$(1) -max_total_time=$(2) -timeout=10 -print_final_stats=1 $(FUZZ_FLAGS_$(1)) \
  -artifact_prefix=$(FUZZ_BUILD)/$(1)- $(FUZZ_BUILD)/corpus/$(1) $(wildcard tests/fuzz/corpus/$(1) tests/fuzz/regressions/$(1))
# $(call fuzz-smoke-run,TARGET,SECONDS): one target briefly, showing its executions and any report.
fuzz-smoke-run = echo "fuzz: $(1) for $(2) s" >&2; $(call fuzz-run,$(1),$(2)) 2>&1 | \
  grep -E "^(stat::number_of_executed_units|==|SUMMARY)|ERROR|fuzz check failed" >&2 || true;
fuzz-smoke-seconds = $(if $(filter hni_fuzz,$(1)),$(FUZZ_SMOKE_SECONDS),$(FUZZ_SMOKE_OTHER_SECONDS))
OUT ?= out

.PHONY: deps build test demo bench bench-quick fuzz fuzz-build fuzz-smoke core-check test-sanitize test-thread clean

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

# Any sanitizer report fails its test: UBSan does not recover, ASan stops at the first error.
test-sanitize: deps
	@cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DNUT_BUILD_BENCH=OFF \
	  -DCMAKE_CXX_FLAGS="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer" \
	  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" > /dev/null
	@cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	@UBSAN_OPTIONS=print_stacktrace=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp \
	  ctest --test-dir $(SANITIZE_BUILD) --output-on-failure -j $(JOBS)

# The code that runs threads (docs/INPUT.md, "Sanitizers"): the pixel loop of both CPU renderers,
# `nut city` and `nut convert` building side by side, the PNG encoder's workers and the viewer's
# loader threads, through the tests that run them with two threads or more.
THREAD_TESTS = cli_test converter_cli_test png_io_test city_viewer_test
THREAD_TEST_NAMES = CityCli|RenderCli|ConvertCli|PngIo|StreamedCity
test-thread: deps
	@cmake -S . -B $(THREAD_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DNUT_BUILD_BENCH=OFF \
	  -DCMAKE_CXX_FLAGS="-fsanitize=thread" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" > /dev/null
	@cmake --build $(THREAD_BUILD) -j $(JOBS) --target $(THREAD_TESTS) nut_cli nut_viewer_app
	@TSAN_OPTIONS="halt_on_error=1 suppressions=$(CURDIR)/tests/tsan.supp" \
	  ctest --test-dir $(THREAD_BUILD) --output-on-failure -j $(JOBS) -R '^($(THREAD_TEST_NAMES))\.'

demo: build
	@./scripts/demo.sh $(BUILD) $(OUT)

bench: build
	@./scripts/bench.sh $(BUILD)

bench-quick: build
	@./scripts/bench-quick.sh $(BUILD)

fuzz-build: deps
	@cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DNUT_BUILD_FUZZ=ON -DNUT_BUILD_BENCH=OFF \
	  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
	  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined" > /dev/null
	@cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(FUZZ_TARGETS) fuzz_seeds
	@$(FUZZ_BUILD)/tests/fuzz_seeds $(FUZZ_BUILD)/corpus

# Fails when any run left a crash, leak, out-of-memory or timeout input (kept until removed).
fuzz-smoke: fuzz-build
	@$(foreach t,$(FUZZ_TARGETS),$(call fuzz-smoke-run,$(t),$(call fuzz-smoke-seconds,$(t))))
	@! ls $(FUZZ_BUILD)/*-crash-* $(FUZZ_BUILD)/*-leak-* $(FUZZ_BUILD)/*-oom-* $(FUZZ_BUILD)/*-timeout-* 2>/dev/null

fuzz: fuzz-build
	@$(call fuzz-run,$(TARGET),$(FUZZ_SECONDS))

clean:
	rm -rf $(BUILD) $(CORE_BUILD) $(SANITIZE_BUILD) $(THREAD_BUILD) $(FUZZ_BUILD) $(OUT)
