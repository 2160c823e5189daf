# SPDX-License-Identifier: MIT
# What the shell tests (tests/*_check.sh) share, sourced after they set $tmp, a folder
# of their own: check NAME WHAT COMMAND... runs COMMAND, shows its output indented and
# prints CMocka's "[       OK ] NAME" or, saying WHAT, "[  FAILED  ] NAME", which
# tests/run_tests.sh counts.
check() {
    name=$1 what=$2; shift 2
    echo "[ RUN      ] $name"
    if "$@" >"$tmp/log" 2>&1; then
        sed 's/^/    /' "$tmp/log"
        echo "[       OK ] $name"
    else
        sed 's/^/    /' "$tmp/log"
        echo "$name: $what"
        echo "[  FAILED  ] $name"
    fi
}
