# irrcache -- the only build entry.
#   make            libirrcache.a and libirrcache.so (CC=clang works too);
#                   PORT=posix|c11|none picks the port compiled in (default
#                   posix); `make PORT=none CC=arm-none-eabi-gcc lib` needs
#                   neither pthreads nor C11 threads
#   make demo       build the demo tracer and render the Cornell box
#   make test       every test; ends with "N passed, N failed"
#   make bench-core the core benchmark (CSV on stdout)
#   make bench-host the cache in a small path tracer, every sample
#   make cross      libirrcache.a for a Cortex-M4F (CROSS=arm-none-eabi-)
#   make embedded-test  that library's host run under QEMU (mps2-an386)
#   make size       code, data and stack per object and entry point
#   make fuzz       libFuzzer harnesses for FUZZ_SECONDS each (clang)
#   make fuzz-long  each harness to FUZZ_RUNS (10 M) or FUZZ_LONG_SECONDS (1 h)
#   make install    DESTDIR= PREFIX=/usr/local LIBDIR= INCLUDEDIR= (README
#                   "Install"); make uninstall removes what it put there

CC ?= cc
CXX ?= c++
AR ?= ar
# Where make install puts things (GNU names); DESTDIR stages them under
# another root for a package, the files still naming PREFIX.
PREFIX ?= /usr/local
LIBDIR ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
PKGCONFIGDIR ?= $(LIBDIR)/pkgconfig
CMAKEDIR ?= $(LIBDIR)/cmake/irrcache
DESTDIR ?=
BUILD ?= build
OPT ?= -O2 -g
# Warnings are errors in make test (and CI), not in a user's build: a new
# compiler's new warning should not stop someone embedding the library.
WERROR ?=
WARN = -Wall -Wextra -Wpedantic $(WERROR) -Wmissing-prototypes -Wshadow
PORT ?= posix
# Only the library's documented API leaves the shared library.  The
# library computes in float (double only in the index's cube arithmetic,
# explicitly), so a float promoted to double is an error; it never reads
# errno, so sqrtf may be the one instruction the FPU has.
CFLAGS_LIB = -std=c99 $(WARN) -Wdouble-promotion $(OPT) $(PIC) -fno-math-errno \
             -fvisibility=hidden -Iinclude $(CFLAGS)
PIC = $(if $(filter none,$(PORT)),,-fPIC)

SRC = src/status.c src/version.c \
      src/block/check.c src/block/octa.c src/block/slots.c src/block/torn.c \
      src/index/cells.c src/index/index.c src/index/query.c src/index/compact.c src/index/verify.c \
      src/store/lock.c src/store/stats.c src/store/trace.c src/store/store.c src/store/walk.c \
      src/store/confirm.c src/store/lookup.c \
      src/sample/grid.c src/sample/sampler.c src/sample/strata.c \
      src/irr/weight.c src/irr/kind_irr.c src/irr/irradiance.c src/irr/gradient.c src/irr/visibility.c \
      src/irr/hessian.c src/irr/detail.c src/irr/progressive.c \
      src/sh/kind_sh.c src/sh/sh.c src/sh/shgrad.c \
      src/api/kinds.c src/api/config.c src/api/life.c src/api/api_irr.c src/api/api_sh.c \
      src/api/occlusion.c src/api/pixel.c src/api/pass.c src/api/progress.c src/api/inspect.c \
      src/persist/snapshot.c src/persist/merge.c
# make LEAVE_OUT="SH VISIBILITY HESSIAN SIGHT SUPERSAMPLE GUARD" (any of them): those parts are
# not compiled, and util.h's IRC_NO_* switch tells the rest (the same
# switches, set in a user config header, compile those files empty).
LEAVE_OUT ?=
LEFT_SH = src/sh/kind_sh.c src/api/api_sh.c src/sh/sh.c src/sh/shgrad.c
LEFT_VISIBILITY = src/irr/visibility.c src/api/occlusion.c
LEFT_HESSIAN = src/irr/hessian.c
LEFT_SIGHT = src/store/confirm.c
LEFT_SUPERSAMPLE =
LEFT_GUARD =
SRC := $(filter-out $(foreach x,$(LEAVE_OUT),$(LEFT_$(x))),$(SRC) src/api/absent.c)
CFLAGS_LIB += $(foreach x,$(LEAVE_OUT),-DIRC_NO_$(x))
# The chosen port, and the single-threaded one (it needs nothing).
# port/unbuilt.c defines the other declared ports as ports that cannot
# make a lock, so that every port irrcache.h declares is defined.
PORT_SRC = $(sort port/$(PORT)/irc_port.c port/none/irc_port.c) port/irc_port_default.c port/unbuilt.c
PORT_BUILT_posix = -DIRC_BUILT_POSIX
PORT_BUILT_c11 = -DIRC_BUILT_C11
OBJ = $(SRC:%.c=$(BUILD)/%.o)
PORT_OBJ = $(PORT_SRC:%.c=$(BUILD)/%.o)
# The version: irrcache.h's macros, the one place it is defined.
version_part = $(shell sed -n 's/^\#define IRC_VERSION_$(1) \([0-9]*\)$$/\1/p' include/irrcache.h)
MAJOR := $(call version_part,MAJOR)
MINOR := $(call version_part,MINOR)
VERSION := $(MAJOR).$(MINOR).$(call version_part,PATCH)
LIBA = $(BUILD)/libirrcache.a
# libirrcache.so.X.Y.Z, soname libirrcache.so.X (libirrcache.so.0.Y while
# the major is 0: each minor is another ABI, irrcache.h), and the link the
# linker's -lirrcache finds.
SONAME = libirrcache.so.$(MAJOR)$(if $(filter 0,$(MAJOR)),.$(MINOR))
LIBSO_REAL = $(BUILD)/libirrcache.so.$(VERSION)
LIBSO = $(BUILD)/libirrcache.so
THREAD_LIBS = $(if $(filter posix,$(PORT)),-lpthread,)

all: $(LIBA) $(if $(filter none,$(PORT)),,$(LIBSO))
lib: $(LIBA)

