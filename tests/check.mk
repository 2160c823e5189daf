# SPDX-License-Identifier: MIT
# rad — `make check`: the reliability gates (sanitizers, valgrind, clang, static analysis,
# configuration variants, fuzzing). Included from the top Makefile:
#
#     include tests/check.mk
#
# Debian packages on top of the README's install line: clang libclang-rt-dev (libFuzzer and clang's
# sanitizer runtimes: a Recommends of clang, so --no-install-recommends leaves them
# out), valgrind, cppcheck, clang-tidy, clang-format; llvm (llvm-symbolizer) for readable stack
# traces is optional.
#
# Every stage builds in its own directory under $(CHECKDIR) through a recursive make of
# this Makefile, so the same suite runs everywhere; each logs to $(CHECKDIR)/<stage>.log
# and prints one line, and `check` ends with a summary table. Stages run in parallel
# ($(CHECK_JOBS) jobs unless make was given -j) and a failing stage does not stop the
# others (-k); `check` fails if any stage did. Each stage is also a target of its own:
#
#   check-asan      gcc, AddressSanitizer + UndefinedBehaviorSanitizer (+ float-cast-
#                   overflow, which gcc leaves out of -fsanitize=undefined), no recovery
#   check-valgrind  gcc -O1 -g under valgrind memcheck, leaks included: VALGRIND_TESTS
#   check-clang     clang -Werror, the whole suite, and the core's nm check
#   check-lint      cppcheck and clang-tidy on lib/, fixed and float builds; clang-format
#                   (.clang-format) on every C source but the generated twin names
#   check-idx16     -DRAD_INDEX_BITS=16: the whole suite
#   check-small     -DRAD_INDEX_BITS=16 -DRAD_MAX_RES=64 (the Cortex-M0 shape): the
#                   programs that need no hemi-cube above 64 (SMALL_TESTS), including
#                   test_hostile's band-mode and small-limit tests
#   check-fuzz      libFuzzer + ASan + UBSan, FUZZ_SECONDS per harness (tests/fuzz/)
#   check-soak      tests/soak/soak.c under UBSan: SOAK_SCENES randomised scenes from
#                   SOAK_SEED, each converged or reported not, saturations reported,
#                   the energy balance met, rendered views finite (18 s, and the build)
#
# test_cli runs "build/rad_cli" relative to the working directory, so each suite runs
# in $(CHECKDIR)/<stage>/root: symbolic links to this tree, with build/ pointing at the
# stage's build directory. The CLI tests then exercise that stage's (instrumented)
# rad_cli rather than the plain build's.

# How to call this file again: through the top Makefile when it includes it, else (as
# in `make -f Makefile -f tests/check.mk check`) with both files.
CHECK_SELF   := $(lastword $(MAKEFILE_LIST))
CHECK_TOP    := $(firstword $(MAKEFILE_LIST))
CHECK_MAKE    = $(MAKE) --no-print-directory -f $(CHECK_TOP) \
                $(if $(shell grep -s -q '^ *-\{0,1\}include  *$(CHECK_SELF)' $(CHECK_TOP) && echo y),,-f $(CHECK_SELF))

CHECKDIR     := $(BUILDDIR)/check
CHECK_STATUS := $(CHECKDIR)/status
CHECK_JOBS   ?= 2
CHECK_GCC    ?= gcc
CHECK_CLANG  ?= clang
FUZZ_SECONDS ?= 40
SOAK_SEED    ?= 19
SOAK_SCENES  ?= 1000
CHECK_STAGE  := sh tests/fuzz/check_stage.sh $(CHECK_STATUS)

# Test programs by name (tests/test_NAME.c).
CHECK_TESTS     = $(TEST_SRCS:tests/test_%.c=%)
# All but test_fgather: its setup solves a reference 4 times finer, 216 of the stage's
# 1,028 s here (2026-12-06); its code runs under ASan and UBSan in the asan stage, and
# the gathers it calls under valgrind in test_gather, test_cull and test_sides.
VALGRIND_TESTS ?= $(filter-out fgather,$(CHECK_TESTS))
SMALL_TESTS    ?= api fixmath render obj image hostile
check_progs = $(addprefix build/tests/test_,$(1))

