#!/bin/sh
# Khronos's hello_xr (OpenGL, Xlib) over the replay runtime under Xvfb, playing RECORDING to its end:
# hello_xr leaves by itself when the session reaches EXITING. Passes when it exits cleanly, its log shows
# the session reaching EXITING, the haptics log has its grab vibrations (hello_xr vibrates a hand while its
# squeeze reads above 0.9), and the first submitted frame was written out as PNG (WEDGE_XR_FRAMES).
# usage: run_hello_xr.sh MANIFEST RECORDING WORKDIR VIDMODE_SHIM [validate]
#   VIDMODE_SHIM: preloaded so that hello_xr's window code survives Xvfb's lack of XF86VidMode
#   (vidmode_shim.cpp says why).
#   validate: with the Khronos core validation layer between the loader and the runtime; it must load and
#   report nothing (run_with_validation.sh has a canary showing it does report misuse).
set -u
manifest=$1
recording=$2
work=$3
shim=$4
validate=${5:-}
rm -rf "$work"
mkdir -p "$work/frames"
if [ "$validate" = validate ]; then
  export XR_ENABLE_API_LAYERS=XR_APILAYER_LUNARG_core_validation XR_CORE_VALIDATION_EXPORT_TYPE=text
  export XR_CORE_VALIDATION_FILE_NAME="$work/validation.txt"
fi
# hello_xr quits on a key press: its stdin is a FIFO held open read-write, which never delivers a key nor EOF.
mkfifo "$work/stdin"
exec 3<>"$work/stdin"
# A fresh Xvfb that picks its own free display and says which (-displayfd): two of these tests at once
# (ctest -j) never race for a display number, as xvfb-run -a can.
Xvfb -displayfd 4 -screen 0 1280x1024x24 -nolisten tcp 4>"$work/display" 2>/dev/null &
xvfb=$!
i=0
while [ ! -s "$work/display" ] && [ $i -lt 200 ]; do sleep 0.05; i=$((i + 1)); done
DISPLAY=":$(cat "$work/display")" timeout 300 env LD_PRELOAD="$shim" XR_RUNTIME_JSON="$manifest" \
  WEDGE_XR_REPLAY="$recording" WEDGE_XR_HAPTICS_LOG="$work/haptics.jsonl" WEDGE_XR_FRAMES="$work/frames" \
  WEDGE_XR_FRAMES_EVERY=90 hello_xr -g OpenGL <&3 > "$work/hello_xr.log" 2>&1
status=$?
kill $xvfb 2>/dev/null
exec 3<&-
cat "$work/hello_xr.log"
fail() {
  echo "FAIL: $1"
  exit 1
}
[ "$status" -eq 0 ] || fail "hello_xr exited with $status"
grep -q "XR_SESSION_STATE_EXITING" "$work/hello_xr.log" || fail "the session never reached EXITING"
applies=$(grep -c '"call":"apply"' "$work/haptics.jsonl" 2> /dev/null || true)
[ "${applies:-0}" -gt 0 ] || fail "no haptic apply lines in $work/haptics.jsonl"
right=$(grep -c '"call":"apply".*"hand":"/user/hand/right"' "$work/haptics.jsonl")
[ "$right" -eq "$applies" ] || fail "apply lines for a hand the recording never squeezes"
[ -s "$work/frames/frame_000000_eye0.png" ] || fail "frame 0 was not written out"
if [ "$validate" = validate ]; then
  grep -q "Core Validation output type: text" "$work/hello_xr.log" || fail "the core validation layer was not loaded"
  if [ -s "$work/validation.txt" ]; then
    cat "$work/validation.txt"
    fail "the core validation layer reported the above"
  fi
  echo "the core validation layer reported nothing"
fi
echo "PASS: hello_xr ran to EXITING; $applies haptic apply lines; frames written"
