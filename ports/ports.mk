# SPDX-License-Identifier: MIT
# rad ports — Cortex-M0, Cortex-M3 and RV32 under QEMU, bit-exact with the host.
#
# Included by the top Makefile (after its own rules: `include ports/ports.mk`).
#   make port-test    build the host and the three targets, run each port test, and
#                     fail unless every target prints the host's results (same profile)
#   make port-bench   instruction counts: one shot at res 16/32/64 and the whole solve,
#                     fixed and float twin, and their ratio -> $(BUILDDIR)/ports/port-bench.md
#   make port-size    the core's .text/.data/.bss per target (-Os) and the RAM each port
#                     test used (static + measured stack) -> $(BUILDDIR)/ports/port-size.md
#   make port-guide   ports/README.md's worked firmware examples, built by the guide's own
#                     commands and run under QEMU (ports/common/guide_check.sh); port-test
#                     runs it too
#   make port-nm      the cross-built core needs nothing but compiler runtime helpers
#   make ports        port-nm, port-test and port-size
# Toolchains and emulators: ARM_PREFIX, RV_PREFIX, QEMU_ARM, QEMU_RV32 (see below).
# Everything is built under $(BUILDDIR)/ports/; run outputs under $(BUILDDIR)/ports/run/.

PORT_SAVED_GOAL := $(.DEFAULT_GOAL)

BUILDDIR ?= build
CC ?= cc
ARM_PREFIX ?= arm-none-eabi-
RV_PREFIX ?= riscv64-unknown-elf-
QEMU_ARM ?= qemu-system-arm
QEMU_RV32 ?= qemu-system-riscv32
# Seconds per port test run and per benchmark run (a hang fails with status 124).
PORT_TIMEOUT ?= 60
PORT_BENCH_TIMEOUT ?= 240
# port-nm accepts compiler runtime helpers (the symbols libgcc defines) and, unless
# PORT_NM_STRICT=1, the four functions GCC requires of every freestanding environment
# (memcpy, memmove, memset, memcmp: GCC calls memcpy for struct copies at -Os).
PORT_NM_STRICT ?= 0

