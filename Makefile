# The README's two commands, plus a few conveniences.
#   make demo   install what is missing, build, render the default scene (EXR + PNG)
#   make test   install what is missing, build, run the whole test suite with ctest
#   make bench  bake times at 256^3 (a table; the Table 1 frame benchmark comes later)
#   make gallery  render every gallery scene at 512^2: docs/gallery/*.png and docs/gallery.md
BUILD ?= build
JOBS ?= $(shell nproc)
BUILD_TYPE ?= Release

.PHONY: all deps configure build demo test bench gallery clean format

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	@if [ ! -f $(BUILD)/build.ninja ]; then \
	  cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) >/dev/null; fi

build: configure
	@cmake --build $(BUILD) --parallel $(JOBS)

demo: configure
	@cmake --build $(BUILD) --parallel $(JOBS) --target cutaway
	@$(BUILD)/cutaway render scenes/demo.json --png
	@echo "demo: open out/demo_0000.exr (linear, premultiplied RGBA) or out/demo_0000.png"

test: build
	@ctest --test-dir $(BUILD) --output-on-failure --timeout 900 -j $(JOBS)

bench: configure
	@cmake --build $(BUILD) --parallel $(JOBS) --target cutaway_bench_bake
	@$(BUILD)/bench/cutaway_bench_bake 256 3

gallery: configure
	@cmake --build $(BUILD) --parallel $(JOBS) --target cutaway
	@/usr/bin/python3 scripts/gallery.py $(BUILD)/cutaway $(SCENES)

format:
	@git ls-files '*.cpp' '*.hpp' '*.h' | xargs clang-format -i

clean:
	@rm -rf $(BUILD) out