# Objects depend on the flags they were compiled with: each stamp holds a
# command line and is rewritten only when it changes (make WERROR=-Werror,
# another OPT or CFLAGS rebuild what they change, and nothing else).
FLAGS_LIB = $(BUILD)/flags/lib
FLAGS_TEST = $(BUILD)/flags/test
$(FLAGS_LIB): FORCE
	@mkdir -p $(dir $@)
	@echo '$(CC) $(CFLAGS_LIB) $(PORT)' | cmp -s - $@ || echo '$(CC) $(CFLAGS_LIB) $(PORT)' > $@
$(FLAGS_TEST): FORCE
	@mkdir -p $(dir $@)
	@echo '$(CC) $(TEST_CFLAGS) $(OPT) $(CFLAGS)' | cmp -s - $@ || echo '$(CC) $(TEST_CFLAGS) $(OPT) $(CFLAGS)' > $@
FORCE:
.PHONY: FORCE

# Each object's headers as the compiler found them (-MMD: BUILD/src/X.d).
$(BUILD)/src/%.o: src/%.c include/irrcache.h $(FLAGS_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_LIB) -MMD -MP -c $< -o $@
-include $(OBJ:.o=.d)

# The default port is the chosen one; the object remembers which.
$(BUILD)/port/irc_port_default.o: port/irc_port_default.c include/irrcache.h Makefile $(FLAGS_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_LIB) -DIRC_PORT_DEFAULT=irc_port_$(PORT) -c $< -o $@

$(BUILD)/port/unbuilt.o: port/unbuilt.c include/irrcache.h Makefile $(FLAGS_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_LIB) $(PORT_BUILT_$(PORT)) -c $< -o $@

# Each port is compiled with the standard its platform needs.
$(BUILD)/port/posix/%.o: port/posix/%.c include/irrcache.h $(FLAGS_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_LIB) -D_POSIX_C_SOURCE=200809L -c $< -o $@
$(BUILD)/port/c11/%.o: port/c11/%.c include/irrcache.h $(FLAGS_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(subst -std=c99,-std=c11,$(CFLAGS_LIB)) -c $< -o $@
$(BUILD)/port/%.o: port/%.c include/irrcache.h $(FLAGS_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_LIB) -c $< -o $@

$(LIBA): $(OBJ) $(PORT_OBJ)
	rm -f $@
	$(AR) rcs $@ $^

$(LIBSO_REAL): $(OBJ) $(PORT_OBJ)
	$(CC) -shared -Wl,-soname,$(SONAME) -o $@ $^ -lm $(THREAD_LIBS)

$(LIBSO): $(LIBSO_REAL)
	ln -sf $(notdir $(LIBSO_REAL)) $(BUILD)/$(SONAME)
	ln -sf $(notdir $(LIBSO_REAL)) $@

# ---------------------------------------------------------------- tests
TEST_SRC = tests/main.c tests/harness.c tests/scenes.c tests/t_record.c tests/t_lookup.c tests/t_index.c \
           tests/t_index_shape.c tests/t_compact.c tests/t_api.c tests/t_bad_input.c tests/t_threads.c \
           tests/t_visibility.c tests/t_sight.c tests/t_attach.c tests/t_sh.c tests/t_shrec.c \
           tests/t_sh_lookup.c tests/t_hard.c tests/t_store.c tests/t_embed.c tests/t_hessian.c \
           tests/t_reach.c tests/t_snapshot.c tests/t_pass.c tests/t_share.c tests/t_kill.c tests/t_levels.c \
           tests/t_detail.c tests/t_detail_pixels.c tests/t_pixel_footprint.c tests/t_progress.c \
           tests/t_config.c tests/t_normals.c tests/kind_occ.c
# The tests exercise every threaded port; the library holds one of them.
TEST_PORTS = $(filter-out $(PORT),posix c11)
TEST_PORT_OBJ = $(TEST_PORTS:%=$(BUILD)/tests/port_%.o)

TEST_CFLAGS = -std=c99 $(WARN) -Wno-missing-prototypes -Iinclude -Isrc -Itests \
              -D_POSIX_C_SOURCE=200809L

$(BUILD)/tests/port_posix.o: port/posix/irc_port.c include/irrcache.h
	@mkdir -p $(dir $@)
	$(CC) $(subst -fvisibility=hidden,,$(CFLAGS_LIB)) -D_POSIX_C_SOURCE=200809L -c $< -o $@
$(BUILD)/tests/port_c11.o: port/c11/irc_port.c include/irrcache.h
	@mkdir -p $(dir $@)
	$(CC) $(subst -std=c99,-std=c11,$(CFLAGS_LIB)) -c $< -o $@

# A record kind of the tests' own (tests/kind_occ.c): the registry
# compiled again with it listed, linked before the library's.
TEST_KINDS = $(BUILD)/tests/kinds.o
$(BUILD)/tests/kinds.o: src/api/kinds.c src/base/kind.h include/irrcache.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_LIB) -DIRC_KIND_EXTRA=irc__kind_occ -c $< -o $@

# One object a test file, so that a change recompiles what it touches
# (-MMD: the headers it includes).
TEST_OBJ = $(TEST_SRC:tests/%.c=$(BUILD)/tests/obj/%.o)
$(BUILD)/tests/obj/%.o: tests/%.c include/irrcache.h $(FLAGS_TEST)
	@mkdir -p $(dir $@)
	$(CC) $(TEST_CFLAGS) $(OPT) $(CFLAGS) -MMD -MP -c $< -o $@
-include $(TEST_OBJ:.o=.d)
$(BUILD)/irc_tests: $(TEST_OBJ) $(LIBA) $(TEST_PORT_OBJ) $(TEST_KINDS)
	$(CC) $(OPT) $(CFLAGS) $(TEST_OBJ) $(TEST_PORT_OBJ) $(TEST_KINDS) $(LIBA) -o $@ -lm -lpthread

test:
	WERROR=-Werror sh tests/run.sh

