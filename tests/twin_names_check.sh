#!/bin/sh
# The float twin's names (tools/host/float_names.h, scene_float.h) are generated from the
# host glue's headers by tools/host/twin_names.py: fails when a header's declarations
# changed and the files were not generated again. CMocka-style lines for run_tests.sh.
if python3 tools/host/twin_names.py --check; then
  echo "[       OK ] twin_names_generated"
else
  echo "[  FAILED  ] twin_names_generated"
  exit 1
fi
