#!/usr/bin/env bash
# corrupt_mesh.sh PREPROCESS INSPECT SCENE WORKDIR
# A mesh file with one flipped byte, and one cut short, must be rejected by nmm-inspect with
# exit status 2 and one line naming the file.
set -u
pre=$1 insp=$2 scene=$3 dir=$4
mkdir -p "$dir"
good="$dir/good.nmm"
"$pre" "$scene" -o "$good" -q || { echo "preprocess failed"; exit 1; }
here=$(dirname "$0")
size=$(stat -c %s "$good")
fail=0
for off in 0 9 40 $((size / 3)) $((size / 2)) $((size - 1)); do
  bad="$dir/flip_$off.nmm"
  cp "$good" "$bad"
  byte=$(od -An -tu1 -j "$off" -N1 "$bad" | tr -d ' ')
  printf "$(printf '\\%03o' $(( (byte ^ 0x10) & 0xff )))" | dd of="$bad" bs=1 seek="$off" conv=notrunc status=none
  "$here/expect_status.sh" 2 "$bad" - -- "$insp" "$bad" --json || { echo "flip at $off"; fail=1; }
done
head -c $((size / 2)) "$good" > "$dir/short.nmm"
"$here/expect_status.sh" 2 "short.nmm" - -- "$insp" "$dir/short.nmm" || fail=1
"$here/expect_status.sh" 2 "missing.nmm" - -- "$insp" "$dir/missing.nmm" || fail=1
exit $fail
