#!/usr/bin/env bash
# Runs the example programs (examples/, built against the installed package in FOLDER) and checks what
# they print against what must happen:
#   grab_4d           the hand grabs the tesseract, lets go of it, and feels the strike on the ground as a
#                     pulse of amplitude 1 (it hits at more than pulse_full_speed, 2 m/s)
#   replay_recording  the shipped toy-table grab recording: at least one grab and one pulse, and the state
#                     hash that `wedge replay` gives for it (recordings/hashes.json)
#   tools/check_examples.sh FOLDER
set -euo pipefail
cd "$(dirname "$0")/.."
dir=$1
fail() { echo "check_examples: $*" >&2; exit 1; }

out=$("$dir/grab_4d")
echo "$out"
grep -q "hand 1 grabs body 1" <<<"$out" || fail "grab_4d: the right hand did not grab the tesseract"
grep -q "hand 1 lets go of body 1" <<<"$out" || fail "grab_4d: the right hand did not let go"
grep -q "pulse to hand 1: amplitude 1.00" <<<"$out" || fail "grab_4d: no full pulse for the strike"

out=$("$dir/replay_recording" scenes/toy_table_4d.json recordings/scripted/toy_table_grab.jsonl)
echo "$out" | tail -n 3
expected=$(grep '"toy_table_grab":' recordings/hashes.json | sed -E 's/.*"state_hash": "([0-9a-f]+)".*/\1/')
summary=$(tail -n 1 <<<"$out")
grep -Eq "replayed [0-9.]+ s: [1-9][0-9]* grabs, [1-9][0-9]* haptic pulses; state hash $expected\$" <<<"$summary" ||
  fail "replay_recording: expected grabs, pulses and state hash $expected, got: $summary"
echo "check_examples: passed"
