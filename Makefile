# SPDX-License-Identifier: MIT
# rad — one entry point: make, make test, make check, make port-test, make bench, make install
#
# Layout of the build (all under $(BUILDDIR)):
#   lib/fixed/*.o  -> librad.a        the product: fixed point, no malloc/libm/stdio
#   lib/float/*.o  -> librad_float.a  the float twin: same sources, -DRAD_FLOAT=1
#   tools/...      -> libradtools.a   host helpers: tools/formats (file formats),
#                                     tools/host (the glue over the core), tools/reference
#                                     (analytic references), tools/bench/plot.c
#   rad_cli, rad_cli_float, rad_bench the programs of tools/cli and tools/bench
#   tests/test_*   one CMocka runner per tests/test_*.c, linked with everything above
#
# WERROR=-Werror (CI and make check set it) turns warnings into errors; a user's newer
# compiler may warn where ours does not, so the default build does not stop on them.

# Cross builds of the library: make lib CROSS_COMPILE=arm-none-eabi- TARGET_FLAGS="-mcpu=...":
# CC and AR from CROSS_COMPILE, objects under build/arm-none-eabi (ports/README.md).
CROSS_COMPILE ?=
TARGET_FLAGS  ?=
ifneq ($(CROSS_COMPILE),)
CC       := $(CROSS_COMPILE)gcc
AR       := $(CROSS_COMPILE)ar
BUILDDIR ?= build/$(CROSS_COMPILE:%-=%)
endif
BUILDDIR ?= build
CC       ?= cc
AR       ?= ar
PREFIX   ?= /usr/local
WERROR   ?=
WARN     := -std=c99 -Wall -Wextra -pedantic -Wshadow -Wundef -Wmissing-prototypes $(WERROR)
OPT      ?= -O2 -g
CFLAGS_EXTRA ?=
# The core must not call memset/memcpy behind our back: no loop-to-libcall rewriting.
LIBFLAGS := -ffreestanding -fno-tree-loop-distribute-patterns
CPPFLAGS := -Iinclude
ALLCFLAGS = $(WARN) $(OPT) $(CFLAGS_EXTRA) $(CPPFLAGS)
TOOLFLAGS := -D_POSIX_C_SOURCE=200809L -Itools

PNG_CFLAGS := $(shell pkg-config --cflags libpng 2>/dev/null)
PNG_LIBS   := $(shell pkg-config --libs libpng 2>/dev/null || echo -lpng)
# stb_image (Debian libstb-dev) for textures: the system's library, see tools/formats/texture.c.
STB_LIBS   := $(shell pkg-config --libs stb 2>/dev/null || echo -lstb)
CMOCKA_LIBS := -lcmocka
# assimp (Debian libassimp-dev) reads the scene formats other than OBJ when pkg-config
# finds it; without it rad_cli reads .obj alone and says how to get the others.
ASSIMP_CFLAGS := $(shell pkg-config --exists assimp 2>/dev/null && echo -DRAD_HAVE_ASSIMP $$(pkg-config --cflags assimp))
ASSIMP_LIBS   := $(shell pkg-config --exists assimp 2>/dev/null && pkg-config --libs assimp)

