#!/bin/sh
# SPDX-License-Identifier: MIT
# rad ports — the shell side of ports/ports.mk: run a port test under QEMU, and print
# (and write as Markdown) the port-test, port-bench and port-size tables; port-nm.
#
#   ports.sh run TARGET PROGRAM OUT TIMEOUT
#   ports.sh test-report OUTDIR RUN...        RUN = TARGET-PROFILE (host-small, rv32-medium...)
#   ports.sh bench-report OUTDIR RUN...
#   ports.sh size-report OUTDIR ARM_SIZE RV_SIZE RUN...
#   ports.sh nm-check OUTDIR "TARGET PREFIX CPUFLAGS..."...
set -u

QEMU_ARM=${QEMU_ARM:-qemu-system-arm}
QEMU_RV32=${QEMU_RV32:-qemu-system-riscv32}

# Value of KEY (first word of a line) in FILE.
val() { awk -v k="$2" '$1 == k { print $2; exit }' "$1" 2>/dev/null; }

# ---- run -----------------------------------------------------------------------------
# Runs PROGRAM for TARGET under `timeout`; OUT gets its output and a last line
# "status N" (the program's exit status through semihosting; 124: timed out).
run() {
    target=$1 prog=$2 out=$3 tmo=$4
    opts="-display none -monitor none -serial none -chardev stdio,id=semi
          -semihosting-config enable=on,target=native,chardev=semi
          -icount shift=0,align=off,sleep=off -kernel $prog"
    case $target in
    host) set -- "$prog" ;;
    cortex-m0) set -- "$QEMU_ARM" -M microbit $opts ;;
    cortex-m3) set -- "$QEMU_ARM" -M mps2-an385 $opts ;;
    rv32) set -- "$QEMU_RV32" -M virt -bios none $opts ;;
    *) echo "ports.sh: unknown target $target" >&2; exit 2 ;;
    esac
    echo "  RUN   $target $prog"
    timeout "$tmo" "$@" </dev/null >"$out.tmp" 2>&1
    st=$?
    echo "status $st" >>"$out.tmp"
    mv "$out.tmp" "$out"
}

# ---- port-test -----------------------------------------------------------------------
# Every target's results must equal the host's for the same profile.
test_report() {
    dir=$1; shift
    keys="elements patches vertices shots unshot saturations checksum"
    md=$dir/port-test.md
    failed=""
    {
        echo "| target | profile | elements | patches | shots | unshot (Q16.16) | checksum | instructions | RAM (bytes) | result |"
        echo "| --- | --- | ---: | ---: | ---: | ---: | --- | ---: | ---: | --- |"
    } >"$md"
    for run in "$@"; do
        t=${run%-*} p=${run##*-}
        f=$dir/run/test-$run.txt ref=$dir/run/test-host-$p.txt
        st=$(val "$f" status)
        result=PASS why=""
        if [ "$st" != 0 ]; then
            result=FAIL why="exit status ${st:-none}"
        elif ! grep -q '^done' "$f"; then
            result=FAIL why="incomplete output"
        elif [ "$t" = host ]; then
            result="reference"
        elif [ "$(val "$ref" status)" != 0 ]; then
            result=FAIL why="no host reference"
        else
            for k in $keys; do
                a=$(val "$f" "$k") b=$(val "$ref" "$k")
                if [ -z "$a" ] || [ "$a" != "$b" ]; then
                    result=FAIL why="$why $k $a (host $b)"
                fi
            done
        fi
        [ "$result" = FAIL ] && failed="$failed $run"
        ins=$(val "$f" instructions) ram=$(val "$f" ram)
        echo "| $t | $p | $(val "$f" elements) | $(val "$f" patches) | $(val "$f" shots) | $(val "$f" unshot) | $(val "$f" checksum) | ${ins:--} | ${ram:--} | $result${why:+ ($why)} |" >>"$md"
    done
    echo
    cat "$md"
    echo
    if [ -n "$failed" ]; then
        for run in $failed; do
            echo "---- output of $run:"
            cat "$dir/run/test-$run.txt"
            rm -f "$dir/run/test-$run.txt" # run it again next time
        done
        echo "port-test: FAIL:$failed"
        return 1
    fi
    echo "port-test: PASS: every target's elements, shots, unshot and checksum equal the host's ($md)"
}

# ---- port-bench ----------------------------------------------------------------------
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (a > 0 && b > 0) printf "%.1fx", b / a; else printf "-" }'; }

# "BAND SHOT HEMICUBE" of resolution RES in FILE (HEMICUBE "-" when not measured), or
# "skipped".
shot() {
    awk -v r="$2" '$1 == "bench_res" && $2 == r {
        if ($3 == "skipped") print "skipped"; else print $4, $6, ($8 == "" ? "-" : $8); exit }' "$1"
}

