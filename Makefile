# Prism. On a fresh Debian 12 machine:
#   make render   installs what is missing, builds (Release), renders the default scene
#   make test     the same set-up, then the whole test suite
#   make check    the repository's own rules: C/C++ layout (clang-format-14) and words (tools/check_words.sh)
#   make test-sanitize   the test suite built with AddressSanitizer + UBSan (in build-asan/)
#   make fuzz     libFuzzer targets (clang, in build-fuzz/), each run FUZZ_SECONDS on a generated corpus
#   make bench-rays   Prism's BVH against Embree, ray for ray (needs raybench built in the shared assets (PRISM_SHARED_DIR))
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
SPP ?= 12
SIZE ?= 512

PACKAGES := cmake make g++ pkg-config python3 libopenexr-dev libopencolorio-dev libtinygltf-dev nlohmann-json3-dev \
            libstb-dev catch2 libtbb-dev libcli11-dev libfmt-dev libdraco-dev libmeshoptimizer-dev libwebp-dev \
            libyaml-cpp-dev
FUZZ_PACKAGES := clang-14 libclang-rt-14-dev
ASAN_DIR ?= build-asan
FUZZ_DIR ?= build-fuzz
FUZZ_SECONDS ?= 60
SANITIZE := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer

.PHONY: all deps build render test check test-slurm test-sanitize fuzz bench-rays clean

all: build

deps:
	@tools/install-deps.sh $(PACKAGES)

build: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD_DIR) -j $(JOBS)

render: build
	$(BUILD_DIR)/apps/prism render data/scenes/cornell.gltf -o out/default.exr --preview out/default.png \
	  --spp $(SPP) --width $(SIZE) --height $(SIZE)

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS) -LE slurm

# The repository's own rules, checked before anything is built: every tracked C/C++ file in the
# layout of .clang-format, and no tracked file speaking of how the work was organised.
check:
	@tools/install-deps.sh clang-format-14 git
	git ls-files -z '*.cpp' '*.h' | xargs -0 clang-format-14 --dry-run -Werror
	tools/check_words.sh

# `prism farm slurm` on a single-node Slurm cluster it starts on this machine (root; skips otherwise).
test-slurm: build
	cd $(BUILD_DIR) && ctest --output-on-failure -L slurm

# The whole suite under AddressSanitizer + UndefinedBehaviorSanitizer: any finding fails a test.
# Optimised, with line tables only (-g1): the reports still name file and line, and the build is
# much quicker than with full debug information.
test-sanitize: deps
	cmake -S . -B $(ASAN_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS=$(SANITIZE)" \
	  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG" "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined"
	cmake --build $(ASAN_DIR) -j $(JOBS)
	cd $(ASAN_DIR) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j $(JOBS) -LE slurm

# Each libFuzzer target for FUZZ_SECONDS on a corpus seeded by fuzz/make_corpus.py (see
# tools/run_fuzzers.sh); a crash, leak, timeout or sanitizer report fails.
fuzz: deps
	@tools/install-deps.sh $(FUZZ_PACKAGES)
	cmake -S . -B $(FUZZ_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
	  -DPRISM_FUZZ=ON -DPRISM_BUILD_TESTS=OFF
	cmake --build $(FUZZ_DIR) -j $(JOBS) --target fuzz_gltf fuzz_env_map fuzz_image
	tools/run_fuzzers.sh $(FUZZ_DIR) $(FUZZ_SECONDS)

# Prism's BVH against Embree on raybench's ray sets (needs raybench built; see tools/bench_rays.sh).
bench-rays: build
	tools/bench_rays.sh

clean:
	rm -rf $(BUILD_DIR) $(ASAN_DIR) $(FUZZ_DIR) out
