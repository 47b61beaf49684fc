#!/usr/bin/env bash
# Regenerate the per-pair contact goldens from MuJoCo itself (the oracle):
# every models/NAME.xml gets goldens/NAME.json, the contacts after mj_forward.
# A model whose first line is a comment with "key=K" is reset to keyframe K first.
#
#   tests/collision_pairs/make_goldens.sh            (from the repository root)
#   tests/collision_pairs/make_goldens.sh NAME ...   (only these models)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
mkdir -p "$here/goldens"

names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  for f in "$here"/models/*.xml; do names+=("$(basename "$f" .xml)"); done
fi
for name in "${names[@]}"; do
  model="$here/models/$name.xml"
  key=$(head -n 1 "$model" | sed -n 's/.*key=\([0-9][0-9]*\).*/\1/p')
  args=()
  if [ -n "$key" ]; then args=(--key "$key"); fi
  node "$root/tools/dump_contacts.mjs" "$model" "${args[@]}" "$here/goldens/$name.json"
  echo "$name: $(grep -o '"ncon":[0-9]*' "$here/goldens/$name.json")"
done
