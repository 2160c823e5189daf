#!/bin/sh
# rad ports — the firmware guide's worked examples, built and run from ports/README.md's
# own text: the block "c firmware_rad.c" is the code, "sh guide-m0" and "sh guide-m3"
# the commands, run as written (RAD, STARTUP and LDFLAGS set to this tree and ports/'s
# startup and linker scripts) in OUTDIR/m0 and OUTDIR/m3; each program then runs under
# QEMU and must solve (status 0) within its board's RAM, in the shots the guide states
# ("solves to 2% unshot in N shots": the fixed build's shots are the same on every CPU).
# Run by `make port-test`.
#
#   guide_check.sh OUTDIR ARM_PREFIX "PLATFORM SOURCES"   (ports.mk's PORT_CM_PLAT)
set -u
out=$1
prefix=$2
plat=$3
rad=$(pwd)
guide=$rad/ports/README.md
ports_sh="sh $rad/ports/common/ports.sh"
failed=""

# The lines of the fenced block whose opening line is ```TAG.
block() { awk -v tag="$1" '$0 == "```" tag { on = 1; next } on && /^```$/ { exit } on' "$guide"; }
val() { awk -v k="$2" '$1 == k { print $2; exit }' "$1" 2>/dev/null; }

mkdir -p "$out"
block "c firmware_rad.c" >"$out/firmware_rad.c"
[ -s "$out/firmware_rad.c" ] || { echo "guide-check: no 'c firmware_rad.c' block in $guide"; exit 1; }
md=$out/guide-check.md
{
    echo "| example | target | shots | instructions | stack | RAM used | RAM | status |"
    echo "| --- | --- | ---: | ---: | ---: | ---: | ---: | --- |"
} >"$md"
# The shots the guide states, in the order of its examples (m0, then m3).
stated() { sed -n 's/.*solves to 2% unshot in \([0-9]*\) shots.*/\1/p' "$guide" | sed -n "$1p"; }
n=0
for ex in m0 m3; do
    n=$((n + 1))
    case $ex in
    m0) target=cortex-m0 cpu="-mcpu=cortex-m0 -mthumb -mfloat-abi=soft" hz=16000000 ram=16384 ;;
    *) target=cortex-m3 cpu="-mcpu=cortex-m3 -mthumb -mfloat-abi=soft" hz=25000000 ram=65536 ;;
    esac
    d=$out/$ex
    rm -rf "$d"
    mkdir -p "$d"
    cp "$out/firmware_rad.c" "$d/"
    block "sh guide-$ex" >"$d/build.sh"
    why=""
    if [ ! -s "$d/build.sh" ]; then
        why="no 'sh guide-$ex' block"
    else
        # The board side the guide leaves to the reader: ports/' startup and a main.
        objs=""
        for src in $plat ports/common/guide_main.c; do
            o=$(basename "$src" .c).o
            objs="$objs $o"
            "${prefix}gcc" -std=c99 -Os $cpu -ffreestanding -Wall -Wextra -Werror \
                -DPORT_TARGET_NAME=$target -DPORT_CPU_HZ=$hz -I"$rad/ports/common" \
                -c "$rad/$src" -o "$d/$o" || why="startup $src did not build"
        done
        echo "  GUIDE $ex: the guide's commands (log: $d/build.log)"
        [ -n "$why" ] || (cd "$d" && env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL RAD="$rad" \
            STARTUP="$objs" \
            LDFLAGS="-L$rad/ports/common -T$rad/ports/$target/link.ld" \
            sh -ex build.sh) >"$d/build.log" 2>&1 || why="the guide's commands failed"
    fi
    if [ -z "$why" ]; then
        $ports_sh run $target "$d/firmware-$ex.elf" "$d/run.txt" 60
        st=$(val "$d/run.txt" status) used=$(( $(val "$d/run.txt" static) + $(val "$d/run.txt" stack) ))
        if [ "$st" != 0 ]; then why="exit status $st"
        elif [ "$used" -gt $ram ]; then why="$used bytes of RAM used, $ram on the board"
        elif [ "$(val "$d/run.txt" result)" != "$(stated $n)" ]; then
            why="$(val "$d/run.txt" result) shots, the guide says $(stated $n): update ports/README.md"
        fi
    fi
    f=$d/run.txt
    echo "| $ex | $target | $(val "$f" result) | $(val "$f" instructions) | $(val "$f" stack) | ${used:-} | $ram | ${why:-PASS} |" >>"$md"
    if [ -n "$why" ]; then
        failed="$failed $ex"
        echo "guide-check: $ex: $why"
        [ -f "$d/build.log" ] && tail -20 "$d/build.log"
        [ -f "$f" ] && cat "$f"
    fi
    used=""
done
echo
cat "$md"
[ -z "$failed" ] || { echo "guide-check: FAIL:$failed"; exit 1; }
echo "guide-check: both worked examples of ports/README.md build, run and fit"