bench_report() {
    dir=$1; shift
    runs=$* # "set --" below reuses the positional parameters
    md=$dir/port-bench.md
    failed=""
    {
        echo "# rad port benchmark: instructions under QEMU"
        echo
        echo "Deterministic counts under \`-icount shift=0\` (one instruction per virtual ns):"
        echo "SysTick on Cortex-M (1 tick = 62.5 instructions on the micro:bit, 40 on mps2-an385,"
        echo "so +-1 tick), minstret on RV32 (exact). Fixed: the product (Q16.16 integer). Float:"
        echo "the float twin in soft float (libgcc), same scene and configuration. One shot ="
        echo "\`rad_shoot(s, 1, 0)\` from a fresh scene (the light shoots: hemi-cube, rasterizer,"
        echo "distribution). One hemi-cube = \`rad_form_factors\` for the same patch (clear, render"
        echo "every element into the item buffer, accumulate: no distribution; the core turns"
        echo "the hemi-cube per patch there and per shot in \`rad_shoot\`, so the two are not"
        echo "subtracted). Whole solve = \`rad_shoot\` until 2% unshot."
        echo "Band = hemi-cube rows rendered per pass (0: all five faces at once)."
        echo
        echo "| target | profile | measurement | band | fixed | float twin | float/fixed |"
        echo "| --- | --- | --- | ---: | ---: | ---: | ---: |"
    } >"$md"
    notes=""
    for run in $runs; do
        t=${run%-*} p=${run##*-}
        fx=$dir/run/bench-$run-fixed.txt fl=$dir/run/bench-$run-float.txt
        if [ "$(val "$fx" status)" != 0 ] || [ "$(val "$fl" status)" != 0 ]; then
            echo "| $t | $p | FAILED (status fixed $(val "$fx" status), float $(val "$fl" status)) | | | | |" >>"$md"
            failed="$failed $run"
            continue
        fi
        for r in 16 32 64; do
            a=$(shot "$fx" $r) b=$(shot "$fl" $r)
            if [ "$a" = skipped ] || [ -z "$a" ]; then
                echo "| $t | $p | one shot, res $r | - | does not fit | does not fit | - |" >>"$md"
                notes="$notes
- $t: res $r does not fit its RAM ($(val "$fx" static) bytes static at res $(val "$fx" res); the res-$r delta form factor table alone is $((r * r * 2)) bytes)."
                continue
            fi
            set -- $a; band=$1 na=$2 ha=$3
            set -- $b; nb=$2 hb=$3
            echo "| $t | $p | one shot, res $r | $band | $na | $nb | $(ratio "$na" "$nb") |" >>"$md"
            if [ "$ha" != - ] && [ "$hb" != - ]; then
                echo "| $t | $p | one hemi-cube, res $r (rad_form_factors) | $band | $ha | $hb | $(ratio "$ha" "$hb") |" >>"$md"
            fi
        done
        na=$(val "$fx" instructions) nb=$(val "$fl" instructions)
        echo "| $t | $p | whole solve, res $(val "$fx" res), $(val "$fx" elements) elements, $(val "$fx" shots)/$(val "$fl" shots) shots | $(val "$fx" band) | $na | $nb | $(ratio "$na" "$nb") |" >>"$md"
    done
    # The float twin is not required to agree across CPUs; say whether it does.
    for p in small medium; do
        sums=""
        for run in $runs; do
            [ "${run##*-}" = "$p" ] || continue
            c=$(val "$dir/run/bench-$run-float.txt" checksum)
            [ -n "$c" ] && sums="$sums ${run%-*}=$c"
        done
        [ -z "$sums" ] && continue
        n=$(echo "$sums" | tr ' ' '\n' | sed -n 's/.*=//p' | sort -u | wc -l)
        if [ "$n" = 1 ]; then same="identical on every target"; else same="differ between targets"; fi
        notes="$notes
- Float twin checksums, $p profile ($same):$sums"
    done
    if [ -n "$notes" ]; then
        printf '\nNotes:\n%s\n' "$notes" >>"$md"
    fi
    echo
    cat "$md"
    echo
    if [ -n "$failed" ]; then
        for run in $failed; do
            for v in fixed float; do
                echo "---- output of $run ($v):"
                cat "$dir/run/bench-$run-$v.txt"
                rm -f "$dir/run/bench-$run-$v.txt"
            done
        done
        echo "port-bench: FAIL:$failed"
        return 1
    fi
    echo "port-bench: written to $md"
}

# ---- port-size -----------------------------------------------------------------------
size_report() {
    dir=$1 arm_size=$2 rv_size=$3; shift 3
    runs=$* # "set --" below reuses the positional parameters
    md=$dir/port-size.md
    {
        echo "# rad port sizes"
        echo
        echo "The core alone (lib/*.c at -Os, \`size -t\` of the archive), fixed and float twin:"
        echo
        echo "| target | .text | .data | .bss | float twin .text |"
        echo "| --- | ---: | ---: | ---: | ---: |"
    } >"$md"
    for t in cortex-m0 cortex-m3 rv32; do
        case $t in rv32) sz=$rv_size ;; *) sz=$arm_size ;; esac
        set -- $("$sz" -t "$dir/$t/librad.a" | tail -n 1)
        text=$1 data=$2 bss=$3
        set -- $("$sz" -t "$dir/$t/librad_float.a" | tail -n 1)
        echo "| $t | $text | $data | $bss | $1 |" >>"$md"
    done
    {
        echo
        echo "RAM each port test used: the pools and the work buffer (static arrays sized for"
        echo "the scene), all .data + .bss, and the deepest stack (painted at boot, measured at"
        echo "exit). Flash = the port test's whole .text (core, test, startup, libgcc helpers)."
        echo
        echo "| target | profile | elements | res | band | pools | work buffer | .data+.bss | stack | RAM used | RAM budget | flash |"
        echo "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    } >>"$md"
    for run in $runs; do
        t=${run%-*} p=${run##*-}
        [ "$t" = host ] && continue
        f=$dir/run/test-$run.txt
        if [ "$(val "$f" status)" != 0 ]; then
            echo "| $t | $p | failed (status $(val "$f" status)): see make port-test | | | | | | | | | |" >>"$md"
            continue
        fi
        case $t in cortex-m0) budget=16384 ;; *) budget=65536 ;; esac
        case $t in rv32) sz=$rv_size ;; *) sz=$arm_size ;; esac
        flash=$("$sz" "$dir/$t/test-$p.elf" | awk 'NR == 2 { print $1 }')
        echo "| $t | $p | $(val "$f" elements) | $(val "$f" res) | $(val "$f" band) | $(val "$f" pools) | $(val "$f" work) | $(val "$f" static) | $(val "$f" stack) | $(val "$f" ram) | $budget | $flash |" >>"$md"
    done
    echo
    cat "$md"
    echo
    echo "port-size: written to $md"
}