PORT_OUT := $(BUILDDIR)/ports
PORT_SH := sh ports/common/ports.sh
PORT_LIB_SRCS := $(wildcard lib/*.c)
PORT_LIB_HDRS := $(wildcard lib/*.h include/rad/*.h)
PORT_HDRS := $(PORT_LIB_HDRS) ports/common/port.h ports/common/probes.h ports/common/semihost.h
PORT_TEST_SRC := ports/common/port_test.c

# The project's warnings, as errors: the core, the port test and the platform files alike
# (the cross compilers are pinned by the Debian release, so -Werror cannot surprise a user).
PORT_WARN := -std=c99 -Wall -Wextra -pedantic -Werror
PORT_FREE := -ffreestanding -fno-tree-loop-distribute-patterns
PORT_CPPFLAGS := -DRAD_INDEX_BITS=16 -Iinclude -Ilib -Iports/common
PORT_TFLAGS := $(PORT_WARN) -Os $(PORT_FREE) $(PORT_CPPFLAGS)
PORT_HOST_CFLAGS := $(PORT_WARN) -O2 $(PORT_CPPFLAGS)
# The port's own files also get the rest of the project's warnings (the Makefile's WARN).
PORT_OWN_WARN := -Wshadow -Wundef -Wmissing-prototypes

# ---- targets -----------------------------------------------------------------------
# Per target: compiler, CPU flags, defines, platform sources, linker script, the
# profiles its port test runs, and extra flags for the test and the benchmark.
PORT_TARGETS := cortex-m0 cortex-m3 rv32
PORT_CM_PLAT := ports/common/cortex_m.c ports/common/probes.c ports/common/semihost.c ports/common/port_libc.c

PORT_cortex-m0_PREFIX := $(ARM_PREFIX)
PORT_cortex-m0_CPU := -mcpu=cortex-m0 -mthumb -mfloat-abi=soft
PORT_cortex-m0_DEFS := -DPORT_TARGET_NAME=cortex-m0 -DPORT_CPU_HZ=16000000
PORT_cortex-m0_PLAT := $(PORT_CM_PLAT)
PORT_cortex-m0_LD := -Lports/common -Tports/cortex-m0/link.ld
PORT_cortex-m0_PROFILES := small sun
# 16 KB of RAM: the hemi-cube is rendered 24 rows at a time at res 16 (half its 48 rows
# of faces: two passes, bit-exact with all at once, and each pass draws the whole scene
# again, so fewer passes is fewer instructions; 28 bytes of the 16 KB are left); the
# benchmark, 2 rows (its res-32 tables take the room), stops at res 32 and has no room
# for a form factor row (PORT_BENCH_FF).
PORT_cortex-m0_TEST := -DPORT_BAND_ROWS=24
PORT_cortex-m0_BENCH := -DPORT_BAND_ROWS=2 -DPORT_BENCH_MAX_RES=32 -DPORT_BENCH_FF=0

PORT_cortex-m3_PREFIX := $(ARM_PREFIX)
PORT_cortex-m3_CPU := -mcpu=cortex-m3 -mthumb -mfloat-abi=soft
PORT_cortex-m3_DEFS := -DPORT_TARGET_NAME=cortex-m3 -DPORT_CPU_HZ=25000000
PORT_cortex-m3_PLAT := $(PORT_CM_PLAT)
PORT_cortex-m3_LD := -Lports/common -Tports/cortex-m3/link.ld
PORT_cortex-m3_PROFILES := small medium sun
PORT_cortex-m3_TEST :=
# The res-64 work buffer (all faces) needs more than the test's 64 KB budget.
PORT_cortex-m3_BENCH := -Wl,--defsym=__ram_budget=0x100000

PORT_rv32_PREFIX := $(RV_PREFIX)
PORT_rv32_CPU := -march=rv32imac -mabi=ilp32 -misa-spec=2.2 -mcmodel=medany
PORT_rv32_DEFS :=
PORT_rv32_PLAT := ports/rv32/start.S ports/rv32/rv32.c ports/common/probes.c ports/common/semihost.c \
                  ports/common/port_libc.c
PORT_rv32_LD := -Tports/rv32/link.ld
PORT_rv32_PROFILES := small medium sun
PORT_rv32_TEST :=
PORT_rv32_BENCH := -Wl,--defsym=__ram_budget=0x100000

PORT_HOST_PROFILES := small medium sun

# ---- rules per target ----------------------------------------------------------------
# $(1): target. Core objects (fixed and float twin) into archives, then the port test
# (test-PROFILE.elf) and the benchmark (bench-PROFILE.elf, benchf-PROFILE.elf: float).
define PORT_TARGET_RULES
PORT_$(1)_CC := $$(PORT_$(1)_PREFIX)gcc
PORT_$(1)_FIXED_OBJS := $$(PORT_LIB_SRCS:lib/%.c=$$(PORT_OUT)/$(1)/lib/fixed/%.o)
PORT_$(1)_FLOAT_OBJS := $$(PORT_LIB_SRCS:lib/%.c=$$(PORT_OUT)/$(1)/lib/float/%.o)
PORT_$(1)_LINK = $$(PORT_$(1)_CC) $$(PORT_TFLAGS) $$(PORT_OWN_WARN) $$(PORT_$(1)_CPU) $$(PORT_$(1)_DEFS)
PORT_$(1)_DEPS := $$(PORT_TEST_SRC) $$(PORT_$(1)_PLAT) $$(PORT_HDRS) ports/ports.mk \
    $$(wildcard ports/$(1)/*.ld ports/common/*.ld)

$$(PORT_OUT)/$(1)/lib/fixed/%.o: lib/%.c $$(PORT_LIB_HDRS)
	@mkdir -p $$(@D)
	$$(PORT_$(1)_CC) $$(PORT_TFLAGS) $$(PORT_$(1)_CPU) -c $$< -o $$@
$$(PORT_OUT)/$(1)/lib/float/%.o: lib/%.c $$(PORT_LIB_HDRS)
	@mkdir -p $$(@D)
	$$(PORT_$(1)_CC) $$(PORT_TFLAGS) $$(PORT_$(1)_CPU) -DRAD_FLOAT=1 -c $$< -o $$@
$$(PORT_OUT)/$(1)/librad.a: $$(PORT_$(1)_FIXED_OBJS)
	@rm -f $$@; $$(PORT_$(1)_PREFIX)ar rcs $$@ $$^
$$(PORT_OUT)/$(1)/librad_float.a: $$(PORT_$(1)_FLOAT_OBJS)
	@rm -f $$@; $$(PORT_$(1)_PREFIX)ar rcs $$@ $$^

$$(PORT_OUT)/$(1)/test-%.elf: $$(PORT_$(1)_DEPS) $$(PORT_OUT)/$(1)/librad.a
	$$(PORT_$(1)_LINK) -DPORT_PROFILE=$$* $$(PORT_$(1)_TEST) $$(PORT_TEST_SRC) $$(PORT_$(1)_PLAT) \
	    $$(PORT_OUT)/$(1)/librad.a -nostdlib $$(PORT_$(1)_LD) -lgcc -o $$@
$$(PORT_OUT)/$(1)/bench-%.elf: $$(PORT_$(1)_DEPS) $$(PORT_OUT)/$(1)/librad.a
	$$(PORT_$(1)_LINK) -DPORT_PROFILE=$$* -DPORT_BENCH=1 $$(PORT_$(1)_BENCH) $$(PORT_TEST_SRC) \
	    $$(PORT_$(1)_PLAT) $$(PORT_OUT)/$(1)/librad.a -nostdlib $$(PORT_$(1)_LD) -lgcc -o $$@
$$(PORT_OUT)/$(1)/benchf-%.elf: $$(PORT_$(1)_DEPS) $$(PORT_OUT)/$(1)/librad_float.a
	$$(PORT_$(1)_LINK) -DPORT_PROFILE=$$* -DPORT_BENCH=1 -DRAD_FLOAT=1 $$(PORT_$(1)_BENCH) \
	    $$(PORT_TEST_SRC) $$(PORT_$(1)_PLAT) $$(PORT_OUT)/$(1)/librad_float.a -nostdlib \
	    $$(PORT_$(1)_LD) -lgcc -o $$@

$$(PORT_OUT)/run/test-$(1)-%.txt: $$(PORT_OUT)/$(1)/test-%.elf ports/common/ports.sh
	@mkdir -p $$(@D)
	@QEMU_ARM="$$(QEMU_ARM)" QEMU_RV32="$$(QEMU_RV32)" $$(PORT_SH) run $(1) $$< $$@ $$(PORT_TIMEOUT)
$$(PORT_OUT)/run/bench-$(1)-%-fixed.txt: $$(PORT_OUT)/$(1)/bench-%.elf ports/common/ports.sh
	@mkdir -p $$(@D)
	@QEMU_ARM="$$(QEMU_ARM)" QEMU_RV32="$$(QEMU_RV32)" $$(PORT_SH) run $(1) $$< $$@ $$(PORT_BENCH_TIMEOUT)
$$(PORT_OUT)/run/bench-$(1)-%-float.txt: $$(PORT_OUT)/$(1)/benchf-%.elf ports/common/ports.sh
	@mkdir -p $$(@D)
	@QEMU_ARM="$$(QEMU_ARM)" QEMU_RV32="$$(QEMU_RV32)" $$(PORT_SH) run $(1) $$< $$@ $$(PORT_BENCH_TIMEOUT)

PORT_KEEP += $$(PORT_$(1)_FIXED_OBJS) $$(PORT_$(1)_FLOAT_OBJS) \
    $$(foreach p,$$(PORT_$(1)_PROFILES),$$(foreach v,test bench benchf,$$(PORT_OUT)/$(1)/$$v-$$p.elf))
PORT_TEST_RUNS += $$(foreach p,$$(PORT_$(1)_PROFILES),$(1)-$$p)
PORT_BENCH_RUNS += $$(foreach p,$$(PORT_$(1)_PROFILES),$(1)-$$p)
PORT_LIBS += $$(PORT_OUT)/$(1)/librad.a $$(PORT_OUT)/$(1)/librad_float.a
endef

PORT_TEST_RUNS := $(foreach p,$(PORT_HOST_PROFILES),host-$(p))
PORT_BENCH_RUNS :=
PORT_LIBS :=
PORT_KEEP :=
$(foreach t,$(PORT_TARGETS),$(eval $(call PORT_TARGET_RULES,$(t))))

# ---- the host: the same port test and core sources, stdio instead of semihosting ----
PORT_HOST_OBJS := $(PORT_LIB_SRCS:lib/%.c=$(PORT_OUT)/host/lib/fixed/%.o)
$(PORT_OUT)/host/lib/fixed/%.o: lib/%.c $(PORT_LIB_HDRS)
	@mkdir -p $(@D)
	$(CC) $(PORT_HOST_CFLAGS) $(PORT_FREE) -c $< -o $@
$(PORT_OUT)/host/test-%: $(PORT_TEST_SRC) ports/host/port_host.c $(PORT_HDRS) $(PORT_HOST_OBJS)
	$(CC) $(PORT_HOST_CFLAGS) $(PORT_OWN_WARN) -DPORT_PROFILE=$* $(PORT_TEST_SRC) ports/host/port_host.c \
	    $(PORT_HOST_OBJS) -o $@
$(PORT_OUT)/run/test-host-%.txt: $(PORT_OUT)/host/test-% ports/common/ports.sh
	@mkdir -p $(@D)
	@$(PORT_SH) run host $< $@ $(PORT_TIMEOUT)

# ---- reports -----------------------------------------------------------------------
PORT_TEST_OUTS := $(PORT_TEST_RUNS:%=$(PORT_OUT)/run/test-%.txt)
PORT_BENCH_OUTS := $(foreach r,$(PORT_BENCH_RUNS),$(PORT_OUT)/run/bench-$(r)-fixed.txt \
    $(PORT_OUT)/run/bench-$(r)-float.txt)

# Objects and programs are made by chained pattern rules: keep them (not intermediate).
PORT_KEEP += $(PORT_HOST_OBJS) $(PORT_HOST_PROFILES:%=$(PORT_OUT)/host/test-%)
.SECONDARY: $(PORT_KEEP)

.PHONY: ports port-test port-bench port-size port-nm port-guide
ports: port-nm port-test port-size

port-test: $(PORT_TEST_OUTS) port-guide
	@$(PORT_SH) test-report $(PORT_OUT) $(PORT_TEST_RUNS)

port-guide:
	@QEMU_ARM="$(QEMU_ARM)" sh ports/common/guide_check.sh $(PORT_OUT)/guide $(ARM_PREFIX) "$(PORT_CM_PLAT)"

port-bench: $(PORT_BENCH_OUTS)
	@$(PORT_SH) bench-report $(PORT_OUT) $(PORT_BENCH_RUNS)

port-size: $(PORT_LIBS) $(PORT_TEST_OUTS)
	@$(PORT_SH) size-report $(PORT_OUT) "$(ARM_PREFIX)size" "$(RV_PREFIX)size" $(PORT_TEST_RUNS)

port-nm: $(PORT_LIBS)
	@PORT_NM_STRICT=$(PORT_NM_STRICT) $(PORT_SH) nm-check $(PORT_OUT) \
	    "cortex-m0 $(ARM_PREFIX) $(PORT_cortex-m0_CPU)" \
	    "cortex-m3 $(ARM_PREFIX) $(PORT_cortex-m3_CPU)" \
	    "rv32 $(RV_PREFIX) $(PORT_rv32_CPU)"

.DEFAULT_GOAL := $(PORT_SAVED_GOAL)
