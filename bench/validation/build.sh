#!/bin/bash
# Build eleven more OTB sequences (a held-out validation set, disjoint from shared/data/otb and
# shared/data/extra), in the same OTB layout (<Name>/img/0001.jpg..., <Name>/groundtruth_rect.txt),
# from public repositories that ship them. First bring each repository below with the search tool's
# fetch (it answers with the snapshot's git folder, <MIRROR>/<owner>+<name>/repo); then
#   MIRROR=<that mirror folder> OUT=<a folder outside the repo> bash build.sh
# Each sequence is checked against the OTB annotation in $ANNO (exit 1 on a mismatch), and its
# image count must equal its number of ground-truth lines.
set -euo pipefail
M=${MIRROR:?set MIRROR to the folder that holds the fetched snapshots}
O=${OUT:?set OUT to the folder to write the sequences into}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
ANNO=${ANNO:-$ROOT/../shared/data/otb-results/anno}
[[ -d $ANNO ]] || { echo "no OTB annotation folder at $ANNO (set ANNO)"; exit 1; }
# name | repository | folder inside it | commit to read (HEAD when empty) | ground-truth file in
# that folder (groundtruth_rect.txt when empty)
SEQS="Boy|sseung0703/ADNet-tensorflow|OTB100/Boy|233575063105f2f7a7c18689cf187e82d66938ae|
Coke|apennisi/kfct|data/Coke|0dca73c621f86c70be2415339051d36b2850440f|
Couple|jwlim/tracker_benchmark|data/Couple|5e1029caba32decf425328f17f2b1a81b9713f66|
DragonBaby|hyseob/py-MDNet|datasets/OTB/DragonBaby|680fa4d58c427b8b647fa59dd9cd61a9fb7061f6|
Jogging-1|zhangzheng0131/Tracker_Benchmark_tb100|trackers/MUSTER/Jogging|61282dbf14495f7091163917def33a83046f7ca9|groundtruth_rect.1.txt
Jogging-2|zhangzheng0131/Tracker_Benchmark_tb100|trackers/MUSTER/Jogging|61282dbf14495f7091163917def33a83046f7ca9|groundtruth_rect.2.txt
MountainBike|apennisi/kfct|data/MountainBike|0dca73c621f86c70be2415339051d36b2850440f|
Skating1|mani-monaj/ColorTracker|sequences/Skating1|051e98da4cecb48901fd521935ca6e937e57c633|
Skiing|ybsong00/CREST-Release|Skiing|e331e6763e6b683b1696e1d61420e902bfce4ef7|
Tiger1|apennisi/kfct|data/Tiger1|0dca73c621f86c70be2415339051d36b2850440f|
Woman|l-sf/Track-trt|workspace/Woman|2db276e6c41d80b4b5f70c26a1cfc71c2862f8b4|"
mkdir -p "$O"
bad=0
while IFS='|' read -r name repo path commit gt; do
  g="$M/${repo/\//+}/repo"; [[ -d $g/.git ]] && g=$g/.git
  [[ -d $g ]] || { echo "$name: fetch $repo first (no snapshot at $g)"; bad=1; continue; }
  tmp=$(mktemp -d)
  # (git may warn about large files elsewhere in the snapshot that were not fetched: harmless)
  git --git-dir="$g" archive "${commit:-HEAD}" "$path/" 2>/dev/null | tar -x -C "$tmp" ||
    echo "$name: (git archive/tar reported an error; checking what came out)"
  src="$tmp/$path/${gt:-groundtruth_rect.txt}"
  if [[ ! -d $tmp/$path/img || ! -f $src ]]; then
    echo "$name: $path/img or its ground truth not in the snapshot of $repo"; bad=1; rm -rf "$tmp"; continue
  fi
  rm -rf "${O:?}/$name"; mkdir -p "$O/$name"
  cp -r "$tmp/$path/img" "$O/$name/img"
  cp "$src" "$O/$name/groundtruth_rect.txt"
  rm -rf "$tmp"; rm -f "$O/$name"/img/*.ini "$O/$name"/img/Thumbs.db
  n=$(ls "$O/$name/img" | wc -l); l=$(grep -c . "$O/$name/groundtruth_rect.txt")
  [[ $n == "$l" ]] || { echo "$name: $n images but $l ground-truth lines"; bad=1; }
  ref="$ANNO/$(ls "$ANNO" | grep -ix "$name.txt" | head -1)"
  [[ -f $ref ]] || { echo "$name: no OTB annotation to check against"; bad=1; }
  if [[ -f $ref ]] && ! python3 - "$O/$name/groundtruth_rect.txt" "$ref" <<'PY'
import re, sys
rows = [[float(v) for v in re.split(r"[,\s]+", l.strip())] for l in open(sys.argv[1]) if l.strip()]
ref = [[float(v) for v in re.split(r"[,\s]+", l.strip())] for l in open(sys.argv[2]) if l.strip()]
sys.exit(0 if rows == ref else 1)
PY
  then echo "$name: ground truth differs from the OTB annotation"; bad=1; fi
  echo "$name: $n frames, $l ground-truth lines"
done <<< "$SEQS"
exit $bad