CHECK_ASAN_FLAGS := -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all \
                    -fno-omit-frame-pointer
CHECK_ASAN_ENV   := ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1:abort_on_error=0 \
                    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
CHECK_VALGRIND   := valgrind -q --error-exitcode=99 --leak-check=full
CHECK_SOAK_FLAGS := -fsanitize=undefined,float-cast-overflow -fno-sanitize-recover=all

# -fno-tree-loop-distribute-patterns in LIBFLAGS is gcc's; clang refuses it.
CHECK_CLANG_LIBFLAGS := -ffreestanding

# The stage's view of the tree: every top-level entry but the build directory, and
# build -> the stage directory.
CHECK_BUILD_TOP  = $(firstword $(subst /, ,$(patsubst $(CURDIR)/%,%,$(abspath $(BUILDDIR)))))
CHECK_ROOT_ITEMS = $(filter-out $(CHECK_BUILD_TOP) build,$(notdir $(wildcard $(CURDIR)/* $(CURDIR)/.clang-tidy)))
define check_root
rm -rf $(1)/root && mkdir -p $(1)/root && \
for f in $(CHECK_ROOT_ITEMS); do ln -s $(CURDIR)/$$f $(1)/root/$$f; done && \
ln -sfn .. $(1)/root/build
endef
# $(call check_make,STAGE-DIR,CC,OPT,CFLAGS_EXTRA,[extra make arguments]) TARGETS...
check_make = $(MAKE) --no-print-directory -C $(1)/root BUILDDIR=build WERROR=-Werror CC=$(2) OPT='$(3)' CFLAGS_EXTRA='$(4)' $(5)

CHECK_STAGES := asan valgrind clang lint idx16 small soak fuzz-obj fuzz-core fuzz-image fuzz-mtl_texture fuzz-views \
                fuzz-json
CHECK_PARALLEL = $(if $(filter -j%,$(MAKEFLAGS)),,-j$(CHECK_JOBS))

.PHONY: check check-stages check-asan check-valgrind check-clang check-lint check-idx16 \
        check-small check-fuzz check-fuzz-build check-fuzz-obj check-fuzz-core check-fuzz-image \
        check-fuzz-mtl_texture check-fuzz-mtl_texture-run \
        check-fuzz-views check-fuzz-views-run check-fuzz-json check-fuzz-json-run \
        check-asan-run check-valgrind-run check-clang-run check-lint-run check-idx16-run \
        check-small-run check-fuzz-obj-run check-fuzz-core-run check-fuzz-image-run \
        check-soak check-soak-run

check:
	@+rm -rf $(CHECK_STATUS); mkdir -p $(CHECK_STATUS); start=$$(date +%s); \
	$(CHECK_MAKE) $(CHECK_PARALLEL) -k check-stages; \
	sh tests/fuzz/check_summary.sh $(CHECK_STATUS) $$(($$(date +%s) - start)) $(CHECK_STAGES)

# Longest first, so that -j2 overlaps valgrind with everything else.
check-stages: check-valgrind check-asan check-fuzz check-clang check-idx16 check-small check-soak check-lint

check-asan:
	@+$(CHECK_STAGE) asan $(CHECKDIR)/asan.log $(CHECK_MAKE) check-asan-run
check-asan-run:
	$(call check_root,$(CHECKDIR)/asan)
	+$(CHECK_ASAN_ENV) $(call check_make,$(CHECKDIR)/asan,$(CHECK_GCC),-O1 -g,$(CHECK_ASAN_FLAGS),-o nm-check) test
	@echo "nm-check skipped: sanitizer runtime calls are expected in an instrumented librad.a"

check-valgrind:
	@+$(CHECK_STAGE) valgrind $(CHECKDIR)/valgrind.log $(CHECK_MAKE) check-valgrind-run
check-valgrind-run:
	$(call check_root,$(CHECKDIR)/valgrind)
	+RAD_TEST_WRAP='$(CHECK_VALGRIND)' RAD_TEST_LIGHT=1 \
	  $(call check_make,$(CHECKDIR)/valgrind,$(CHECK_GCC),-O1 -g,,TESTS='$(call check_progs,$(VALGRIND_TESTS))') test

check-clang:
	@+$(CHECK_STAGE) clang $(CHECKDIR)/clang.log $(CHECK_MAKE) check-clang-run
check-clang-run:
	$(call check_root,$(CHECKDIR)/clang)
	+$(call check_make,$(CHECKDIR)/clang,$(CHECK_CLANG),-O2 -g,,LIBFLAGS='$(CHECK_CLANG_LIBFLAGS)' -o nm-check) test
	@# The host nm check refuses every libc symbol; clang turns struct copies into
	@# memcpy calls even with -ffreestanding (as gcc does at -Os on the ports), so
	@# accept the four functions every freestanding C environment must provide, as
	@# ports/ports.mk does, and nothing else.
	@out=$$(sh tests/nm_check.sh $(CHECKDIR)/clang/librad.a); echo "$$out"; \
	case "$$out" in *FAIL*) \
	  extra=$$(echo "$$out" | sed -n 's/.*outside the core://p' | tr ' ' '\n' | grep -v -x -E 'memcpy|memmove|memset|memcmp|' || true); \
	  if [ -n "$$extra" ]; then echo "clang nm-check: FAIL:" $$extra; exit 1; fi; \
	  echo "clang nm-check: ok apart from freestanding memcpy/memset/memmove/memcmp";; \
	esac

# Static analysis of the core, in both builds. Reasons for the suppressed warnings are in
# tests/cppcheck-suppressions.txt and .clang-tidy. The house style (.clang-format) on
# every C source; tools/host/twin_names.py writes the two generated headers.
CHECK_LINT_DEFS := -DRAD_FLOAT=0 -DRAD_FLOAT=1
FORMAT_SRCS := $(filter-out tools/host/float_names.h tools/host/scene_float.h, \
    $(sort $(shell find lib include ports tools tests -name '*.[ch]' -not -path 'tests/data/*')))
check-lint:
	@+$(CHECK_STAGE) lint $(CHECKDIR)/lint.log $(CHECK_MAKE) check-lint-run
check-lint-run:
	@mkdir -p $(CHECKDIR)/lint
	@rc=0; for d in $(CHECK_LINT_DEFS); do \
	  echo "== cppcheck $$d (64-bit)"; \
	  cppcheck --enable=warning,performance,portability --error-exitcode=1 --inline-suppr -q \
	    --std=c99 --platform=unix64 --suppressions-list=tests/cppcheck-suppressions.txt \
	    -Iinclude -Ilib $$d $(LIB_SRCS) || rc=1; \
	  echo "== cppcheck $$d -DRAD_INDEX_BITS=16 (32-bit)"; \
	  cppcheck --enable=warning,portability --error-exitcode=1 --inline-suppr -q \
	    --std=c99 --platform=unix32 --suppressions-list=tests/cppcheck-suppressions.txt \
	    -Iinclude -Ilib $$d -DRAD_INDEX_BITS=16 $(LIB_SRCS) || rc=1; \
	  echo "== clang-tidy $$d (.clang-tidy)"; \
	  clang-tidy --quiet $(LIB_SRCS) -- -std=c99 -Iinclude -Ilib -ffreestanding $$d \
	    >$(CHECKDIR)/lint/tidy.out 2>&1 || rc=1; \
	  grep -v 'warnings generated' $(CHECKDIR)/lint/tidy.out || true; \
	done; \
	echo "== clang-format --dry-run (.clang-format), $(words $(FORMAT_SRCS)) files"; \
	clang-format --dry-run -Werror $(FORMAT_SRCS) || rc=1; \
	if [ $$rc -ne 0 ]; then echo "lint: findings above"; exit 1; fi; \
	echo "cppcheck and clang-tidy: no findings in lib/ (fixed and float builds); clang-format: none"

check-idx16:
	@+$(CHECK_STAGE) idx16 $(CHECKDIR)/idx16.log $(CHECK_MAKE) check-idx16-run
check-idx16-run:
	$(call check_root,$(CHECKDIR)/idx16)
	+$(call check_make,$(CHECKDIR)/idx16,$(CHECK_GCC),-O2 -g,-DRAD_INDEX_BITS=16) test

check-small:
	@+$(CHECK_STAGE) small $(CHECKDIR)/small.log $(CHECK_MAKE) check-small-run
check-small-run:
	$(call check_root,$(CHECKDIR)/small)
	+$(call check_make,$(CHECKDIR)/small,$(CHECK_GCC),-O2 -g,-DRAD_INDEX_BITS=16 -DRAD_MAX_RES=64,TESTS='$(call check_progs,$(SMALL_TESTS))') test

check-soak:
	@+$(CHECK_STAGE) soak $(CHECKDIR)/soak.log $(CHECK_MAKE) check-soak-run
check-soak-run:
	$(call check_root,$(CHECKDIR)/soak)
	+$(call check_make,$(CHECKDIR)/soak,$(CHECK_GCC),-O2 -g,$(CHECK_SOAK_FLAGS)) build/tests/soak/soak
	cd $(CHECKDIR)/soak/root && UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 build/tests/soak/soak $(SOAK_SEED) $(SOAK_SCENES)

# ---- fuzzing ---------------------------------------------------------------------------
# Harnesses in tests/fuzz/, seeds in tests/fuzz/corpus/NAME (read only); what a run adds
# goes to $(FUZZDIR)/corpus-NAME and is kept for the next run, crashes to
# $(FUZZDIR)/NAME-crash-*. Reproduce one with: $(FUZZDIR)/fuzz_NAME FILE
FUZZDIR     := $(CHECKDIR)/fuzz
FUZZ_CFLAGS := -std=c99 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
               -fno-omit-frame-pointer -Wall -Wextra -Werror $(CPPFLAGS) -Ilib -Itools
# FUZZ_SECONDS=0 only replays the seeds and the saved corpus.
FUZZ_RUN     = $(if $(filter 0,$(FUZZ_SECONDS)),-runs=0,-max_total_time=$(FUZZ_SECONDS)) \
               -timeout=30 -rss_limit_mb=2560 -print_final_stats=1
FUZZ_HARNESSES := obj core image mtl_texture views json
FUZZ_DICT_obj   = -dict=$(CURDIR)/tests/fuzz/obj.dict
FUZZ_DICT_mtl_texture = -dict=$(CURDIR)/tests/fuzz/mtl_texture.dict
FUZZ_DICT_json  = -dict=$(CURDIR)/tests/fuzz/json.dict
FUZZ_FIXED   = $(LIB_SRCS:lib/%.c=$(FUZZDIR)/lib/fixed/%.o)
FUZZ_FLOAT   = $(LIB_SRCS:lib/%.c=$(FUZZDIR)/lib/float/%.o)

$(FUZZDIR)/lib/fixed/%.o: lib/%.c $(LIB_HDRS)
	@mkdir -p $(@D)
	$(CHECK_CLANG) $(FUZZ_CFLAGS) -ffreestanding -c $< -o $@
$(FUZZDIR)/lib/float/%.o: lib/%.c $(LIB_HDRS)
	@mkdir -p $(@D)
	$(CHECK_CLANG) $(FUZZ_CFLAGS) -ffreestanding -DRAD_FLOAT=1 -c $< -o $@
$(FUZZDIR)/tools/%.o: tools/%.c $(TOOL_HDRS) $(LIB_HDRS)
	@mkdir -p $(@D)
	$(CHECK_CLANG) $(FUZZ_CFLAGS) -D_POSIX_C_SOURCE=200809L $(PNG_CFLAGS) -c $< -o $@
$(FUZZDIR)/fuzz_obj: tests/fuzz/fuzz_obj.c $(FUZZDIR)/tools/formats/obj.o $(FUZZDIR)/tools/formats/file_io.o $(TOOL_HDRS)
	$(CHECK_CLANG) $(FUZZ_CFLAGS) -D_POSIX_C_SOURCE=200809L $< $(FUZZDIR)/tools/formats/obj.o $(FUZZDIR)/tools/formats/file_io.o -lm -o $@
$(FUZZDIR)/fuzz_image: tests/fuzz/fuzz_image.c $(FUZZDIR)/tools/formats/image.o $(FUZZDIR)/tools/formats/file_io.o $(TOOL_HDRS)
	$(CHECK_CLANG) $(FUZZ_CFLAGS) -D_POSIX_C_SOURCE=200809L $(PNG_CFLAGS) $< $(FUZZDIR)/tools/formats/image.o $(FUZZDIR)/tools/formats/file_io.o $(PNG_LIBS) -lm -o $@
# libstb is the system's (not instrumented): the harness covers our side of it.
# gltf.o re-encodes BMP and TGA textures as PNG (image.o, libpng).
FUZZ_TEX_OBJS = $(FUZZDIR)/tools/formats/obj.o $(FUZZDIR)/tools/formats/texture.o $(FUZZDIR)/tools/formats/gltf.o \
                $(FUZZDIR)/tools/formats/image.o $(FUZZDIR)/tools/formats/file_io.o
$(FUZZDIR)/fuzz_mtl_texture: tests/fuzz/fuzz_mtl_texture.c $(FUZZ_TEX_OBJS) $(TOOL_HDRS)
	$(CHECK_CLANG) $(FUZZ_CFLAGS) -D_POSIX_C_SOURCE=200809L $(PNG_CFLAGS) $< $(FUZZ_TEX_OBJS) $(STB_LIBS) $(PNG_LIBS) -lm -o $@
# rad_cli's --views and --animate parsers, taken from a buffer (tools/cli/views.c).
$(FUZZDIR)/fuzz_views: tests/fuzz/fuzz_views.c $(FUZZDIR)/tools/cli/views.o $(TOOL_HDRS)
	$(CHECK_CLANG) $(FUZZ_CFLAGS) -D_POSIX_C_SOURCE=200809L $< $(FUZZDIR)/tools/cli/views.o -lm -o $@
# rad_cli's --lights reader (tools/formats/json.c).
$(FUZZDIR)/fuzz_json: tests/fuzz/fuzz_json.c $(FUZZDIR)/tools/formats/json.o $(TOOL_HDRS)
	$(CHECK_CLANG) $(FUZZ_CFLAGS) -D_POSIX_C_SOURCE=200809L $< $(FUZZDIR)/tools/formats/json.o -lm -o $@
$(FUZZDIR)/fuzz_core_float.o: tests/fuzz/fuzz_core.c $(LIB_HDRS)
	@mkdir -p $(@D)
	$(CHECK_CLANG) $(FUZZ_CFLAGS) -DRAD_FLOAT=1 -c $< -o $@
$(FUZZDIR)/fuzz_core: tests/fuzz/fuzz_core.c $(FUZZDIR)/fuzz_core_float.o $(FUZZ_FIXED) $(FUZZ_FLOAT)
	$(CHECK_CLANG) $(FUZZ_CFLAGS) $< $(FUZZDIR)/fuzz_core_float.o $(FUZZ_FIXED) $(FUZZ_FLOAT) -o $@

check-fuzz-build: $(FUZZ_HARNESSES:%=$(FUZZDIR)/fuzz_%)
check-fuzz: check-fuzz-obj check-fuzz-core check-fuzz-image check-fuzz-mtl_texture check-fuzz-views check-fuzz-json

# One stage per harness, so that two can run at once; each builds its own harness.
check-fuzz-obj check-fuzz-core check-fuzz-image check-fuzz-mtl_texture check-fuzz-views check-fuzz-json: check-fuzz-%:
	@+$(CHECK_STAGE) fuzz-$* $(CHECKDIR)/fuzz-$*.log $(CHECK_MAKE) check-fuzz-$*-run
check-fuzz-obj-run check-fuzz-core-run check-fuzz-image-run check-fuzz-mtl_texture-run check-fuzz-views-run \
check-fuzz-json-run: check-fuzz-%-run: $(FUZZDIR)/fuzz_%
	@mkdir -p $(FUZZDIR)/corpus-$*
	cd $(FUZZDIR) && UBSAN_OPTIONS=print_stacktrace=1 ASAN_OPTIONS=detect_leaks=1 \
	  ./fuzz_$* $(FUZZ_RUN) $(FUZZ_DICT_$*) -artifact_prefix=$*- corpus-$* $(CURDIR)/tests/fuzz/corpus/$*
