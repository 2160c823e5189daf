#!/bin/sh
# SPDX-License-Identifier: MIT
# One stage of `make check` (tests/check.mk): runs COMMAND with its output in LOG,
# records "PASS|FAIL SECONDS LOG" in STATUSDIR/NAME and prints one line (and, on
# failure, the end of the log), so stages running in parallel do not interleave.
#
#   check_stage.sh STATUSDIR NAME LOG COMMAND [ARG...]
set -u
dir=$1 name=$2 log=$3
shift 3
mkdir -p "$dir" "$(dirname "$log")"
rm -f "$dir/$name"
echo "check: $name: started"
start=$(date +%s)
"$@" >"$log" 2>&1
rc=$?
secs=$(($(date +%s) - start))
if [ $rc -eq 0 ]; then st=PASS; else st=FAIL; fi
echo "$st $secs $log" >"$dir/$name"
echo "check: $name: $st in ${secs}s (log: $log)"
if [ $rc -ne 0 ]; then
  tail -n 60 "$log" | sed "s/^/  $name| /"
fi
exit $rc
