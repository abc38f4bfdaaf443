#!/bin/bash
# Run every study of SRC/configs with SRC's code (one worker, no cache) into OUT, with
# each run's time in OUT/times.txt; compare two such folders with compare_datasets.py.
# usage: benchmarks/run_all_configs.sh SRC_DIR OUT_DIR
SRC=$1; OUT=$2; mkdir -p "$OUT"
PY=${PYTHON:-python}
cd "$SRC" || exit 1
for f in configs/*.yaml; do
  n=$(basename "$f" .yaml)
  s=$(date +%s.%N)
  PYTHONPATH=$SRC $PY -m cablestudy run "$f" --out "$OUT" --workers 1 --no-cache --no-progress > "$OUT/$n.log" 2>&1
  echo "$n rc=$? $(echo "$(date +%s.%N) - $s" | bc)" >> "$OUT/times.txt"
done
