#!/usr/bin/env bash
# Goldens of tests/rne_post_test.cc: MuJoCo 3.5.1's cacc, cfrc_int, cfrc_ext,
# subtree_linvel, subtree_angmom and energy at the steps listed in tests/rne_post/cases.txt
# (tools/dump_rnepost.mjs). Controls of our own models come from ctrlgen.mjs (200 steps).
#
# Usage: tests/rne_post/make_goldens.sh   (SIMLAB_ORACLE: the oracle folder with
#        node_modules/mujoco; default ../shared/oracle beside the repository)
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
ORACLE="${SIMLAB_ORACLE:-$ROOT/../shared/oracle}"
cd "$ROOT"
node "$ORACLE/ctrlgen.mjs" tests/rne_post/models/equality_sites.xml --steps 200 \
  --out tests/rne_post/ctrl/equality_sites.csv
grep -v '^#' tests/rne_post/cases.txt | while read -r model key ctrl at xfrc; do
  args=(--key "$key" --ctrl "$ctrl" --at "$at")
  if [ "$xfrc" != "-" ]; then
    IFS=';' read -ra forces <<< "$xfrc"
    for f in "${forces[@]}"; do args+=(--xfrc "$f"); done
  fi
  out="tests/rne_post/goldens/$(basename "$model" .xml).json"
  node tools/dump_rnepost.mjs "$model" "${args[@]}" "$out"
  echo "$out"
done
