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
CMOCKA_LIBS := -lcmocka

LIB_SRCS   := $(wildcard lib/*.c)
LIB_HDRS   := $(wildcard lib/*.h include/rad/*.h)
# Host glue built once per build of the core (fixed: sc_*, float: scf_*).
TWIN_SRCS  := tools/host/scene.c tools/host/parallel.c
# Host helpers built once.
TOOL_SRCS  := $(wildcard tools/formats/*.c tools/reference/*.c tools/bake/*.c) tools/host/obj_polys.c \
              tools/host/clock.c tools/bench/plot.c
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
TESTS      := $(TEST_SRCS:tests/%.c=$(BUILDDIR)/tests/%)

.PHONY: all test check ports port-test port-bench port-size bench install clean nm-check example readme-image
all: $(LIBRAD) $(LIBRADF) $(BUILDDIR)/rad_cli $(BUILDDIR)/rad_cli_float

$(BUILDDIR)/lib/fixed/%.o: lib/%.c $(LIB_HDRS)
	@mkdir -p $(@D)
	$(CC) $(ALLCFLAGS) $(LIBFLAGS) -c $< -o $@
$(BUILDDIR)/lib/float/%.o: lib/%.c $(LIB_HDRS)
	@mkdir -p $(@D)
	$(CC) $(ALLCFLAGS) $(LIBFLAGS) -DRAD_FLOAT=1 -c $< -o $@
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
$(LIBTOOLS): $(TOOL_OBJS)
	@rm -f $@; $(AR) rcs $@ $^

# rad_cli is one source set built twice: rad_cli (fixed) and rad_cli_float (the twin).
CLI_SRCS   := $(wildcard tools/cli/*.c)
$(BUILDDIR)/rad_cli: $(CLI_SRCS:tools/%.c=$(BUILDDIR)/tools/%.o) $(TWIN_FIXED) $(LIBTOOLS) $(LIBRAD)
	$(CC) $(OPT) $(CFLAGS_EXTRA) $^ $(PNG_LIBS) -lm -lpthread -o $@
$(BUILDDIR)/rad_cli_float: $(CLI_SRCS:tools/%.c=$(BUILDDIR)/tools/float/%.o) $(TWIN_FLOAT) $(LIBTOOLS) $(LIBRADF)
	$(CC) $(OPT) $(CFLAGS_EXTRA) $^ $(PNG_LIBS) -lm -lpthread -o $@

# The benchmark: both builds of the core side by side (see tools/bench/rad_bench.c).
$(BUILDDIR)/rad_bench: $(BUILDDIR)/tools/bench/rad_bench.o $(TWIN_FIXED) $(TWIN_FLOAT) $(LIBTOOLS) $(LIBRAD) $(LIBRADF)
	$(CC) $(OPT) $(CFLAGS_EXTRA) $^ $(PNG_LIBS) -lm -lpthread -o $@

bench: $(BUILDDIR)/rad_bench
	$(BUILDDIR)/rad_bench ../shared/scenes/CornellBox-Original.obj

# Every test links both builds of the core (through the host glue) and the host tools.
# A test that drives the core's API in both builds is compiled twice: its float half
# (-DRAD_FLOAT=1, tests/float/*.o, a prerequisite below) is linked into the fixed one.
$(BUILDDIR)/tests/%: tests/%.c $(TWIN_FIXED) $(TWIN_FLOAT) $(LIBTOOLS) $(LIBRAD) $(LIBRADF) $(LIB_HDRS) $(TOOL_HDRS) $(TEST_HDRS)
	@mkdir -p $(@D)
	$(CC) $(ALLCFLAGS) $(TOOLFLAGS) -Itests -Ilib $(PNG_CFLAGS) $< $(filter $(BUILDDIR)/tests/float/%.o,$^) $(TWIN_FIXED) $(TWIN_FLOAT) $(LIBTOOLS) $(LIBRAD) $(LIBRADF) $(CMOCKA_LIBS) $(PNG_LIBS) -lm -lpthread -o $@
$(BUILDDIR)/tests/float/%.o: tests/%.c $(LIB_HDRS) $(TOOL_HDRS) $(TEST_HDRS)
	@mkdir -p $(@D)
	$(CC) $(ALLCFLAGS) $(TOOLFLAGS) -Itests -Ilib -DRAD_FLOAT=1 -c $< -o $@
$(BUILDDIR)/tests/test_gather: $(BUILDDIR)/tests/float/test_gather.o

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
	@sh tests/run_tests.sh $(BUILDDIR) $(TESTS)

clean:
	rm -rf $(BUILDDIR)

# The main job on the bundled example.
example: all
	$(BUILDDIR)/rad_cli examples/cornell_box.obj -o cornell_box.png --stats

# The README's picture, regenerated (never edited by hand).
readme-image: $(BUILDDIR)/rad_cli
	$(BUILDDIR)/rad_cli examples/cornell_box.obj -o docs/cornell_box.png --res 128 --width 400 --height 400 --quiet
	$(BUILDDIR)/rad_cli examples/gallery.obj -o docs/gallery.png --res 128 --width 400 --height 300 --quiet

install: all
	install -d $(DESTDIR)$(PREFIX)/lib $(DESTDIR)$(PREFIX)/include/rad $(DESTDIR)$(PREFIX)/bin
	install -m 644 $(LIBRAD) $(LIBRADF) $(DESTDIR)$(PREFIX)/lib
	install -m 644 include/rad/*.h $(DESTDIR)$(PREFIX)/include/rad
	install -m 755 $(BUILDDIR)/rad_cli $(BUILDDIR)/rad_cli_float $(DESTDIR)$(PREFIX)/bin
include ports/ports.mk
include tests/check.mk