LIB_SRCS   := $(wildcard lib/*.c)
LIB_HDRS   := $(wildcard lib/*.h include/rad/*.h)
# Host glue built once per build of the core (fixed: sc_*, float: scf_*).
TWIN_SRCS  := tools/host/scene.c tools/host/scene_rows.c tools/host/scene_relight.c \
              tools/host/scene_gather.c tools/host/parallel.c tools/bake/gltf_export.c \
              tools/host/tex_render.c tools/host/ply_export.c tools/host/fgather.c
# Host helpers built once.
TOOL_SRCS  := $(wildcard tools/formats/*.c tools/reference/*.c) \
              $(filter-out $(TWIN_SRCS),$(wildcard tools/bake/*.c)) tools/host/polys.c \
              tools/host/geom.c tools/host/clock.c tools/host/sky_map.c tools/bench/plot.c tools/bench/level.c
TOOL_HDRS  := $(wildcard tools/*/*.h)
TEST_SRCS  := $(wildcard tests/test_*.c)
TEST_HDRS  := $(wildcard tests/*.h)

FIXED_OBJS := $(LIB_SRCS:lib/%.c=$(BUILDDIR)/lib/fixed/%.o)
FLOAT_OBJS := $(LIB_SRCS:lib/%.c=$(BUILDDIR)/lib/float/%.o)
TOOL_OBJS  := $(TOOL_SRCS:tools/%.c=$(BUILDDIR)/tools/%.o)
TWIN_FIXED := $(TWIN_SRCS:tools/%.c=$(BUILDDIR)/tools/%.o)
TWIN_FLOAT := $(TWIN_SRCS:tools/%.c=$(BUILDDIR)/tools/float/%.o)
LIBRAD     := $(BUILDDIR)/librad.a
LIBRADF    := $(BUILDDIR)/librad_float.a
LIBTOOLS   := $(BUILDDIR)/libradtools.a
RAD_BUILD_H := $(BUILDDIR)/include/rad/rad_build.h
TESTS      := $(TEST_SRCS:tests/%.c=$(BUILDDIR)/tests/%)

.PHONY: all lib test check ports port-test port-bench port-size bench bench-level bench-curve install install-lib uninstall clean nm-check example readme-image
all: lib $(BUILDDIR)/rad_cli $(BUILDDIR)/rad_cli_float
# The library alone: no libpng, no CMocka, no host tools.
lib: $(LIBRAD) $(LIBRADF) $(RAD_BUILD_H)

$(BUILDDIR)/lib/fixed/%.o: lib/%.c $(LIB_HDRS)
	@mkdir -p $(@D)
	$(CC) $(ALLCFLAGS) $(LIBFLAGS) $(TARGET_FLAGS) -c $< -o $@
$(BUILDDIR)/lib/float/%.o: lib/%.c $(LIB_HDRS)
	@mkdir -p $(@D)
	$(CC) $(ALLCFLAGS) $(LIBFLAGS) $(TARGET_FLAGS) -DRAD_FLOAT=1 -c $< -o $@
$(LIBRAD): $(FIXED_OBJS)
	@rm -f $@; $(AR) rcs $@ $^
$(LIBRADF): $(FLOAT_OBJS)
	@rm -f $@; $(AR) rcs $@ $^

$(BUILDDIR)/tools/float/%.o: tools/%.c $(TOOL_HDRS) $(LIB_HDRS)
	@mkdir -p $(@D)
	$(CC) $(ALLCFLAGS) $(TOOLFLAGS) -DRAD_FLOAT=1 $(PNG_CFLAGS) -c $< -o $@
$(BUILDDIR)/tools/%.o: tools/%.c $(TOOL_HDRS) $(LIB_HDRS)
	@mkdir -p $(@D)
	$(CC) $(ALLCFLAGS) $(TOOLFLAGS) $(PNG_CFLAGS) -c $< -o $@
$(BUILDDIR)/tools/formats/assimp_scene.o: TOOLFLAGS += $(ASSIMP_CFLAGS)
$(LIBTOOLS): $(TOOL_OBJS)
	@rm -f $@; $(AR) rcs $@ $^

# rad_cli is one source set built twice: rad_cli (fixed) and rad_cli_float (the twin).
CLI_SRCS   := $(wildcard tools/cli/*.c)
$(BUILDDIR)/rad_cli: $(CLI_SRCS:tools/%.c=$(BUILDDIR)/tools/%.o) $(TWIN_FIXED) $(LIBTOOLS) $(LIBRAD)
	$(CC) $(OPT) $(CFLAGS_EXTRA) $^ $(PNG_LIBS) $(STB_LIBS) $(ASSIMP_LIBS) -lm -lpthread -o $@
$(BUILDDIR)/rad_cli_float: $(CLI_SRCS:tools/%.c=$(BUILDDIR)/tools/float/%.o) $(TWIN_FLOAT) $(LIBTOOLS) $(LIBRADF)
	$(CC) $(OPT) $(CFLAGS_EXTRA) $^ $(PNG_LIBS) $(STB_LIBS) $(ASSIMP_LIBS) -lm -lpthread -o $@

# The benchmark: both builds of the core side by side (see tools/bench/rad_bench.c; its
# sections' files are listed in tools/bench/bench.h).
BENCH_SRCS := tools/bench/rad_bench.c tools/bench/bench_peer.c tools/bench/bench_threads.c \
              tools/bench/bench_bake.c tools/bench/bench_tex.c
BENCH_OBJS := $(BENCH_SRCS:tools/%.c=$(BUILDDIR)/tools/%.o)
$(BUILDDIR)/rad_bench: $(BENCH_OBJS) $(TWIN_FIXED) $(TWIN_FLOAT) $(LIBTOOLS) $(LIBRAD) $(LIBRADF)
	$(CC) $(OPT) $(CFLAGS_EXTRA) $^ $(PNG_LIBS) $(STB_LIBS) $(ASSIMP_LIBS) -lm -lpthread -o $@

bench: $(BUILDDIR)/rad_bench $(BUILDDIR)/rad_cli
	$(BUILDDIR)/rad_bench ../shared/scenes/CornellBox-Original.obj

# The level of Sponza's class alone (long: tools/bench/level.h, docs/new-level.md).
bench-level: $(BUILDDIR)/rad_bench
	$(BUILDDIR)/rad_bench --level

# The cost curve against rpkCpp (long; the peer built beside the project: docs/bench.md).
bench-curve: $(BUILDDIR)/rad_bench $(BUILDDIR)/rad_cli
	$(BUILDDIR)/rad_bench --curve

# Every test links both builds of the core (through the host glue) and the host tools,
# and the objects under $(BUILDDIR)/tests/ that a line below adds to its prerequisites.
# A test that drives the core's API in both builds is compiled twice: its float half
# (-DRAD_FLOAT=1, tests/float/*.o) is linked into the fixed one.
$(BUILDDIR)/tests/%: tests/%.c $(TWIN_FIXED) $(TWIN_FLOAT) $(LIBTOOLS) $(LIBRAD) $(LIBRADF) $(LIB_HDRS) $(TOOL_HDRS) $(TEST_HDRS)
	@mkdir -p $(@D)
	$(CC) $(ALLCFLAGS) $(TOOLFLAGS) -Itests -Ilib $(PNG_CFLAGS) $< $(filter $(BUILDDIR)/tests/%.o,$^) $(TWIN_FIXED) $(TWIN_FLOAT) $(LIBTOOLS) $(LIBRAD) $(LIBRADF) $(CMOCKA_LIBS) $(PNG_LIBS) $(STB_LIBS) $(ASSIMP_LIBS) -lm -lpthread -o $@

# test_adopt's caller compiled with the other index width than the library's (16 <-> 32).
$(BUILDDIR)/tests/test_adopt: $(BUILDDIR)/tests/adopt_other_abi.o
$(BUILDDIR)/tests/adopt_other_abi.o: tests/adopt_other_abi.c tests/adopt_other_abi.h $(RAD_BUILD_H) $(LIB_HDRS)
	@mkdir -p $(@D)
	bits=$$(awk '$$1 == "#define" && $$2 == "RAD_INDEX_BITS" { print $$3 }' $(RAD_BUILD_H)); \
	$(CC) $(ALLCFLAGS) -Itests -URAD_INDEX_BITS -DRAD_INDEX_BITS=$$((48 - bits)) -c $< -o $@

$(BUILDDIR)/tests/float/%.o: tests/%.c $(LIB_HDRS) $(TOOL_HDRS) $(TEST_HDRS)
	@mkdir -p $(@D)
	$(CC) $(ALLCFLAGS) $(TOOLFLAGS) -Itests -Ilib -DRAD_FLOAT=1 -c $< -o $@
$(BUILDDIR)/tests/test_gather: $(BUILDDIR)/tests/float/test_gather.o
$(BUILDDIR)/tests/test_cull: $(BUILDDIR)/tests/float/test_cull.o
$(BUILDDIR)/tests/test_light: $(BUILDDIR)/tests/float/test_light.o

# tests/test_scale.c drives the core directly in both builds: its float pass is an
# object of its own (RAD_FLOAT=1), as tests/fuzz/fuzz_core.c's is.
$(BUILDDIR)/tests/test_scale_float.o: tests/test_scale.c $(LIB_HDRS)
	@mkdir -p $(@D)
	$(CC) $(ALLCFLAGS) -DRAD_FLOAT=1 -c $< -o $@
$(BUILDDIR)/tests/test_scale: tests/test_scale.c $(BUILDDIR)/tests/test_scale_float.o $(LIBRAD) $(LIBRADF) $(LIB_HDRS)
	$(CC) $(ALLCFLAGS) $< $(BUILDDIR)/tests/test_scale_float.o $(LIBRAD) $(LIBRADF) $(CMOCKA_LIBS) -lm -o $@

# The core's promise, proven from the objects: nothing from outside but compiler helpers.
nm-check: $(LIBRAD)
	@sh tests/nm_check.sh $(LIBRAD)

test: all $(TESTS) nm-check
	@MAKE="$(MAKE)" CC="$(CC)" RAD_CFLAGS_EXTRA="$(CFLAGS_EXTRA)" sh tests/run_tests.sh $(BUILDDIR) $(TESTS) tests/pkgconfig_check.sh tests/docs_check.sh tests/twin_names_check.sh

clean:
	rm -rf $(BUILDDIR)

# The main job on the bundled example.
example: all
	$(BUILDDIR)/rad_cli examples/cornell_box.obj -o cornell_box.png --stats

# The README's pictures, regenerated (never edited by hand). The level (rad_bench's
# atrium, 62,296 quads under its sun and sky) solves for about 4 minutes on 2 threads;
# --coarse 0 because coarse shots (res down to 24) mottle its columns' small elements
# in the shade.
readme-image: $(BUILDDIR)/rad_cli $(BUILDDIR)/rad_bench
	$(BUILDDIR)/rad_cli examples/cornell_box.obj -o docs/cornell_box.png --width 400 --height 400 --quiet
	$(BUILDDIR)/rad_cli examples/gallery.obj -o docs/gallery.png --width 400 --height 300 --quiet
	mkdir -p $(BUILDDIR)/level
	$(BUILDDIR)/rad_bench --write-level $(BUILDDIR)/level
	$(BUILDDIR)/rad_cli $(BUILDDIR)/level/level.obj --lights $(BUILDDIR)/level/level.json --tol 0.01 \
	    --coarse 0 --threads 2 --camera -16,8,16,5,2,-5,55 --width 640 --height 400 -o docs/level.png --quiet

# ---- installing ----------------------------------------------------------------
# make install-lib: the libraries, headers and pkg-config files (rad, rad_float) alone;
# make install: those and the programs; make uninstall removes what either installed.
# DESTDIR stages (packagers); PREFIX is what the .pc files and paths record.
RAD_VERSION_STR := $(shell awk '/^.define RAD_VERSION_(MAJOR|MINOR|PATCH) /{ v = v s $$3; s = "." } END { print v }' include/rad/rad.h)
INST_LIB := $(DESTDIR)$(PREFIX)/lib
INST_INC := $(DESTDIR)$(PREFIX)/include/rad
INST_PC  := $(INST_LIB)/pkgconfig
INST_BIN := $(DESTDIR)$(PREFIX)/bin
INST_HDRS := $(filter-out include/rad/rad_build.h,$(wildcard include/rad/*.h))

# How librad.a was built, for the installed headers: the index width and limits the
# library's compiler saw (a program built with others gets RAD_ERR_ABI from rad_init).
$(RAD_BUILD_H): include/rad/rad_config.h include/rad/rad_build.h Makefile
	@mkdir -p $(@D)
	@{ echo '/* rad — how the installed librad.a was built (generated by make lib). */'; \
	  echo '#ifndef RAD_BUILD_H'; echo '#define RAD_BUILD_H'; \
	  echo '#define RAD_BUILD_TARGET "'"$$($(CC) -dumpmachine)"'"'; \
	  $(CC) $(ALLCFLAGS) $(LIBFLAGS) $(TARGET_FLAGS) -dM -E include/rad/rad_config.h | \
	    awk '$$2 ~ /^RAD_(INDEX_BITS|MAX_RES|MAX_RASTER)$$/ { print "#ifndef " $$2; print $$0; print "#endif" }'; \
	  echo '#endif'; } >$@.tmp && mv $@.tmp $@

