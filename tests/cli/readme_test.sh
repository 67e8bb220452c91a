#!/usr/bin/env bash
# The README's commands run as written. Every ```sh block of README.md is run, in order, in one
# bash (set -euo pipefail) in a scratch folder holding samples/ and build/bin/ (links to the
# checkout's samples and the built executables), as a user runs them from the repository root;
# each block must exit 0 and leave the files its `<!-- readme_test: outputs FILE... -->` line
# promises. A block after a `<!-- readme_test: skip REASON -->` line is not run: the two commands
# (scripts/demo.sh, scripts/test.sh) install, build and run for minutes; for them the test checks
# that the scripts exist and that .ci/run calls scripts/test.sh. Also: the README is at most 150
# lines and its relative links and picture exist.
# usage: readme_test.sh QF_BAKE SOURCE_DIR
set -u
bake=$1 src=$2
source "$(dirname "$0")/test_lib.sh"
readme=$src/README.md

lines=$(wc -l <"$readme")
[[ $lines -le 150 ]] && ok || bad "README.md has $lines lines (at most 150)"

# Relative links and images: [text](path) and ![alt](path), without #anchors.
while read -r target; do
  [[ -e $src/$target ]] && ok || bad "README.md links $target, which does not exist"
done < <(grep -o '](\([^)#:]*\)[)#]' "$readme" | sed 's/^](//; s/[)#]$//' | sort -u)

# The blocks: bash scripts under $work/blocks, their promised outputs, the skipped ones.
mkdir -p "$work/blocks"
/usr/bin/python3 - "$readme" "$work/blocks" <<'PY' || { bad "README.md's sh blocks cannot be read"; finish readme; exit 1; }
import re, sys
text, out = open(sys.argv[1]).read(), sys.argv[2]
n = 0
for m in re.finditer(r"^```sh\n(.*?)^```\n", text, re.S | re.M):
    before = text[:m.start()].rstrip("\n").split("\n")[-1]
    after = text[m.end():].split("\n")[0]
    skip = re.match(r"<!-- readme_test: skip (.+) -->$", before)
    outputs = re.match(r"<!-- readme_test: outputs (.+) -->$", after)
    n += 1
    kind = "skip" if skip else "run"
    open(f"{out}/{n:02d}.{kind}", "w").write(m.group(1))
    open(f"{out}/{n:02d}.outputs", "w").write("\n".join(outputs.group(1).split()) + "\n" if outputs and not skip else "")
if n == 0:
    sys.exit("no sh block")
PY
runs=("$work"/blocks/*.run) skips=("$work"/blocks/*.skip)
[[ -e ${runs[0]} ]] && ok || bad "README.md has no sh block to run"
[[ -e ${skips[0]} ]] || skips=()
for f in "${runs[@]}"; do
  [[ -s ${f%.run}.outputs ]] && ok || bad "README.md's sh block $(basename "${f%.run}") promises no outputs (<!-- readme_test: outputs ... -->)"
done

# The skipped blocks: the two commands exist, and CI runs the test command.
for f in "${skips[@]}"; do
  while read -r cmd _; do
    [[ -z $cmd || $cmd == \#* ]] && continue
    [[ -x $src/$cmd ]] && ok || bad "README.md's command $cmd is not an executable in the repository"
  done <"$f"
done
grep -q '^scripts/demo.sh' "$work"/blocks/*.skip 2>/dev/null && grep -q '^scripts/test.sh' "$work"/blocks/*.skip 2>/dev/null &&
  ok || bad "README.md does not show the two commands (scripts/demo.sh, scripts/test.sh)"
grep -q 'scripts/test.sh' "$src/.ci/run" && ok || bad ".ci/run does not call scripts/test.sh"

# The run blocks, in order, in one shell, from a scratch "repository root".
root=$work/root
mkdir -p "$root/build"
ln -s "$src/samples" "$root/samples"
ln -s "$(cd "$(dirname "$bake")" && pwd)" "$root/build/bin"
{
  echo 'set -euo pipefail'
  for f in "${runs[@]}"; do
    b=$(basename "${f%.run}")
    echo "echo '== README block $b' >&2"
    cat "$f"
    echo "while read -r out; do [[ -z \$out || -s \$out ]] || { echo \"README block $b: \$out was not made\" >&2; exit 99; }; done <'${f%.run}.outputs'"
  done
  echo "echo '== README blocks done' >&2"
} >"$work/readme.sh"
start=$SECONDS
(cd "$root" && env -u QF_SHARDS bash "$work/readme.sh") >"$work/log" 2>&1
rc=$?
if [[ $rc -eq 0 ]] && grep -q '^== README blocks done' "$work/log"; then
  ok
else
  bad "the README's commands failed (exit $rc) in $(grep '^== README block' "$work/log" | tail -1 | sed 's/^== //'):"
  tail -n 25 "$work/log"
fi
echo "readme: ${#runs[@]} blocks run in $((SECONDS - start)) s"
finish readme
