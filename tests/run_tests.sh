#!/bin/sh
# Runs every CMocka test program given (cwd: the repository root), then prints one
# closing line for the whole suite: "tests: N passed, N failed, N skipped".
# RAD_TEST_WRAP (e.g. "valgrind -q --error-exitcode=99") runs each program under a tool.
# A shell script (NAME.sh) runs as `sh NAME.sh BUILDDIR`, unwrapped, and prints CMocka's
# "[       OK ] name" / "[  FAILED  ] name" lines for its checks, counted the same way.
set -u
builddir=$1; shift
passed=0; failed=0; skipped=0; bad=""
for t in "$@"; do
  log="$builddir/tests/$(basename "$t").log"
  case "$t" in
  *.sh) sh "$t" "$builddir" >"$log" 2>&1 ;;
  *) ${RAD_TEST_WRAP:-} "$t" >"$log" 2>&1 ;;
  esac
  rc=$?
  cat "$log"
  p=$(grep -c '^\[       OK \]' "$log")
  f=$(grep '^\[  FAILED  \] [a-z_]' "$log" | sort -u | wc -l)
  s=$(grep '^\[  SKIPPED \] [a-z_]' "$log" | sort -u | wc -l)
  passed=$((passed + p)); failed=$((failed + f)); skipped=$((skipped + s))
  if [ $rc -ne 0 ] && [ "$f" -eq 0 ]; then
    failed=$((failed + 1)); bad="$bad $(basename "$t")(exit $rc)"
  fi
done
[ -n "$bad" ] && echo "programs that failed outside a test:$bad"
echo "tests: $passed passed, $failed failed, $skipped skipped"
[ $failed -eq 0 ]