# One .pc per build of the core: rad (fixed) and rad_float (the float twin).
define RAD_PC
prefix=$(PREFIX)
libdir=$${prefix}/lib
includedir=$${prefix}/include

Name: $(1)
Description: $(2)
Version: $(RAD_VERSION_STR)
Cflags: -I$${includedir}$(3)
Libs: -L$${libdir} -l$(1)
endef
export RAD_PC_FIXED := $(call RAD_PC,rad,hemi-cube radiosity in fixed point (no malloc, libm or FPU),)
export RAD_PC_FLOAT := $(call RAD_PC,rad_float,hemi-cube radiosity: the float twin of rad, -DRAD_FLOAT=1)

install-lib: lib
	install -d $(INST_LIB) $(INST_INC) $(INST_PC)
	install -m 644 $(LIBRAD) $(LIBRADF) $(INST_LIB)
	install -m 644 $(INST_HDRS) $(RAD_BUILD_H) $(INST_INC)
	printf '%s\n' "$$RAD_PC_FIXED" >$(INST_PC)/rad.pc
	printf '%s\n' "$$RAD_PC_FLOAT" >$(INST_PC)/rad_float.pc

install: all install-lib
	install -d $(INST_BIN)
	install -m 755 $(BUILDDIR)/rad_cli $(BUILDDIR)/rad_cli_float $(INST_BIN)

uninstall:
	rm -f $(INST_LIB)/librad.a $(INST_LIB)/librad_float.a $(INST_PC)/rad.pc $(INST_PC)/rad_float.pc
	rm -f $(INST_HDRS:include/rad/%=$(INST_INC)/%) $(INST_INC)/rad_build.h
	rm -f $(INST_BIN)/rad_cli $(INST_BIN)/rad_cli_float
	-rmdir $(INST_INC) $(INST_PC) 2>/dev/null || true
include ports/ports.mk
include tests/check.mk