# ---- port-nm -------------------------------------------------------------------------
# What the cross-built core (fixed and float) needs from outside: only what libgcc
# defines, plus (unless PORT_NM_STRICT=1) GCC's freestanding four.
nm_check() {
    dir=$1; shift
    bad=0
    for spec in "$@"; do
        set -- $spec
        t=$1 prefix=$2; shift 2
        libgcc=$("${prefix}gcc" "$@" -print-libgcc-file-name)
        helpers=$("${prefix}nm" --defined-only "$libgcc" 2>/dev/null | awk 'NF == 3 { print $3 }' | sort -u)
        for lib in "$dir/$t/librad.a" "$dir/$t/librad_float.a"; do
            defined=$("${prefix}nm" --defined-only "$lib" | awk 'NF == 3 { print $3 }' | sort -u)
            undef=$("${prefix}nm" -u "$lib" | awk '$1 == "U" { print $2 }' | sort -u)
            rt="" mem="" other=""
            for s in $undef; do
                if echo "$defined" | grep -qx "$s"; then continue; fi
                if echo "$helpers" | grep -qx "$s"; then rt="$rt $s"; continue; fi
                case $s in
                memcpy | memmove | memset | memcmp)
                    if [ "${PORT_NM_STRICT:-0}" = 1 ]; then other="$other $s"; else mem="$mem $s"; fi ;;
                *) other="$other $s" ;;
                esac
            done
            if [ -n "$other" ]; then
                echo "port-nm: FAIL: $lib needs from outside the core:$other"
                bad=1
            else
                echo "port-nm: ok: $lib: compiler runtime:${rt:- none}${mem:+; freestanding (GCC's contract, provided by ports/common/port_libc.c):$mem}"
            fi
        done
    done
    return $bad
}

cmd=${1:-}
[ $# -gt 0 ] && shift
case $cmd in
run) run "$@" ;;
test-report) test_report "$@" ;;
bench-report) bench_report "$@" ;;
size-report) size_report "$@" ;;
nm-check) nm_check "$@" ;;
*) echo "usage: ports.sh run|test-report|bench-report|size-report|nm-check ..." >&2; exit 2 ;;
esac
