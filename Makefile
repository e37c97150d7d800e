# Prism. On a fresh Debian 12 machine:
#   make render   installs what is missing, builds (Release), renders the default scene
#   make test     the same set-up, then the whole test suite
#   make bench-rays   Prism's BVH against Embree, ray for ray (needs ../shared/tools/raybench built)
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
SPP ?= 64
SIZE ?= 512

PACKAGES := cmake make g++ pkg-config libopenexr-dev libopencolorio-dev libtinygltf-dev nlohmann-json3-dev \
            libstb-dev catch2 libtbb-dev libcli11-dev libfmt-dev \
            libdraco-dev libmeshoptimizer-dev libwebp-dev

.PHONY: all deps build render test bench-rays clean

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
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# Prism's BVH against Embree on raybench's ray sets (needs raybench built; see tools/bench_rays.sh).
bench-rays: build
	tools/bench_rays.sh

clean:
	rm -rf $(BUILD_DIR) out
