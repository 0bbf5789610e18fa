# The README's two commands, plus a few conveniences.
#   make demo   install what is missing, build, render the default scene (EXR + PNG)
#   make test   install what is missing, build, run the whole test suite with ctest
#   make bench  the paper's Table 1 benchmark and VTK's CPU ray caster on the same work:
#               tables, bench/results.json and the results section of docs/performance.md
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
	@bash scripts/install-deps.sh --bench
	@cmake --build $(BUILD) --parallel $(JOBS) --target cutaway_bench
	@rm -rf $(BUILD)/bench/vtk
	@$(BUILD)/bench/cutaway_bench --vtk-dir $(BUILD)/bench/vtk $(BENCH_ARGS)
	@xvfb-run -a /usr/bin/python3 bench/vtk_bench.py $(BUILD)/bench/vtk bench/results.json
	@/usr/bin/python3 bench/report.py bench/results.json docs/performance.md

gallery: configure
	@cmake --build $(BUILD) --parallel $(JOBS) --target cutaway
	@/usr/bin/python3 scripts/gallery.py $(BUILD)/cutaway $(SCENES)

format:
	@git ls-files '*.cpp' '*.hpp' '*.h' | xargs clang-format -i

clean:
	@rm -rf $(BUILD) out
