#!/bin/sh
# SPDX-License-Identifier: MIT
# make install-lib as a user meets it: stage an install in a temporary prefix, build a
# program from outside the tree (tests/pkgconfig/outside.c) with
# `pkg-config --cflags --libs rad` (and rad_float), run it, check that a program
# compiled with another RAD_INDEX_BITS is refused by rad_init with an error, that
# DESTDIR stages the same files, that make uninstall removes every file, and that
# README.md's library example builds and gives its figure.
# Run by tests/run_tests.sh as `sh tests/pkgconfig_check.sh BUILDDIR` (cwd: the tree);
# prints a CMocka-style line per check. MAKE: the make to call (default make); CC and
# RAD_CFLAGS_EXTRA: the compiler and extra flags the library was built with (a
# sanitizer build's outside program needs the sanitizer's flags to link).
set -u
builddir=$1
make=${MAKE:-make}
cc="${CC:-cc} ${RAD_CFLAGS_EXTRA:-}"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/rad_pkgconfig.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
prefix=$tmp/usr
src=tests/pkgconfig/outside.c

. tests/check_lib.sh

# The value of KEY (first word) in FILE.
val() { awk -v k="$2" '$1 == k { print $2; exit }' "$1"; }

install_lib() {
    $make -s --no-print-directory install-lib BUILDDIR="$builddir" PREFIX="$prefix" &&
        test -f "$prefix/lib/librad.a" && test -f "$prefix/include/rad/rad.h" &&
        grep -q '^#define RAD_INDEX_BITS ' "$prefix/include/rad/rad_build.h" &&
        grep -q '^Libs: .*-lrad$' "$prefix/lib/pkgconfig/rad.pc"
}

# Builds and runs the outside program with the flags of package $1 (extra cflags $2);
# the plan must equal what the scene used, the solve must converge.
build_run() {
    pc=$1 extra=$2
    flags=$(PKG_CONFIG_PATH=$prefix/lib/pkgconfig pkg-config --cflags --libs "$pc") || return 1
    echo "pkg-config --cflags --libs $pc: $flags"
    $cc -std=c99 -Wall -Wextra -pedantic -Werror $extra "$src" $flags -o "$tmp/outside" || return 1
    "$tmp/outside" >"$tmp/out" 2>&1
    rc=$?
    cat "$tmp/out"
    test $rc -eq 0 || { echo "exit status $rc, expected 0"; return 1; }
    planned=$(grep '^planned ' "$tmp/out" | cut -d' ' -f2-)
    used=$(grep '^used ' "$tmp/out" | cut -d' ' -f2-)
    test -n "$planned" && test "$planned" = "$used" ||
        { echo "planned '$planned' against used '$used'"; return 1; }
    test "$(val "$tmp/out" version)" = \
        "$(PKG_CONFIG_PATH=$prefix/lib/pkgconfig pkg-config --modversion "$pc")" ||
        { echo "RAD_VERSION differs from the .pc's Version"; return 1; }
}

# The installed headers say 32 (or 16) bits; a program that insists on the other width
# must get RAD_ERR_ABI's message and exit 3, not crash.
abi_refused() {
    bits=$(awk '$1 == "#define" && $2 == "RAD_INDEX_BITS" { print $3 }' "$prefix/include/rad/rad_build.h")
    other=$((48 - bits))
    flags=$(PKG_CONFIG_PATH=$prefix/lib/pkgconfig pkg-config --cflags --libs rad) || return 1
    $cc -std=c99 -Wall -Wextra -pedantic -Werror -URAD_INDEX_BITS -DRAD_INDEX_BITS=$other "$src" $flags \
        -o "$tmp/outside_other" || return 1
    "$tmp/outside_other" >"$tmp/out" 2>&1
    rc=$?
    cat "$tmp/out"
    echo "library $bits-bit, program $other-bit: exit status $rc (expected 3)"
    test $rc -eq 3 && grep -q '^rad_init: program compiled with another rad.h layout' "$tmp/out"
}

