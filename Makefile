# One-command entry points (README). Each target installs missing Debian packages first.
BUILD ?= build
JOBS ?= $(shell nproc)
# -g1 (line tables: backtraces and gdb still name file and line) instead of CMake's -g: each
# vulkan.hpp-heavy file compiles about a quarter faster and the objects are 4x smaller, which is
# minutes of every clean build and of CI (docs/testing.md "Build time").
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG"

.PHONY: deps configure build demo test install sanitize sanitize-ci fuzz format clean

deps:
	bash scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD) -G Ninja $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# Runs the default graph headless on the default device; images + report.json in out/demo.
# Builds only the executable (about a third of the compile units are tests: `make test`).
demo: configure
	cmake --build $(BUILD) -j $(JOBS) --target fovea
	$(BUILD)/fovea run graphs/demo.json --out out/demo --overwrite
	@echo "demo: pictures in $(CURDIR)/out/demo/ (tm.ldr.frame0015.png: the tone-mapped mean; report.json: timings)"
	@echo "next: $(BUILD)/fovea run graphs/koskela_bmfr.json --size 320x180 --out out/bmfr --overwrite"

# The whole suite, validation layer on (FOVEA_VALIDATION=1 is set by ctest for every test).
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 900

# A Release build without the test suite, installed stripped (docs/install.md):
#   make install PREFIX=/opt/fovea
# Its own build tree, so the test tree's RelWithDebInfo objects stay as they are.
PREFIX ?= /usr/local
INSTALL_BUILD ?= build-release
install: deps
	cmake -S . -B $(INSTALL_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DFOVEA_BUILD_TESTS=OFF
	cmake --build $(INSTALL_BUILD) -j $(JOBS)
	cmake --install $(INSTALL_BUILD) --prefix $(PREFIX) --strip

# Address + UndefinedBehavior sanitizers in a separate build tree.
sanitize:
	$(MAKE) test BUILD=build-asan-full CMAKE_FLAGS="-DCMAKE_BUILD_TYPE=Debug -DFOVEA_SANITIZE=ON"

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) build-asan build-asan-full $(INSTALL_BUILD) out

# The CI's sanitizer step: ASan + UBSan over the tests that parse and check user input (graph
# JSON, parameters, glTF incl. the malformed-file suite, camera paths, CLI arguments) and build
# CPU data structures, and the fuzz targets (tests/fuzz): their saved inputs replayed, then
# libFuzzer for FUZZ_SECONDS per target. GPU-heavy tests stay in `make test` (lavapipe under ASan
# is slow). Leak detection is off for the tests: the Vulkan loader, llvmpipe's JIT and librsvg
# (loaded by OpenImageIO) keep allocations until exit, which LeakSanitizer reports (and turns into
# exit code 1); the fuzz targets touch no Vulkan and run with it on (tests/fuzz/fuzz.sh).
# clang at -O0 -g1: libFuzzer needs clang, and this tree builds in about a third of gcc's time
# (docs/testing.md "Build time"); only the test files of these suites are compiled
# (fovea_input_tests, tests/CMakeLists.txt).
SANITIZE_TESTS ?= Flip|ReferenceShard\.|CliImageFile|CliCompare|CliPlugin|PngOutput|Environment|TextureView|Tangents|SceneLoad|SceneFeatures|ShaderCompiler|SceneGltfSynthetic|SceneGltfAlpha|SceneGltfLimits|SceneBuiltin|GraphDesc|Param|Compiler|BadGraph|JsonUtil|Camera|BvhBuild|LightTable|CliInput|CliValidate
FUZZ_SECONDS ?= 20
sanitize-ci: deps
	cmake -S . -B build-asan -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=None \
	  -DCMAKE_CXX_FLAGS="-O0 -g1" -DFOVEA_SANITIZE=ON -DFOVEA_FUZZ=ON
	cmake --build build-asan -j $(JOBS) --target fovea_input_tests fovea_fuzz_targets
	cd build-asan && ASAN_OPTIONS=detect_leaks=0 ctest -R '^(input\..*($(SANITIZE_TESTS))|fuzz\.replay\.)' --output-on-failure -j $(JOBS) --timeout 900
	FUZZ_SEED=1 bash tests/fuzz/fuzz.sh fuzz build-asan $(FUZZ_SECONDS)

# Fuzz for longer (docs/testing.md "Fuzzing"): e.g. make fuzz FUZZ_SECONDS=1800 FUZZ_TARGETS=gltf
FUZZ_TARGETS ?=
fuzz: deps
	cmake -S . -B build-asan -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=None \
	  -DCMAKE_CXX_FLAGS="-O0 -g1" -DFOVEA_SANITIZE=ON -DFOVEA_FUZZ=ON
	cmake --build build-asan -j $(JOBS) --target fovea_fuzz_targets
	bash tests/fuzz/fuzz.sh fuzz build-asan $(FUZZ_SECONDS) $(FUZZ_TARGETS)
