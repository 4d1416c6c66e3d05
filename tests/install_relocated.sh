#!/usr/bin/env bash
# Installs granvv to a temporary prefix, moves the prefix, and runs the installed binary from
# an unrelated folder end to end (a scene with its report): the binary must find its cases and
# report scripts relative to itself, never through the source or build tree.
# Usage: install_relocated.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/first" >/dev/null
mv "$tmp/first" "$tmp/moved"   # a relocated install must still work
bin="$tmp/moved/bin/granvv"
if grep -qF "$src" "$bin"; then
  echo "FAIL: the installed binary embeds the source path $src"; exit 1
fi
mkdir "$tmp/elsewhere" && cd "$tmp/elsewhere"
"$bin" list | grep -q '^single_mode ' || { echo "FAIL: granvv list misses single_mode"; exit 1; }
"$bin" run haff --out run --quiet --set hydro.cells=64
grep -q '"status": "ok"' run/summary.json || { echo "FAIL: haff status not ok"; exit 1; }
/usr/bin/python3 "$tmp/moved/share/granvv/scripts/check_report.py" run/report.html
"$bin" report run
# A data folder given explicitly must hold the data; a wrong one is a clear exit 2.
set +e
GRANVV_DATA_DIR="$tmp/nowhere" "$bin" list 2>err.txt
code=$?
set -e
[[ $code -eq 2 ]] && grep -q "GRANVV_DATA_DIR" err.txt || { echo "FAIL: bad GRANVV_DATA_DIR gave exit $code: $(cat err.txt)"; exit 1; }
GRANVV_DATA_DIR="$tmp/moved/share/granvv" "$bin" list | grep -q '^haff '
echo "installed binary ran haff with its report from $tmp/elsewhere"
