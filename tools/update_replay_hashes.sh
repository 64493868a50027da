#!/usr/bin/env bash
# Rewrites recordings/hashes.json: the final state hash of every shipped replay (a scene and the
# recordings replayed into it with `wedge replay`). Run it only after an intentional change to the
# physics or the input layer, and say so in the commit message: the test "shipped replays reproduce
# their recorded state hashes" then guards bit-identical replay.
# usage: tools/update_replay_hashes.sh [path/to/wedge]   (default build/apps/wedge/wedge)
set -euo pipefail
cd "$(dirname "$0")/.."
wedge="${1:-build/apps/wedge/wedge}"
# name | scene | recordings (space-separated)
replays=(
  "toy_table_grab|scenes/toy_table_4d.json|recordings/scripted/toy_table_grab.jsonl"
  "toy_table_tilt|scenes/toy_table_4d.json|recordings/scripted/toy_table_tilt.jsonl"
  "toy_table_grab_and_tilt|scenes/toy_table_4d.json|recordings/scripted/toy_table_grab.jsonl recordings/scripted/toy_table_tilt.jsonl"
  "dominoes_push|scenes/fig3_dominoes_4d.json|recordings/scripted/dominoes_push.jsonl"
  "chain_swing|scenes/chain_4d.json|recordings/scripted/chain_swing.jsonl"
  "quest2_toy_table|scenes/toy_table_4d.json|recordings/quest2/sample_movement.jsonl"
  "coremotion_toy_table|scenes/toy_table_4d.json|recordings/coremotion/kinetic_tremor.jsonl"
)
{
  echo "{"
  first=1
  for r in "${replays[@]}"; do
    IFS='|' read -r name scene recs <<< "$r"
    # shellcheck disable=SC2086
    hash=$("$wedge" replay "$scene" $recs --every 1000000 --hash | tail -1 | sed 's/.*"state_hash":"\([0-9a-f]*\)".*/\1/')
    [[ $first == 1 ]] || echo ","
    first=0
    list=$(printf '"%s", ' $recs)
    printf '  "%s": {"scene": "%s", "recordings": [%s], "state_hash": "%s"}' "$name" "$scene" "${list%, }" "$hash"
  done
  echo
  echo "}"
} > recordings/hashes.json.tmp
mv recordings/hashes.json.tmp recordings/hashes.json
cat recordings/hashes.json
