#!/bin/sh
# SPDX-License-Identifier: MIT
# The closing table of `make check`: one line per stage from STATUSDIR (written by
# check_stage.sh), the fuzzers' executions and coverage from their logs, and the exit
# status: 0 only when every expected stage passed.
#
#   check_summary.sh STATUSDIR TOTAL_SECONDS STAGE...
set -u
dir=$1 total=$2
shift 2
bad=0
echo
echo "==== make check summary ===================================================="
printf '%-16s %-6s %8s  %s\n' stage result seconds log
for s in "$@"; do
  if [ -f "$dir/$s" ]; then
    read -r st secs log <"$dir/$s"
  else
    st=MISSING secs=- log=-
  fi
  [ "$st" = PASS ] || bad=$((bad + 1))
  printf '%-16s %-6s %8s  %s\n' "$s" "$st" "$secs" "$log"
  case $s in
    fuzz-*)
      if [ -f "$log" ]; then
        runs=$(grep 'stat::number_of_executed_units' "$log" | tail -n 1 | awk '{print $2}')
        cov=$(grep -E '^#[0-9]+.*cov: [0-9]+' "$log" | tail -n 1 | sed -E 's/.*cov: ([0-9]+) ft: ([0-9]+) corp: ([0-9]+).*/cov \1, features \2, corpus \3/')
        crash=$(grep -c -E '^==[0-9]+==ERROR|runtime error:|check failed|deadly signal|ERROR: libFuzzer' "$log")
        printf '%-16s        executions %s, %s, crash reports %s\n' "" "${runs:-?}" "${cov:-cov ?}" "$crash"
      fi
      ;;
  esac
done
echo "total wall time: ${total}s"
if [ $bad -ne 0 ]; then
  echo "make check: FAILED ($bad stage(s) not passing)"
  exit 1
fi
echo "make check: all stages passed"
