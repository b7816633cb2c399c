# glint — the two commands a new user needs:
#   make gallery   install what is missing, build, render every variant into out/gallery/index.html
#   make test      install what is missing, build, run the whole test suite (ctest)
# Both are idempotent and quick when everything is already there.
# The CI also runs `make sanitize`: the unit and GL tests under ASan + UBSan, 30 s of every
# fuzz harness, and the multi-threaded tools' tests under TSan (clang; separate builds).

BUILD ?= build
JOBS  ?= $(shell nproc)
GLINT := $(BUILD)/app/glint

# Unity builds (CMake: up to 16 sources of a target compiled as one translation unit): the
# headers (fmt, GLM, CLI11, nlohmann-json, Embree, CGAL) are parsed once per batch instead of
# once per file, which halves the CPU time of a clean build (src/render: 111 s -> 51 s).
# Incremental rebuilds recompile a whole batch; UNITY=-DCMAKE_UNITY_BUILD=OFF builds file by file.
# A target whose files share anonymous-namespace names opts out in its CMakeLists.txt.
UNITY ?= -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=16
# The Python the module is built for and tested with (Debian's, with numpy and pytest from
# scripts/setup; a python3 earlier on PATH, e.g. a pyenv shim, may lack them).
PYTHON ?= /usr/bin/python3
ASAN_BUILD ?= build-asan
TSAN_BUILD ?= build-tsan
FUZZ_SECONDS ?= 30
SANITIZER_ENV := ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 \
  LSAN_OPTIONS=suppressions=$(CURDIR)/fuzz/lsan.supp:print_suppressions=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  TSAN_OPTIONS=suppressions=$(CURDIR)/fuzz/tsan.supp:halt_on_error=1:second_deadlock_stack=1
# scripts/sanitized-ctest runs a failed test once more, alone, and ends with a digest of the
# failures: one that repeats fails the step, one that passes alone is reported as a flake.
# The GL tests run without leak checks: LeakSanitizer's stop-the-world tracer (clang 14)
# crashes at exit in processes with llvmpipe's threads ("Tracer caught signal 11"): a few
# GL test processes a run, sometimes twice in a row. ASan and UBSan stay on.
# Not under ASan: the viewer tests (X11 and GLX modules that Xvfb's GLFW loads and unloads
# leak 112 bytes that LeakSanitizer cannot name a library for), and the install test (it
# builds a consumer project without the sanitizer flags), and the farm test (a Slurm cluster
# running plain glint tools, which the other tests already run under ASan; make test runs it).
# Nor the tests of promises about processes rather than memory, which run the glint command
# on big inputs many times over (ASan makes them 5-8x slower: 7 minutes of CI between them)
# and add no code path the unit and GL tests miss: kill -9 at random points (KillNine.*),
# byte-identical output across runs and thread counts (Determinism.*; TSan checks the
# threads), glslangValidator reading the shader files (Glslang.*), and the edge cases of
# issue 33 (Trust*: the farm on the local scheduler, a full tmpfs, signals; their library
# code runs under ASan in the unit tests: farm_local_test, the CLI tests). make test runs them.
# And of issue 35's: the preview page in Chromium (BakePreview: a browser's time, not glint's
# memory), the model viewer under Xvfb (ModelView, as the viewer tests), and the model test
# that renders a dozen pictures (ModelRender.ABakes...: ModelRender.Cuts... runs the same
# loader and scene under ASan). And issue 37's pack test (gpu_check.pack): it installs the
# command and runs it with a clean environment, as a bare GPU machine would, so without the
# sanitizer options (LeakSanitizer would meet llvmpipe's threads); the readers it exercises
# run under ASan in BuiltinCodecs.*, the gallery's reference check in Cli.Gallery*.
# And issue 44's HostileModels: some 180 runs of the glint command (a model corpus through
# five commands) to check exit statuses and time limits; the readers it reaches run under
# ASan in the fuzz harnesses' replays of the same corpus (fuzz.gltf, fuzz.mesh_parts,
# fuzz.model_file) and in 30 s of fuzzing each.
ASAN_EXCLUDE := Viewer|Install\.AConsumer|farm_test|KillNine\.|Determinism\.|Glslang\.|Trust|BakePreview\.|ModelView\.|ModelRender\.ABakes|gpu_check\.|HostileModels\.
# Tests of the multi-threaded tools that TSan runs: the baker's and the cutter's parallel
# loops (oneTBB) and post's three-thread decode/process/encode pipeline (video/transcode).
# Library tests only, so the TSan build skips the GL layers and the glint command.
TSAN_TESTS := tests/bake/bake_maps_test tests/bake/bake_extra_maps_test tests/cut/cut_test tests/post/post_video_test

