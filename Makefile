# voxgi - build, tests, demo and benchmarks.  `make test` and `make demo` set up what they need.
CC      ?= cc
CXX     ?= c++
WARN    := -Wall -Wextra -pedantic -Werror
CFLAGS  ?= -O2 -g
LDLIBS  := -lm -lpthread -ldl
B       := build
ASAN    := -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
TSAN    := -O1 -g -fsanitize=thread -fno-omit-frame-pointer

GLSL    := $(sort $(wildcard shaders/*.glsl))
# The test programs, on one line (tests/run.sh reads it), in the order tests/run.sh starts them:
# the tool's first (test_tool runs longest), then one per part of voxgi.h, each with its GL twins
# (test_core: parts 2 and 4, test_rays 3, test_voxelize 5 and test_exact its GMP oracle,
# test_volumes 6, test_octree 7, test_vct 8-9, test_lightspace 10, test_screenspace 11,
# test_linespace 12, test_reference 13, test_plan 14, test_files 15), then the stiff cases across
# the parts, two contexts on two threads at once (test_threads; also under ThreadSanitizer: make
# tsan), every allocation failing and every progress report cancelling in turn (test_faults) and
# the private helpers' tests (test_internals, ordered by part). test_fuzz_inputs runs the fuzzers'
# seeds and findings (fuzz/) through their harnesses.
TESTS   := test_tool test_mesh_io test_io_export test_fuzz_inputs test_headless_gl test_core test_rays test_voxelize test_exact test_volumes test_octree test_vct test_lightspace test_screenspace test_linespace test_reference test_plan test_files test_stiff test_threads test_faults test_internals
# The test programs that link the implementation object (voxgi.h's and voxgi_io.h's; they include
# the headers for the declarations only); test_internals (private helpers) compiles the
# implementation itself.
LINKED_TESTS := $(filter-out test_internals test_headless_gl,$(TESTS))
# test_exact's oracle computes in GMP rationals (libgmp-dev, a test-only dependency).
$(B)/test_exact $(B)/asan/test_exact: LDLIBS += -lgmp
NPROC   := $(shell nproc 2>/dev/null || echo 2)
TOOL_SRC := tools/voxgi.c $(wildcard tools/cli*.c tools/cmd_*.c)
TOOL_H   := $(wildcard tools/*.h)
# The examples (examples/*.c; tests/run.sh runs each); quickstart.c is the README's, built by its test.
EXAMPLES := $(addprefix $(B)/example_,voxelize octree render ambient_occlusion gl_cone_trace own_mesh)

.PHONY: all deps test tsan mutate fuzz fuzz-build fuzz-deps fuzz-regress fuzz-seeds demo bench bench-anchors clean $(addprefix opt-level-,$(OPT_LEVELS))
all: deps $(B)/voxgi $(EXAMPLES) $(VIEWER)

# Installs missing system packages (headless GL) with apt-get; silent when all is there.
deps:
	@bash tools/deps.sh

$(B) $(B)/asan $(B)/tsan:
	@mkdir -p $@

$(B)/embed_shaders: tools/embed_shaders.c | $(B)
	$(CC) -O2 $(WARN) -o $@ $<

# shaders.h is generated from shaders/*.glsl, never edited; it is committed so that
# voxgi.h + shaders.h work without this Makefile (a test fails when the committed copy is stale).
shaders.h: $(GLSL) $(B)/embed_shaders
	$(B)/embed_shaders $@ $(GLSL)

# The implementation, compiled once per configuration; the tool and the tests link it.
$(B)/voxgi_impl.o: tools/voxgi_impl.c voxgi.h voxgi_io.h shaders.h | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -c -o $@ $<
$(B)/asan/voxgi_impl.o: tools/voxgi_impl.c voxgi.h voxgi_io.h shaders.h | $(B)/asan
	$(CC) -std=c99 $(ASAN) $(WARN) -c -o $@ $<
$(B)/tsan/voxgi_impl.o: tools/voxgi_impl.c voxgi.h voxgi_io.h shaders.h | $(B)/tsan
	$(CC) -std=c99 $(TSAN) $(WARN) -c -o $@ $<

$(B)/voxgi: $(TOOL_SRC) $(TOOL_H) voxgi_io.h $(B)/voxgi_impl.o | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ $(TOOL_SRC) $(B)/voxgi_impl.o $(LDLIBS)

# voxelize.c and own_mesh.c are whole programs (they define VOXGI_IMPLEMENTATION, as one file of a
# project does; own_mesh.c, the README's "your own mesh", also VOXGI_IO_IMPLEMENTATION); the other
# examples link the implementation object (with voxgi_io.h's loaders), and gl_cone_trace.c libEGL,
# with which it makes its own GL context (libegl-dev: tools/deps.sh).
$(B)/example_voxelize: examples/voxelize.c voxgi.h shaders.h | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ $< $(LDLIBS)
$(B)/example_own_mesh: examples/own_mesh.c voxgi.h voxgi_io.h | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -DVOXGI_NO_GL -o $@ $< $(LDLIBS)
$(B)/example_octree $(B)/example_ambient_occlusion: $(B)/example_%: examples/%.c voxgi.h $(B)/voxgi_impl.o | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ $< $(B)/voxgi_impl.o $(LDLIBS)
$(B)/example_render: examples/render.c voxgi.h voxgi_io.h tools/image_io.h $(B)/voxgi_impl.o | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ $< $(B)/voxgi_impl.o $(LDLIBS)
$(B)/example_gl_cone_trace: examples/gl_cone_trace.c voxgi.h tools/image_io.h $(B)/voxgi_impl.o | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ $< $(B)/voxgi_impl.o $(LDLIBS) -lEGL

# The viewer (examples/viewer.c, a GLFW window) only where GLFW's header is (libglfw3-dev:
# tools/deps.sh); `make all` says when it is left out. GLFW and VIEWER are looked up when used, so
# `make test`, whose recipe runs after deps.sh, finds a header that deps.sh has just installed
# (`make all` reads its prerequisites first: there the next run builds the viewer).
# GLFW_LIBS: pkg-config's, else -lglfw.
GLFW     = $(shell $(CC) $$(pkg-config --cflags glfw3 2>/dev/null) -E -x c -include GLFW/glfw3.h /dev/null >/dev/null 2>&1 && echo yes)
GLFW_LIBS := $(or $(shell pkg-config --libs glfw3 2>/dev/null),-lglfw)
VIEWER   = $(if $(GLFW),$(B)/example_viewer,viewer-missing)
$(B)/example_viewer: examples/viewer.c voxgi.h voxgi_io.h tools/image_io.h $(B)/voxgi_impl.o | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) $$(pkg-config --cflags glfw3 2>/dev/null) -o $@ $< $(B)/voxgi_impl.o $(GLFW_LIBS) $(LDLIBS)
.PHONY: viewer-missing
viewer-missing:
	@echo "make: examples/viewer.c not built: GLFW's header (GLFW/glfw3.h) is missing; bash tools/deps.sh installs libglfw3-dev"

TEST_H  := $(wildcard tests/*.h) $(TOOL_H)

$(addprefix $(B)/,$(LINKED_TESTS)): $(B)/%: tests/%.c voxgi.h voxgi_io.h $(TEST_H) $(B)/voxgi_impl.o | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ $< $(B)/voxgi_impl.o $(LDLIBS)
$(addprefix $(B)/asan/,$(LINKED_TESTS)): $(B)/asan/%: tests/%.c voxgi.h voxgi_io.h $(TEST_H) $(B)/asan/voxgi_impl.o | $(B)/asan
	$(CC) -std=c99 $(ASAN) $(WARN) -o $@ $< $(B)/asan/voxgi_impl.o $(LDLIBS)

# The rest are whole programs: test_internals with the implementation inside,
# test_headless_gl with tools/embed_shaders.c inside.
$(B)/test_%: tests/test_%.c voxgi.h $(TEST_H) shaders.h tools/embed_shaders.c | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ $< $(LDLIBS)
$(B)/asan/test_%: tests/test_%.c voxgi.h $(TEST_H) shaders.h tools/embed_shaders.c | $(B)/asan
	$(CC) -std=c99 $(ASAN) $(WARN) -o $@ $< $(LDLIBS)

# The ray core without SIMD (VOXGI_NO_SIMD): its scalar code held to the same tests.
$(B)/test_rays_scalar: tests/test_rays.c tools/voxgi_impl.c voxgi.h $(TEST_H) shaders.h | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -DVOXGI_NO_SIMD -o $@ tests/test_rays.c tools/voxgi_impl.c $(LDLIBS)

# The ray core with AVX2 (eight-wide nodes), where the compiler can target it; tests/run.sh runs it
# where the CPU has AVX2.
AVX2_CC := $(shell echo 'int main(void) { return 0; }' | $(CC) -mavx2 -mfma -x c - -o /dev/null 2>/dev/null && echo yes)
$(B)/test_rays_avx2: tests/test_rays.c tools/voxgi_impl.c voxgi.h $(TEST_H) shaders.h | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -mavx2 -mfma -o $@ tests/test_rays.c tools/voxgi_impl.c $(LDLIBS)

$(B)/asan/voxgi: $(TOOL_SRC) $(TOOL_H) voxgi_io.h $(B)/asan/voxgi_impl.o | $(B)/asan
	$(CC) -std=c99 $(ASAN) $(WARN) -o $@ $(TOOL_SRC) $(B)/asan/voxgi_impl.o $(LDLIBS)

# Two contexts on two threads at once under ThreadSanitizer (CI runs it in make test; make tsan alone).
$(B)/tsan/test_threads: tests/test_threads.c voxgi.h $(TEST_H) $(B)/tsan/voxgi_impl.o | $(B)/tsan
	$(CC) -std=c99 $(TSAN) $(WARN) -o $@ $< $(B)/tsan/voxgi_impl.o $(LDLIBS)
tsan: deps $(B)/tsan/test_threads
	TSAN_OPTIONS=suppressions=$(CURDIR)/tests/tsan.supp $(B)/tsan/test_threads

# Leaks on purpose: tests/run.sh checks that the leak checks report it.
$(B)/asan/leak_canary: tests/leak_canary.c voxgi.h tools/headless_gl.h $(B)/asan/voxgi_impl.o | $(B)/asan
	$(CC) -std=c99 $(ASAN) $(WARN) -o $@ $< $(B)/asan/voxgi_impl.o $(LDLIBS)

# Builds everything the tests run, in parallel (one job per processor unless make was given -j),
# then runs them (tests/run.sh, in parallel too).
TEST_BUILD := $(B)/embed_shaders $(B)/voxgi $(B)/asan/voxgi $(EXAMPLES) $(addprefix $(B)/,$(TESTS)) $(B)/test_rays_scalar \
              $(if $(AVX2_CC),$(B)/test_rays_avx2) \
              $(addprefix $(B)/asan/,$(TESTS)) $(B)/asan/leak_canary
# CI (VOXGI_CI=1) also builds the tool and the test programs at -O0 and -O3 (the main build is
# -O2), in $(B)/O<level>, and tests/run.sh runs them: no test may depend on the optimiser's mood;
# and test_threads under ThreadSanitizer.
OPT_LEVELS := 0 3
test: deps
	@$(MAKE) --no-print-directory $(if $(filter -j%,$(MAKEFLAGS)),,-j$(NPROC)) $(TEST_BUILD) $(VIEWER) \
	    $(if $(filter 1,$(VOXGI_CI)),$(addprefix opt-level-,$(OPT_LEVELS)) $(B)/tsan/test_threads)
	@VOXGI_BUILD=$(B) bash tests/run.sh

opt-level-%:
	@$(MAKE) --no-print-directory B=$(B)/O$* CFLAGS="-O$* -g" $(addprefix $(B)/O$*/,voxgi $(TESTS))

# Plants each bug of tests/mutations.txt in a copy of the sources and runs the tests that must
# notice it; prints the survivors (minutes, not part of `make test`). MUTATE_ARGS: e.g. --only ID.
mutate: deps
	@bash tests/mutate.sh $(MUTATE_ARGS)

# libFuzzer harnesses (fuzz/, docs/fuzzing.md), built by clang under ASan and UBSan without GL:
# `make fuzz` installs clang (tools/deps.sh fuzz), builds them and fuzzes each FUZZ_S seconds in
# turn, then prints a table of executions and findings; any finding fails it. `make fuzz-regress`
# runs each harness once over its seeds and fuzz/regressions/ (seconds, no fuzzing).
FUZZ_CC    ?= clang
FUZZ_S     ?= 60
FUZZERS    := obj mtl off stl ply gltf glb binvox pfm svo api
FUZZ_FLAGS := -std=c99 -g -O1 -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer \
              -Wall -Wextra -pedantic -Werror -DVOXGI_NO_GL
FUZZ_BINS  := $(addprefix $(B)/fuzz/fuzz_,$(FUZZERS))

fuzz-deps:
	@bash tools/deps.sh fuzz

$(B)/fuzz:
	@mkdir -p $@

$(B)/fuzz/voxgi_impl.o: tools/voxgi_impl.c voxgi.h voxgi_io.h | $(B)/fuzz
	$(FUZZ_CC) $(FUZZ_FLAGS) -fsanitize=fuzzer-no-link -c -o $@ $<
$(FUZZ_BINS): $(B)/fuzz/fuzz_%: fuzz/fuzz_%.c $(wildcard fuzz/*.h) tools/image_io.h voxgi.h voxgi_io.h $(B)/fuzz/voxgi_impl.o
	$(FUZZ_CC) $(FUZZ_FLAGS) -fsanitize=fuzzer -o $@ $< $(B)/fuzz/voxgi_impl.o -lm -lpthread

# The binary seeds of fuzz/corpus/ (committed; rerun when a seed's format or fuzz_api.c's decoding changes).
$(B)/make_seeds: fuzz/make_seeds.c voxgi.h $(B)/voxgi_impl.o | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ $< $(B)/voxgi_impl.o $(LDLIBS)
fuzz-seeds: $(B)/make_seeds
	$(B)/make_seeds fuzz/corpus

fuzz-build: $(FUZZ_BINS)
fuzz: fuzz-deps
	@$(MAKE) --no-print-directory fuzz-build
	@bash fuzz/run.sh $(B)/fuzz $(FUZZ_S) $(FUZZERS)

fuzz-regress: fuzz-deps
	@$(MAKE) --no-print-directory fuzz-build
	@bash fuzz/run.sh --regress $(B)/fuzz $(FUZZERS)

demo: all
	$(B)/voxgi bench voxelize
	$(B)/voxgi svo builtin:sphere --res 256 --format float16
	$(B)/voxgi render cornell-box --spp 64 --bounces -1 -o $(B)/cornell-box.png
	$(B)/voxgi render cornell-box --method vct --res 128 --anisotropic --cones 32 --cone-stride 2 --size 128 128 --compare 256 -o $(B)/cornell-box-vct.png
	$(B)/voxgi render cornell-box --method vct --res 128 --octree --cones 32 --cone-stride 2 --size 128 128 --compare 256 -o $(B)/cornell-box-vct-octree.png

bench: all
	$(B)/voxgi bench voxelize --methods conservative,thin,geometry,solid,solid-vote,solid-flood,slicemap,slicemap-atomic,atlas,atlas-compute,volume-buffer,volume-buffer-m1 --csv $(B)/bench.csv

# Optional: voxgi's CPU voxelizer against OpenVDB's meshToLevelSet (needs libopenvdb-dev).
bench-anchors: all
	bash bench/anchors.sh $(ANCHOR_ARGS)
	bash bench/anchors_rays.sh

clean:
	rm -rf $(B)
