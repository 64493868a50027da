#!/usr/bin/env bash
# Rewrites scenes/hashes.json: the state hash of every shipped scene after 600 steps.
# Run it only after an intentional change to the physics, and say so in the commit message: the test
# "shipped scenes reproduce their recorded state hashes" then guards bit-identical replay.
# usage: tools/update_scene_hashes.sh [path/to/wedge]   (default build/apps/wedge/wedge)
set -euo pipefail
cd "$(dirname "$0")/.."
wedge="${1:-build/apps/wedge/wedge}"
steps=600
{
  echo "{"
  first=1
  for f in scenes/*.json; do
    name=$(basename "$f")
    [[ "$name" == hashes.json || "$name" == inertia_*.json ]] && continue
    hash=$("$wedge" simulate "$f" --steps "$steps" --every "$steps" --hash | tail -1 | sed 's/.*"state_hash":"\([0-9a-f]*\)".*/\1/')
    [[ $first == 1 ]] || echo ","
    first=0
    printf '  "%s": {"steps": %d, "state_hash": "%s"}' "$name" "$steps" "$hash"
  done
  echo
  echo "}"
} > scenes/hashes.json.tmp
mv scenes/hashes.json.tmp scenes/hashes.json
cat scenes/hashes.json