# The maintainer's loop (TESTING.md, "Tiers"): the library and the tests
# built with -Werror (every object whose flags differ rebuilt), the core
# suite in its quickest mode, the documents, the suites' lists, module
# cycles, the one-file library (gcc, posix), in under a minute on an idle
# 2-core machine (the suite runs beside the other steps).  It prints what
# failed and a summary; the suite's measurements are in BUILD/check.log.
check:
	@start=$$(date +%s); \
	$(MAKE) -s WERROR=-Werror $(BUILD)/irc_tests > $(BUILD)/check-build.log 2>&1 || \
	    { cat $(BUILD)/check-build.log; exit 1; }; \
	IRC_TEST_QUICK=2 $(BUILD)/irc_tests > $(BUILD)/check.log 2>&1 & suite=$$!; rc=0; \
	for step in "sh tests/docs.sh" "sh tests/bench_vars.sh" "sh tests/listed.sh" \
	            "$(MAKE) -s WERROR=-Werror cycles" "AMALG_QUICK=1 sh tests/amalgamation.sh"; do \
	    out=$$(eval "$$step" 2>&1) || { echo "$$out"; rc=1; }; \
	done; \
	wait $$suite || rc=1; \
	grep -E '^FAIL|^  [^ ].*: CHECK' $(BUILD)/check.log; tail -1 $(BUILD)/check.log; \
	[ $$rc = 0 ] && echo "check: passed in $$(( $$(date +%s) - start )) s"

# The hand-kept lists, for tests/listed.sh to hold against the tree.
print-lists:
	@echo "SRC $(SRC)"
	@echo "TEST_SRC $(TEST_SRC)"

# No module of the library uses another that uses it back (tests/cycles.sh
# on the library's objects; DESIGN.md, "Layers").
LAYERS = top base block index store sample irr,sh api,persist
cycles: $(LIBA)
	sh tests/cycles.sh --self-test
	LAYERS="$(LAYERS)" sh tests/cycles.sh $(OBJ)
	sh tests/includes.sh --self-test
	LAYERS="$(LAYERS)" sh tests/includes.sh src
	sh tests/state.sh

# Line and branch coverage of src/ (gcov): the core suite and the fuzz
# corpora.  make test prints it too.
coverage:
	sh tests/coverage.sh

# ---------------------------------------------------------------- embedded
# The library for a Cortex-M4F (single-precision FPU) with the none port,
# and a host of the project's own run under QEMU's mps2-an386 board with
# semihosting (docs/PORTING.md, "Embedded").  embedded/need.sh installs the
# compiler, newlib and QEMU from Debian's packages when they are missing.
CROSS ?= arm-none-eabi-
M4_FLAGS = -mcpu=cortex-m4 -mfpu=fpv4-sp-d16 -mfloat-abi=hard -mthumb
M4_OPT = $(M4_FLAGS) -Os -ffunction-sections -fdata-sections
M4_BUILD = build-m4
QEMU_M4 = qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none \
          -semihosting-config enable=on,target=native -icount shift=0

cross:
	@sh embedded/need.sh
	$(MAKE) -s CC=$(CROSS)gcc AR=$(CROSS)ar PORT=none BUILD=$(M4_BUILD) OPT="$(M4_OPT)" lib

$(M4_BUILD)/host.elf: cross embedded/host.c embedded/board.c embedded/board.h embedded/mps2.ld
	$(CROSS)gcc -std=c99 $(WARN) $(M4_OPT) -Iinclude -Iembedded embedded/host.c \
	  embedded/board.c $(M4_BUILD)/libirrcache.a --specs=rdimon.specs -nostartfiles \
	  -T embedded/mps2.ld -Wl,--gc-sections -lm -o $@

embedded-test: $(M4_BUILD)/host.elf
	timeout 300 $(QEMU_M4) -kernel $(M4_BUILD)/host.elf

# Code, data and stack per object and entry point, x86-64 and Cortex-M4F;
# fails if the library can recurse (embedded/size.sh).
size:
	sh embedded/size.sh

# The same host on the build machine (no counter, no stack painting).
$(BUILD)/embedded_host: embedded/host.c embedded/board.c embedded/board.h $(LIBA)
	$(CC) -std=c99 $(WARN) $(OPT) -Iinclude -Iembedded embedded/host.c embedded/board.c \
	  $(LIBA) -o $@ -lm $(THREAD_LIBS)

embedded-host: $(BUILD)/embedded_host
	$(BUILD)/embedded_host