# DESTDIR stages the same files under another root, recording PREFIX in the .pc.
destdir_same() {
    $make -s --no-print-directory install-lib BUILDDIR="$builddir" DESTDIR="$tmp/stage" \
        PREFIX=/opt/rad || return 1
    (cd "$tmp/stage/opt/rad" && find . -type f | sort) >"$tmp/staged"
    (cd "$prefix" && find . -type f | sort) >"$tmp/direct"
    diff "$tmp/direct" "$tmp/staged" && grep -qx 'prefix=/opt/rad' "$tmp/stage/opt/rad/lib/pkgconfig/rad.pc"
}

uninstall_all() {
    $make -s --no-print-directory uninstall BUILDDIR="$builddir" PREFIX="$prefix" || return 1
    left=$(find "$prefix" -type f)
    test -z "$left" || { echo "left after uninstall: $left"; return 1; }
}

# README.md's library example (its first ```c block, taken from the file so the two
# cannot drift) built with package $1's flags and run: a floor of reflectance 1/2 under
# a square lamp of emission 1 and its own size, 4 units above it. The lamp fills the
# hemi-cube's top face exactly (its half side equals its height), so the floor, one
# element, gets 1/2 times the closed-form form factor from the lamp's centre,
# (4 / pi) q atan q with q = 1 / sqrt 2: 0.27706. Only the delta form factor table's
# midpoint rule and its normalisation to a sum of one separate the two (measured
# -0.07% at res 64, both builds); 0.5% bounds that with room for either.
readme_example() {
    pc=$1
    awk '/^```c$/ { f = 1; next } /^```$/ { if (f) exit } f' README.md >"$tmp/example.c"
    test -s "$tmp/example.c" || { echo "README.md has no \`\`\`c block"; return 1; }
    flags=$(PKG_CONFIG_PATH=$prefix/lib/pkgconfig pkg-config --cflags --libs "$pc") || return 1
    $cc -std=c99 -Wall -Wextra -pedantic -Werror "$tmp/example.c" $flags -o "$tmp/example" || return 1
    "$tmp/example" >"$tmp/out" 2>&1
    rc=$?
    cat "$tmp/out"
    test $rc -eq 0 || { echo "exit status $rc, expected 0"; return 1; }
    awk '$1 == "floor" && $2 == "radiosity" { got = $3 }
         END {
             q = 1 / sqrt(2); want = 0.5 * 4 / atan2(0, -1) * q * atan2(q, 1)
             err = (got - want) / want
             printf "README example: %.5f against %.5f in closed form: %+.3f%% (bound 0.5%%)\n", got, want, 100 * err
             exit !(got != "" && err < 0.005 && err > -0.005)
         }' "$tmp/out"
}

# make lib needs neither libpng nor CMocka: its commands mention neither, nor tools/.
lib_alone() {
    $make -n --no-print-directory lib BUILDDIR="$tmp/fresh" >"$tmp/cmds" || return 1
    grep -c 'lib/.*\.c' "$tmp/cmds"
    ! grep -E 'png|cmocka|tools/' "$tmp/cmds"
}

if ! command -v pkg-config >/dev/null 2>&1; then
    echo "pkgconfig_check: pkg-config is not installed (apt-get install pkg-config)"
    echo "[  SKIPPED ] pkgconfig_install_lib"
    exit 0
fi
check pkgconfig_install_lib "make install-lib did not install the library, headers and rad.pc" install_lib
check pkgconfig_outside_fixed "the outside program built with pkg-config rad did not solve" build_run rad ""
check pkgconfig_outside_float "the outside program built with pkg-config rad_float did not solve" build_run rad_float ""
check pkgconfig_readme_example_fixed "README.md's library example did not build or give its figure" readme_example rad
check pkgconfig_readme_example_float "README.md's library example did not build or give its figure with rad_float" readme_example rad_float
check pkgconfig_abi_refused "a program with the other RAD_INDEX_BITS was not refused by rad_init" abi_refused
check pkgconfig_destdir "DESTDIR did not stage the same files" destdir_same
check pkgconfig_uninstall "make uninstall left files behind" uninstall_all
check pkgconfig_lib_alone "make lib needs more than the core" lib_alone
