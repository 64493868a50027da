#!/bin/sh
# Runs a command with the Khronos core validation layer (XR_APILAYER_LUNARG_core_validation) between the
# loader and the runtime, its findings written as text to REPORT (XR_CORE_VALIDATION_EXPORT_TYPE /
# XR_CORE_VALIDATION_FILE_NAME; the layer only creates the file when it has something to say).
#   clean:  passes when the command passes, the layer was loaded, and it reported nothing;
#   report: passes when the layer was loaded and reported a VALID_ERROR (the canary showing that "clean"
#           would see a report if there were one).
# usage: run_with_validation.sh clean|report REPORT COMMAND...
set -u
mode=$1
report=$2
shift 2
rm -f "$report"
XR_ENABLE_API_LAYERS=XR_APILAYER_LUNARG_core_validation XR_CORE_VALIDATION_EXPORT_TYPE=text \
  XR_CORE_VALIDATION_FILE_NAME="$report" "$@" > "$report.out" 2>&1
status=$?
cat "$report.out"
if ! grep -q "Core Validation output type: text" "$report.out"; then
  echo "FAIL: the core validation layer was not loaded"
  exit 1
fi
if [ "$mode" = report ]; then
  if [ -s "$report" ] && grep -q VALID_ERROR "$report"; then
    echo "PASS: the layer reported the misuse:"
    head -n 5 "$report"
    exit 0
  fi
  echo "FAIL: the layer reported nothing for a deliberate misuse"
  exit 1
fi
if [ -s "$report" ]; then
  echo "FAIL: the core validation layer reported:"
  cat "$report"
  exit 1
fi
[ "$status" -eq 0 ] || { echo "FAIL: the command failed ($status)"; exit 1; }
echo "PASS: the core validation layer reported nothing"