# ---------------------------------------------------------------- demo
# The demo tracer: every demo/*.c but the stand-alone program and the
# bench's Embree backend (built into the bench alone, where Embree is).
DEMO_LIB_SRC = $(filter-out demo/main.c demo/embree_rays.c,$(wildcard demo/*.c))
DEMO_CFLAGS = -std=c99 $(WARN) -Iinclude -Idemo $(OPT) $(CFLAGS)
# An archive, so that each program links the demo's parts it uses.
DEMO_OBJ = $(DEMO_LIB_SRC:demo/%.c=$(BUILD)/demo-lib/%.o)
DEMO_LIBA = $(BUILD)/libdemo.a
$(BUILD)/demo-lib/%.o: demo/%.c demo/*.h include/irrcache.h
	@mkdir -p $(dir $@)
	$(CC) $(DEMO_CFLAGS) -c $< -o $@
$(DEMO_LIBA): $(DEMO_OBJ)
	rm -f $@
	$(AR) rcs $@ $(DEMO_OBJ)
DEMO_OUT = $(BUILD)/demo
# The Cornell box at the same rays per shading point in both modes (16 x 64
# strata per record, 1024 rays per pixel for the reference); a second
# reference with another seed measures the reference's own noise.
DEMO_ARGS = --size 256x256 --strata 16x64 --exposure 4

$(BUILD)/irc_demo: demo/main.c $(DEMO_LIBA) demo/*.h $(LIBA)
	$(CC) $(DEMO_CFLAGS) demo/main.c $(DEMO_LIBA) $(LIBA) -o $@ -lm -lpthread

demo: $(BUILD)/irc_demo
	@mkdir -p $(DEMO_OUT)
	$(BUILD)/irc_demo demo/scenes/cornell.scene $(DEMO_ARGS) --reference 1024 --out $(DEMO_OUT)/cornell-reference
	$(BUILD)/irc_demo demo/scenes/cornell.scene $(DEMO_ARGS) --reference 1024 --seed 2 --compare $(DEMO_OUT)/cornell-reference.exr
	$(BUILD)/irc_demo demo/scenes/cornell.scene $(DEMO_ARGS) --cache --compare $(DEMO_OUT)/cornell-reference.exr --out $(DEMO_OUT)/cornell-cache

# The real scenes (the Dabrovic Sponza and the Stanford bunny,
# demo/README.md, "Scene files"): shipped gzip'd, read from build/scenes with their scene
# files and materials beside them.
REAL_SCENES = $(BUILD)/scenes/sponza.obj $(BUILD)/scenes/bunny.obj $(BUILD)/scenes/sponza.mtl \
              $(patsubst demo/scenes/%,$(BUILD)/scenes/%,$(wildcard demo/scenes/sponza-*.scene \
                 demo/scenes/breakfast-room-*.scene demo/scenes/grey-white-room-*.scene \
                 demo/scenes/country-kitchen-*.scene))
# The furnished interiors' models are not shipped (bench/notes.md, "The
# corpus"): where CORPUS holds them (NAME.obj.gz and NAME.mtl), they are
# copied in too; make bench skips their views otherwise.
CORPUS ?= ../shared/data/real-scenes
CORPUS_MODELS = $(foreach m,breakfast-room grey-white-room country-kitchen,$(if $(wildcard $(CORPUS)/$(m).obj.gz),\
                  $(BUILD)/scenes/$(m).obj $(BUILD)/scenes/$(m).mtl))
$(BUILD)/scenes/%.obj: demo/scenes/%.obj.gz
	@mkdir -p $(dir $@)
	gzip -dc $< > $@.part && mv $@.part $@
$(BUILD)/scenes/%: demo/scenes/%
	@mkdir -p $(dir $@)
	cp $< $@
$(BUILD)/scenes/%.obj: $(CORPUS)/%.obj.gz
	@mkdir -p $(dir $@)
	gzip -dc $< > $@.part && mv $@.part $@
$(BUILD)/scenes/%.mtl: $(CORPUS)/%.mtl
	@mkdir -p $(dir $@)
	cp $< $@
real-scenes: $(REAL_SCENES) $(CORPUS_MODELS)

# The first-order paper's Fig. 15 experiment (docs/DESIGN.md: "Visibility gradients").
$(BUILD)/fig15: experiments/fig15.c $(DEMO_LIBA) demo/*.h $(LIBA)
	$(CC) $(DEMO_CFLAGS) experiments/fig15.c $(DEMO_LIBA) $(LIBA) -o $@ -lm -lpthread

fig15: $(BUILD)/fig15
	$(BUILD)/fig15 demo/scenes/fig15.scene 200 16384 64 256
	$(BUILD)/fig15 demo/scenes/fig15-sharp.scene 200 16384 64 256

# The first-order paper's adaptive image sampling (experiments/README.md: "Adaptive
# image sampling"): three importance metrics at 10% and 17% of the pixels
# against the full render, on the Fig. 5 scene and the Cornell box (each
# with the gradient check); then the gradient's SV and CDV terms and their
# ratio as the light rises (Fig. 5-6).
# The experiments' own machinery (adaptive image sampling, the image
# gradient), linked only where used.
EXP_SAMPLING = experiments/sampling.c experiments/delaunay.c
EXP_IMGRAD = experiments/imgrad.c
$(BUILD)/adaptive: experiments/adaptive.c $(EXP_SAMPLING) $(EXP_IMGRAD) experiments/*.h $(DEMO_LIBA) demo/*.h $(LIBA)
	$(CC) $(DEMO_CFLAGS) -Iexperiments experiments/adaptive.c $(EXP_SAMPLING) $(EXP_IMGRAD) $(DEMO_LIBA) $(LIBA) -o $@ -lm -lpthread

$(BUILD)/terms: experiments/terms.c $(EXP_IMGRAD) experiments/imgrad.h $(DEMO_LIBA) demo/*.h $(LIBA)
	$(CC) $(DEMO_CFLAGS) -Iexperiments experiments/terms.c $(EXP_IMGRAD) $(DEMO_LIBA) $(LIBA) -o $@ -lm -lpthread

adaptive: $(BUILD)/adaptive $(BUILD)/terms
	$(BUILD)/adaptive demo/scenes/fig5.scene --check
	$(BUILD)/adaptive demo/scenes/fig5.scene --light-samples 128
	$(BUILD)/adaptive demo/scenes/cornell.scene --check
	for s in sh leak fig15 fig15-sharp; do $(BUILD)/adaptive demo/scenes/$$s.scene 256 192 --check-only; done
	$(BUILD)/terms demo/scenes/fig5.scene

# Glossy indirect light from SH records against sampling the lobe, by
# Phong exponent (experiments/README.md: "Glossy indirect light").
$(BUILD)/glossy: experiments/glossy.c $(DEMO_LIBA) demo/*.h $(LIBA)
	$(CC) $(DEMO_CFLAGS) experiments/glossy.c $(DEMO_LIBA) $(LIBA) -o $@ -lm -lpthread

glossy: $(BUILD)/glossy
	$(BUILD)/glossy demo/scenes/sh.scene object 128 128
	$(BUILD)/glossy demo/scenes/fig5.scene glossy 256 192
	$(BUILD)/glossy demo/scenes/cornell-glossy.scene glossy 128 128

# The SH-gradient paper's experiments (experiments/README.md).
SHOBJ = experiments/shobj.c experiments/shobj.h
$(BUILD)/shexp: experiments/shexp.c $(SHOBJ) $(DEMO_LIBA) demo/*.h $(LIBA)
	$(CC) $(DEMO_CFLAGS) experiments/shexp.c experiments/shobj.c $(DEMO_LIBA) $(LIBA) \
	      -o $@ -lm -lpthread

sh-experiments: $(BUILD)/shexp
	$(BUILD)/shexp demo/scenes/sh.scene 48 64 256

# The paper's setting animated: the object on a loop among the emitters,
# shaded per frame from 1 or 8 records with and without gradients against
# a record per pixel, with Eq. 16's exponent at the default 2 and at 8
# (experiments/README.md: "A moving object").  About 8 minutes.
$(BUILD)/shanim: experiments/shanim.c $(SHOBJ) $(DEMO_LIBA) demo/*.h $(LIBA)
	$(CC) $(DEMO_CFLAGS) experiments/shanim.c experiments/shobj.c $(DEMO_LIBA) $(LIBA) \
	      -o $@ -lm -lpthread

sh-animation: $(BUILD)/shanim
	mkdir -p $(BUILD)/sh-animation
	$(BUILD)/shanim --power 2 --out $(BUILD)/sh-animation/b2 demo/scenes/sh.scene
	$(BUILD)/shanim --power 8 --out $(BUILD)/sh-animation/b8 demo/scenes/sh.scene

# Small forms of the long documented targets, seconds each: make test runs
# them (stage 2b), so a change that breaks one fails there.  Their figures
# mean nothing at these sizes.
adaptive-small: $(BUILD)/adaptive
	$(BUILD)/adaptive demo/scenes/fig5.scene 64 48 --check
fig15-small: $(BUILD)/fig15
	$(BUILD)/fig15 demo/scenes/fig15.scene 20 256 8 32
glossy-small: $(BUILD)/glossy
	$(BUILD)/glossy demo/scenes/sh.scene object 16 16 --exponents 10
sh-experiments-small: $(BUILD)/shexp
	$(BUILD)/shexp demo/scenes/sh.scene 8 8 16
sh-animation-small: $(BUILD)/shanim
	$(BUILD)/shanim --frames 2 --size 32 --strata 8 16 --out $(BUILD)/sh-animation-small demo/scenes/sh.scene
bench-bounces-small: $(BUILD)/bench_run
	BENCH_SCENES=bounces2-cornell BENCH_A=0.4 $(BUILD)/bench_run quick
# make bench's fast backend: Embree installed (as root with apt; else the
# run says so and takes the demo's BVH), one small cache run on the Cornell
# box, its line of the library's own CPU printed and naming the backend.
bench-embree-small:
	@sh examples/need-embree.sh || echo "bench-embree-small: Embree not installed: the demo's BVH"
	@$(MAKE) -s $(BUILD)/bench_run
	BENCH_THREADS=1 BENCH_SCENES=cornell BENCH_SIZE=64x64 BENCH_METHODS=trans+rot BENCH_A=0.4 \
	  BENCH_NOISE=0 $(BUILD)/bench_run > $(BUILD)/bench-embree-small.log
	@cat $(BUILD)/bench-embree-small.log
	@want=$$([ -e /usr/include/embree3/rtcore.h ] && echo Embree || echo "the demo's BVH"); \
	  grep -q "library's own CPU (outside the callback) .*pass ends .*($$want)" \
	    $(BUILD)/bench-embree-small.log || { echo "bench-embree-small: no split line for $$want"; exit 1; }
# The cache in progressive path tracers (docs/DESIGN.md, "Progressive
# hosts"): bench/host.c's scene sample-major, and the Sponza atrium with
# the cache at the first hit and at the second vertex (PT_ARGS: width
# height samples reference_samples).
bench-progressive: real-scenes $(BUILD)/bench_progressive $(BUILD)/bench_pathtracer
	@sh examples/need-embree.sh || echo "bench-progressive: Embree not installed: the demo's BVH"
	@$(MAKE) -s $(BUILD)/bench_pathtracer
	sh bench/progressive.sh $(BUILD)/bench_progressive $(BUILD)/bench_pathtracer \
	   $(BUILD)/scenes/sponza-atrium.scene
bench-progressive-small:
	@$(MAKE) -s $(BUILD)/bench_progressive $(BUILD)/bench_pathtracer
	NO_PLOT=1 PROG_ARGS="32 24 16 64" PT_ARGS="24 24 16 64" sh bench/progressive.sh $(BUILD)/bench_progressive \
	  $(BUILD)/bench_pathtracer demo/scenes/cornell.scene > $(BUILD)/bench-progressive-small.log
	@cat $(BUILD)/bench-progressive-small.log
	@for m in pixel sample fixed second first; do grep -q "^$$m  *16 " $(BUILD)/bench-progressive-small.log || \
	  { echo "bench-progressive-small: no 16-sample row for $$m"; exit 1; }; done

SMALL_TARGETS = adaptive-small fig15-small glossy-small sh-experiments-small sh-animation-small bench-bounces-small \
                bench-embree-small bench-progressive-small
small-targets:
	@echo $(SMALL_TARGETS)

$(BUILD)/demo_tests: tests/t_demo.c tests/t_demo_render.c tests/t_bounce.c tests/harness.c tests/scenes.c $(EXP_IMGRAD) experiments/imgrad.h $(DEMO_LIBA) demo/*.h tests/*.h $(LIBA)
	$(CC) $(TEST_CFLAGS) -Idemo -Iexperiments $(OPT) $(CFLAGS) tests/t_demo.c tests/t_demo_render.c tests/t_bounce.c tests/harness.c tests/scenes.c $(EXP_IMGRAD) $(DEMO_LIBA) $(LIBA) -o $@ -lm -lpthread

$(BUILD)/adaptive_tests: tests/t_adaptive.c tests/harness.c tests/scenes.c $(EXP_SAMPLING) experiments/sampling.h tests/*.h $(LIBA)
	$(CC) $(TEST_CFLAGS) -Iexperiments $(OPT) $(CFLAGS) tests/t_adaptive.c tests/harness.c tests/scenes.c $(EXP_SAMPLING) $(LIBA) -o $@ -lm -lpthread

# The demo's own tests.  t_exr reads the demo's files with OpenEXR's C
# library (OpenEXRCore): a test-only dependency, found by pkg-config.
IMAGE_SRC = demo/image.c demo/png.c
LOADER_SRC = demo/loader.c demo/obj.c
EXR_CFLAGS = $(shell pkg-config --cflags OpenEXR)
EXR_LIBS = $(shell pkg-config --libs OpenEXR)

$(BUILD)/t_image: tests/t_image.c tests/harness.c tests/test.h $(IMAGE_SRC) demo/image.h demo/image_int.h
	$(CC) $(TEST_CFLAGS) -Idemo $(OPT) $(CFLAGS) tests/t_image.c tests/harness.c $(IMAGE_SRC) -o $@ -lm

$(BUILD)/t_loader: tests/t_loader.c tests/harness.c tests/test.h $(LOADER_SRC) demo/scene.h demo/loader_int.h
	$(CC) $(TEST_CFLAGS) -Idemo $(OPT) $(CFLAGS) tests/t_loader.c tests/harness.c $(LOADER_SRC) -o $@ -lm

$(BUILD)/t_exr: tests/t_exr.c tests/harness.c tests/test.h $(IMAGE_SRC) demo/image.h
	$(CC) $(TEST_CFLAGS) -Idemo $(EXR_CFLAGS) $(OPT) $(CFLAGS) tests/t_exr.c tests/harness.c $(IMAGE_SRC) -o $@ $(EXR_LIBS) -lm

# ---------------------------------------------------------------- amalgamation
# make amalgamation: build/amalgamation/irrcache.c (the library and the
# chosen port in one file) and irrcache.h beside it (pkg/amalgamate.sh).
AMALG = $(BUILD)/amalgamation
amalgamation: $(AMALG)/irrcache.c $(AMALG)/irrcache.h
$(AMALG)/irrcache.c: $(SRC) $(wildcard src/*.h src/*/*.h) $(PORT_SRC) pkg/amalgamate.sh include/irrcache.h
	@mkdir -p $(AMALG)
	sh pkg/amalgamate.sh $(PORT) $(VERSION) $@ $(SRC)
$(AMALG)/irrcache.h: include/irrcache.h
	@mkdir -p $(AMALG)
	cp include/irrcache.h $@

# ---------------------------------------------------------------- fuzz
# make fuzz FUZZ_SECONDS=N runs each harness under libFuzzer (clang) for N
# seconds, then merges what it found worth keeping into fuzz/corpus/NAME.
# make test replays the committed corpora without libFuzzer.
FUZZ_SECONDS ?= 60
FUZZ_TARGETS = api attach callback scene snapshot
FUZZ_SAN = -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all
# Sources each harness needs besides the library: the scene harness drives
# the demo's parsers.
FUZZ_EXTRA_api =
FUZZ_EXTRA_attach =
FUZZ_EXTRA_callback =
FUZZ_EXTRA_snapshot =
FUZZ_EXTRA_scene = demo/loader.c demo/obj.c demo/bvh.c
FUZZ_CORPORA = fuzz/corpus/api fuzz/corpus/attach fuzz/corpus/callback fuzz/corpus/scene fuzz/corpus/snapshot

$(BUILD)/replay_%: fuzz/fuzz_%.c fuzz/replay.c fuzz/fuzz_input.h demo/*.h $(LIBA)
	$(CC) -std=c99 $(WARN) -Iinclude -Ifuzz -Idemo $(OPT) $(CFLAGS) fuzz/fuzz_$*.c fuzz/replay.c \
	    $(FUZZ_EXTRA_$*) $(LIBA) -o $@ -lm -lpthread

# Every corpus through every harness: what one harness found may trouble
# another.
replay: $(foreach t,$(FUZZ_TARGETS),$(BUILD)/replay_$(t))
	for t in $(FUZZ_TARGETS); do $(BUILD)/replay_$$t $(FUZZ_CORPORA) || exit 1; done

fuzz:
	$(MAKE) -s CC=clang BUILD=build-fuzz OPT="$(FUZZ_SAN) -fsanitize=fuzzer-no-link" build-fuzz/libirrcache.a
	for t in $(FUZZ_TARGETS); do \
	    extra=""; [ $$t = scene ] && extra="$(FUZZ_EXTRA_scene)"; \
	    clang -std=c99 $(FUZZ_SAN) -fsanitize=fuzzer -Iinclude -Ifuzz -Idemo fuzz/fuzz_$$t.c \
	        $$extra build-fuzz/libirrcache.a -o build-fuzz/fuzz_$$t -lm -lpthread && \
	    mkdir -p build-fuzz/new-$$t fuzz/corpus/$$t && \
	    build-fuzz/fuzz_$$t -max_total_time=$(FUZZ_SECONDS) $(FUZZ_FLAGS) -print_final_stats=1 \
	        build-fuzz/new-$$t fuzz/corpus/$$t && \
	    build-fuzz/fuzz_$$t -merge=1 fuzz/corpus/$$t build-fuzz/new-$$t || exit 1; \
	done

# make fuzz-long: each harness until FUZZ_RUNS executions (default 10 M)
# or FUZZ_LONG_SECONDS (default an hour), whichever comes first.
FUZZ_RUNS ?= 10000000
FUZZ_LONG_SECONDS ?= 3600
fuzz-long:
	$(MAKE) fuzz FUZZ_SECONDS=$(FUZZ_LONG_SECONDS) FUZZ_FLAGS=-runs=$(FUZZ_RUNS)

# ---------------------------------------------------------------- bench
$(BUILD)/bench_core: bench/bench_core.c bench/bench_util.h tests/scenes.c tests/scenes.h $(DEMO_LIBA) demo/*.h $(LIBA)
	$(CC) $(TEST_CFLAGS) -Idemo -O2 -g $(CFLAGS) bench/bench_core.c tests/scenes.c $(DEMO_LIBA) $(LIBA) -o $@ -lm -lpthread

$(BUILD)/bench_lookups: bench/lookups.c bench/bench_util.h bench/box.h $(LIBA)
	$(CC) $(TEST_CFLAGS) -O2 -g $(CFLAGS) bench/lookups.c $(LIBA) -o $@ -lm

$(BUILD)/bench_anchor: bench/anchor.c bench/bench_util.h bench/box.h $(LIBA)
	$(CC) $(TEST_CFLAGS) -O2 -g $(CFLAGS) bench/anchor.c $(LIBA) -o $@ -lm

$(BUILD)/bench_records: bench/records.c bench/bench_util.h $(LIBA)
	$(CC) $(TEST_CFLAGS) -O2 -g $(CFLAGS) bench/records.c $(LIBA) -o $@ -lm

# make fingerprint: a hash a config of records, lookups, snapshots and
# counters (tests/fingerprint.c); a refactor prints the same lines before
# and after.
$(BUILD)/fingerprint: tests/fingerprint.c tests/scenes.c tests/scenes.h $(LIBA)
	$(CC) $(TEST_CFLAGS) $(OPT) $(CFLAGS) tests/fingerprint.c tests/scenes.c $(LIBA) -o $@ -lm -lpthread

fingerprint: $(BUILD)/fingerprint
	$(BUILD)/fingerprint

# ---------------------------------------------------------------- examples
$(BUILD)/minimal: examples/minimal.c $(LIBA)
	$(CC) -std=c99 $(WARN) -Iinclude $(OPT) examples/minimal.c $(LIBA) -o $@ -lm $(THREAD_LIBS)
$(BUILD)/threads: examples/threads.c $(LIBA)
	$(CC) -std=c99 $(WARN) -D_POSIX_C_SOURCE=200809L -Iinclude $(OPT) examples/threads.c $(LIBA) -o $@ -lm -lpthread
$(BUILD)/levels: examples/levels.c $(LIBA)
	$(CC) -std=c99 $(WARN) -D_POSIX_C_SOURCE=200809L -Iinclude $(OPT) examples/levels.c $(LIBA) -o $@ -lm -lpthread
$(BUILD)/passes: examples/passes.c $(LIBA)
	$(CC) -std=c99 $(WARN) -D_POSIX_C_SOURCE=200809L -Iinclude $(OPT) examples/passes.c $(LIBA) -o $@ -lm -lpthread
$(BUILD)/minimal_cpp: examples/minimal.cpp $(LIBA)
	$(CXX) -std=c++11 -Wall -Wextra $(WERROR) -pedantic -Iinclude $(OPT) examples/minimal.cpp $(LIBA) \
	       -o $@ -lm $(THREAD_LIBS)
examples: $(BUILD)/minimal $(BUILD)/threads $(BUILD)/levels $(BUILD)/passes $(BUILD)/minimal_cpp

# irrcache in an Embree 3 tracer on the Sponza atrium (bench/notes.md, "On real
# geometry"): installs libembree-dev from Debian's packages when missing;
# neither the library nor make test needs Embree.
$(BUILD)/embree: examples/embree.c $(LOADER_SRC) demo/scene.h $(LIBA)
	$(CC) -std=c99 $(WARN) -Iinclude -Idemo $(OPT) examples/embree.c $(LOADER_SRC) $(LIBA) \
	      -o $@ -lembree3 -lm -lpthread
embree-example: real-scenes
	@sh examples/need-embree.sh
	$(MAKE) -s $(BUILD)/embree
	$(BUILD)/embree $(BUILD)/scenes/sponza-atrium.scene 320 240

bench-core: $(BUILD)/bench_core
	$(BUILD)/bench_core

# The cache in a small path tracer of its own, called at every sample of
# every pixel (bench/notes.md, "In a path tracer's hands"); BEFORE=<commit>
# also runs the same host against that commit's library.
$(BUILD)/bench_host: bench/host.c bench/host_scene.h bench/bench_util.h $(LIBA)
	$(CC) -std=c99 $(WARN) -Iinclude -Ibench $(OPT) bench/host.c $(LIBA) -o $@ -lm $(THREAD_LIBS)
bench-host: $(BUILD)/bench_host $(BUILD)/bench_progressive
	sh bench/host.sh $(BUILD)/bench_host $(BEFORE)
	$(BUILD)/bench_progressive $(PROG_ARGS)
$(BUILD)/bench_progressive: bench/progressive.c bench/host_scene.h bench/bench_util.h $(LIBA)
	$(CC) -std=c99 $(WARN) -Iinclude -Ibench $(OPT) bench/progressive.c $(LIBA) -o $@ -lm $(THREAD_LIBS)

# One lookup workload for profilers (bench/notes.md: "Where the lookup time goes"):
# rates, entries scanned and passed, and a checksum of the answers.
# The lookup anchor (bench/notes.md, "The lookup anchor"): instructions a
# lookup of irrcache and of a pbrt-v2-style octree on the same records.
bench-anchor: $(BUILD)/bench_anchor
	sh bench/anchor.sh $(BUILD)/bench_anchor 100000 $(BUILD)/bench/anchor.csv

bench-lookups: $(BUILD)/bench_lookups
	for o in scanline random; do for n in 100000 1000000; do for f in "" pass; do \
	  $(BUILD)/bench_lookups $$o 200000 $$n $$f count || exit 1; done; done; done

# One record workload for profilers (bench/notes.md: "Speed and memory"): time a
# record and a checksum of the records, per feature set.
bench-records: $(BUILD)/bench_records
	for f in bare both sh shgrad; do $(BUILD)/bench_records $$f 2000 || exit 1; done

# Speed against error on every shipped scene (bench/notes.md: "Speed against
# error").  BENCH_QUICK=1: small images, one real view, fewer runs (32 s).
BENCH_RUN_SRC = bench/bench.c bench/report.c bench/bounces.c bench/select.c
# Its rays come from Embree where Embree is installed (make bench installs
# libembree-dev as root; BENCH_RAYS=bvh picks the demo's BVH at run time),
# else from the demo's BVH; the stamp rebuilds it when that changes.
EMBREE_H = $(wildcard /usr/include/embree3/rtcore.h)
BENCH_RAYS_BUILD = $(if $(EMBREE_H),embree,bvh)
$(BUILD)/rays-%.stamp:
	@mkdir -p $(BUILD) && rm -f $(BUILD)/rays-*.stamp && touch $@
$(BUILD)/bench_run: $(BENCH_RUN_SRC) bench/bench.h $(DEMO_LIBA) demo/*.h demo/embree_rays.c $(LIBA) \
                    $(BUILD)/rays-$(BENCH_RAYS_BUILD).stamp
	$(CC) $(DEMO_CFLAGS) $(if $(EMBREE_H),-DBENCH_EMBREE demo/embree_rays.c) $(BENCH_RUN_SRC) \
	      $(DEMO_LIBA) $(LIBA) -o $@ -lm -lpthread $(if $(EMBREE_H),-lembree3)

$(BUILD)/bench_pathtracer: bench/pathtracer.c bench/bench_util.h $(DEMO_LIBA) demo/*.h demo/embree_rays.c \
                           $(LIBA) $(BUILD)/rays-$(BENCH_RAYS_BUILD).stamp
	$(CC) $(DEMO_CFLAGS) -Ibench $(if $(EMBREE_H),-DBENCH_EMBREE demo/embree_rays.c) bench/pathtracer.c \
	      $(DEMO_LIBA) $(LIBA) -o $@ -lm -lpthread $(if $(EMBREE_H),-lembree3)

bench: real-scenes
	@sh examples/need-embree.sh || echo "bench: Embree not installed: rays from the demo's BVH"
	$(MAKE) -s $(BUILD)/bench_run $(BUILD)/glossy
	sh bench/bench.sh $(BUILD)/bench_run

# Several bounces (bench/notes.md, "Several bounces"): path tracing, the
# cache at the first level with path-traced gathers, a cache at every level,
# on the Cornell box at 2 and 3 bounces and the Sponza atrium at 2.
BOUNCE_SCENES ?= bounces3-cornell,bounces2-cornell,bounces2-sponza-atrium
bench-bounces: $(BUILD)/bench_run real-scenes
	BENCH_SCENES=$(BOUNCE_SCENES) $(BUILD)/bench_run

# The Cornell box on a Slurm job array of 4 tile jobs, merged by a fifth
# (farm/README.md); starts a single-node Slurm of its own as root.
farm-demo: $(BUILD)/irc_demo
	sh farm/farm-demo.sh 4

# What deterministic fill passes cost over free-running fills (bench/README.md:
# "Deterministic fills"); about two minutes.
$(BUILD)/bench_fill: bench/fill.c $(DEMO_LIBA) demo/*.h $(LIBA)
	$(CC) $(DEMO_CFLAGS) bench/fill.c $(DEMO_LIBA) $(LIBA) -o $@ -lm -lpthread

bench-fill: $(BUILD)/bench_fill
	$(BUILD)/bench_fill

# make install [DESTDIR=stage] [PREFIX=/usr/local] [LIBDIR=...] [INCLUDEDIR=...]
# puts the header, both libraries (the shared one as libirrcache.so.X.Y.Z
# with its soname link and development link), irrcache.pc and the CMake
# package (written for these variables by pkg/pc.sh and pkg/cmake.sh, no
# CMake needed); make uninstall, with the same variables, removes exactly
# those.
INSTALLED = $(INCLUDEDIR)/irrcache.h $(LIBDIR)/libirrcache.a $(PKGCONFIGDIR)/irrcache.pc \
            $(CMAKEDIR)/irrcacheConfig.cmake $(CMAKEDIR)/irrcacheConfigVersion.cmake \
            $(if $(filter none,$(PORT)),,$(LIBDIR)/libirrcache.so.$(VERSION) \
                                          $(LIBDIR)/$(SONAME) $(LIBDIR)/libirrcache.so)
install: all
	install -d $(DESTDIR)$(INCLUDEDIR) $(DESTDIR)$(LIBDIR) $(DESTDIR)$(PKGCONFIGDIR) \
	           $(DESTDIR)$(CMAKEDIR)
	install -m 644 include/irrcache.h $(DESTDIR)$(INCLUDEDIR)/
	install -m 644 $(LIBA) $(DESTDIR)$(LIBDIR)/
	sh pkg/pc.sh '$(PREFIX)' '$(LIBDIR)' '$(INCLUDEDIR)' '$(VERSION)' '-lm $(THREAD_LIBS)' \
	   > $(DESTDIR)$(PKGCONFIGDIR)/irrcache.pc
	sh pkg/cmake.sh '$(CMAKEDIR)' '$(LIBDIR)' '$(INCLUDEDIR)' '$(VERSION)' \
	   '$(if $(filter none,$(PORT)),,libirrcache.so.$(VERSION))' '$(SONAME)' \
	   '$(if $(filter posix,$(PORT)),Threads::Threads,)' \
	   "$$(echo __SIZEOF_POINTER__ | $(CC) -E -P - | tail -n 1)" $(DESTDIR)$(CMAKEDIR)
	chmod 644 $(DESTDIR)$(PKGCONFIGDIR)/irrcache.pc $(DESTDIR)$(CMAKEDIR)/irrcache*.cmake
	$(if $(filter none,$(PORT)),,install -m 755 $(LIBSO_REAL) $(DESTDIR)$(LIBDIR)/)
	$(if $(filter none,$(PORT)),,ln -sf libirrcache.so.$(VERSION) $(DESTDIR)$(LIBDIR)/$(SONAME))
	$(if $(filter none,$(PORT)),,ln -sf $(SONAME) $(DESTDIR)$(LIBDIR)/libirrcache.so)

uninstall:
	rm -f $(addprefix $(DESTDIR),$(INSTALLED))
	rmdir $(DESTDIR)$(CMAKEDIR) 2>/dev/null || true

clean:
	rm -rf build build-*

.PHONY: print-lists small-targets bench-embree-small bench-progressive bench-progressive-small adaptive-small fig15-small glossy-small sh-experiments-small sh-animation-small bench-bounces-small cycles fingerprint amalgamation embree-example all lib cross embedded-test embedded-host size examples test check coverage demo real-scenes fig15 adaptive glossy sh-experiments sh-animation fuzz fuzz-long replay bench-core bench-host bench-anchor bench-lookups bench-records bench bench-bounces bench-fill farm-demo install uninstall clean

# Which records answer the worst pixels of a Sponza render, and why
# (bench/notes.md, "On real geometry"); needs make bench's cached references.
$(BUILD)/outliers: experiments/outliers.c $(DEMO_LIBA) demo/*.h $(LIBA)
	$(CC) $(DEMO_CFLAGS) experiments/outliers.c $(DEMO_LIBA) $(LIBA) -o $@ -lm -lpthread

# How many pixels the records serve (bench/notes.md: "Where the records go").
$(BUILD)/reach: experiments/reach.c $(DEMO_LIBA) demo/*.h $(LIBA)
	$(CC) $(DEMO_CFLAGS) experiments/reach.c $(DEMO_LIBA) $(LIBA) -o $@ -lm -lpthread
$(BUILD)/probes: experiments/probes.c $(DEMO_LIBA) demo/*.h $(LIBA)
	$(CC) $(DEMO_CFLAGS) experiments/probes.c $(DEMO_LIBA) $(LIBA) -o $@ -lm -lpthread
