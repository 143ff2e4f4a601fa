# One-command entry points (README). Each target installs missing Debian packages first.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=RelWithDebInfo

.PHONY: deps configure build demo test sanitize format clean

deps:
	bash scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD) -G Ninja $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# Runs the default graph headless on the default device; images + report.json in out/demo.
demo: build
	$(BUILD)/fovea run graphs/demo.json --out out/demo --overwrite
	@echo "demo: see out/demo/ (report.json, *.exr, *.png)"

# The whole suite, validation layer on (FOVEA_VALIDATION=1 is set by ctest for every test).
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 900

# Address + UndefinedBehavior sanitizers in a separate build tree.
sanitize:
	$(MAKE) test BUILD=build-asan CMAKE_FLAGS="-DCMAKE_BUILD_TYPE=Debug -DFOVEA_SANITIZE=ON"

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) build-asan out