.PHONY: all setup setup-test configure build gallery test sanitize fuzz view accept-golden clean

all: build

# SETUP=true skips the installer: a system that is not Debian 12 or 13, with the packages
# README.md lists installed by hand (make SETUP=true test).
SETUP ?= scripts/setup
setup:
	@$(SETUP)

setup-test:
	@$(SETUP) --test

# Optimised as RelWithDebInfo (-O2, NDEBUG) but without debug info: a clean build compiles
# about a third faster (one large unit: 26.5 → 17.8 CPU s), and a new user's first
# `make gallery` / `make test` waits that much less. For a debugger:
# make BUILD=build-debug BUILD_TYPE=RelWithDebInfo test
BUILD_TYPE ?= Release
$(BUILD)/build.ninja:
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" $(UNITY) \
	  -DPython3_EXECUTABLE=$(PYTHON)

configure: $(BUILD)/build.ninja

build: setup configure
	cmake --build $(BUILD) -j $(JOBS)

gallery: build
	$(GLINT) gallery -o out/gallery
	@echo "open out/gallery/index.html"

test: setup-test configure
	cmake --build $(BUILD) -j $(JOBS)
	rm -rf $(BUILD)/cache $(BUILD)/test-home
	cd $(BUILD) && MESA_SHADER_CACHE_DISABLE=true ctest --output-on-failure -j $(JOBS) --timeout 600

sanitize: setup-test
	cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ $(UNITY) \
	  -DGLINT_SANITIZE=address,undefined -DGLINT_BUILD_FUZZERS=ON -DGLINT_HEADER_CHECK=OFF
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	$(SANITIZER_ENV) scripts/sanitized-ctest $(ASAN_BUILD) -L unit -E '$(ASAN_EXCLUDE)' -j $(JOBS) --timeout 900
	$(SANITIZER_ENV) ASAN_OPTIONS=detect_leaks=0:allocator_may_return_null=1 \
	  scripts/sanitized-ctest $(ASAN_BUILD) -L gl -E '$(ASAN_EXCLUDE)' -j $(JOBS) --timeout 900
	GLINT_FUZZ_BUILD=$(CURDIR)/$(ASAN_BUILD) scripts/fuzz $(FUZZ_SECONDS)
	cmake -S . -B $(TSAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ $(UNITY) \
	  -DGLINT_SANITIZE=thread -DGLINT_BUILD_VIEWER=OFF -DGLINT_BUILD_GL_TESTS=OFF
	cmake --build $(TSAN_BUILD) -j $(JOBS) --target $(notdir $(TSAN_TESTS))
	set -e; for t in $(TSAN_TESTS); do echo "TSan: $$t"; $(SANITIZER_ENV) $(TSAN_BUILD)/$$t --gtest_brief=1; done

# Fuzz for longer: make fuzz FUZZ_SECONDS=600 (after make sanitize has built the harnesses).
fuzz:
	GLINT_FUZZ_BUILD=$(CURDIR)/$(ASAN_BUILD) scripts/fuzz $(FUZZ_SECONDS)

view: build
	$(GLINT) view

# After looking at build/test-output/golden/**/*.actual.png: make accept-golden [FILTER=scene]
accept-golden:
	scripts/accept-golden $(FILTER)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(TSAN_BUILD) out
