#!/usr/bin/env bash
# Reproduces data/default_vocabulary.bowgvoc, the vocabulary the demo, the
# launch files and the tests use out of the box (data/README.md):
#   1. renders a training sequence with the project's own pipe generator, with
#      its own seed (2) so that its wall texture (grain tile and marks) differs
#      from the demo sequence's (seed 1): the vocabulary never sees the test data;
#   2. trains a k=10, L=4 tree (~10k words) with bowg_train_vocabulary on GFTT
#      corners + oriented ORB, the features of config/pipe_gftt.yaml (and the
#      descriptor of config/pipe.yaml's multi-scale ORB, which uses it too).
# Needs the tools built (scripts/build.sh). Same tools + same options = the
# same file, bit for bit (the renderer and the trainer are seeded).
#   BOWG_WS=/tmp/ws ./scripts/make_default_vocabulary.sh [OUTPUT]
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${BOWG_WS:-$repo/.ws}"
out="${1:-$repo/data/default_vocabulary.bowgvoc}"
tools="$ws/devel/lib/bowg_ros"
for t in bowg_generate_pipe_sequence bowg_train_vocabulary; do
  if [ ! -x "$tools/$t" ]; then
    echo "make_default_vocabulary: $tools/$t not found; build first: BOWG_WS=$ws scripts/build.sh" >&2
    exit 1
  fi
done
export PATH="/usr/bin:$PATH"

work="$(mktemp -d "${TMPDIR:-/tmp}/bowg_vocabulary.XXXXXX")"
trap 'rm -rf "$work"' EXIT

# Two laps of the whole route (94 m of pipe, every pipe and junction, several
# rolls per place) at one frame every 20 cm: 473 frames, ~470 features each.
"$tools/bowg_generate_pipe_sequence" --images "$work/frames" --seed 2 --rate 1 --laps 2 \
  --marks-per-metre "${BOWG_VOC_MARKS:-8}" >"$work/generate.log" 2>&1 ||
  { cat "$work/generate.log" >&2; exit 1; }
tail -n 3 "$work/generate.log"

# GFTT corners, the detector of config/pipe_gftt.yaml (the trainer's defaults
# are FeatureOptions' defaults: GFTT, 500 corners, quality 0.01, min distance
# 10, size 31, oriented ORB), tree k=10 L=4, TF-IDF, trainer seed 2.
"$tools/bowg_train_vocabulary" --output "$work/voc.bowgvoc" --k 10 --L 4 --seed 2 --threads 2 \
  "$work/frames" 2>/dev/null | tail -n 2
mkdir -p "$(dirname "$out")"
mv "$work/voc.bowgvoc" "$out.tmp" && mv "$out.tmp" "$out"
echo "make_default_vocabulary: wrote $out ($(stat -c %s "$out") bytes)"
