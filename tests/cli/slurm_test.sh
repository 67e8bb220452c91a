#!/usr/bin/env bash
# The farm examples of docs/farm.md, run. Without a cluster: the page shows scripts/slurm/*.sbatch as they
# are; its Kubernetes indexed Job turns JOB_COMPLETION_INDEX 0..N-1 into --shard 1/N..N/N (the YAML
# parsed, its args expanded as the kubelet does, qf-bake's --dry-run taking each shard once). Then a
# one-node Slurm cluster started here (munged, slurmctld, slurmd in a scratch folder; stopped on every
# exit): scripts/slurm/bake-array.sbatch as an --array=1-3 job on 4 CGAL models with the merge after
# it (--dependency=afterany) writes the same bytes as an unsharded batch and a merged report of every
# asset; a task cancelled mid-bake (scancel) fails the merge with the missing shard named, and
# resubmitted alone (QF_SHARDS=3 sbatch --array=1) finishes the job: same files, no staging left.
# Exits 77 (skipped) without the models, when not root, or when the daemons cannot start here.
# usage: slurm_test.sh QF_BAKE SOURCE_DIR
set -u
bake=$1 src=$2
source "$(dirname "$0")/test_lib.sh"
# Nothing from a surrounding job or shell steers ours (sbatch reads SBATCH_* as options).
unset QF_SHARDS $(compgen -e | grep -E '^(SLURM|SBATCH|SALLOC|SRUN|SQUEUE|SINFO|SCONTROL)_')
schemas=$src/schemas slurm_dir=$src/scripts/slurm
listing() { (cd "$1" && find . -path ./batch-report\* -prune -o -type f ! -name report.json -print0 | sort -z | xargs -0 sha256sum); }

# Cleanup on every exit: cancel our jobs, stop the daemons, then anything still holding the scratch
# folder (a job's slurmstepd or bake), then test_lib's own cleanup.
daemons=() watchdog=""
held() {  # PIDs (not this shell) whose working folder or an open file is under $work
  local p
  for p in /proc/[0-9]*; do
    [[ ${p#/proc/} == "$$" ]] && continue
    { readlink "$p/cwd"; ls -l "$p/fd" 2>/dev/null; } 2>/dev/null | grep -q -- "$work/" && echo "${p#/proc/}"
  done
}
stop_cluster() {
  cd /
  [[ -n $watchdog ]] && kill -9 "$watchdog" 2>/dev/null   # it ignores TERM
  if [[ ${#daemons[@]} -gt 0 ]]; then
    if kill -0 "${daemons[0]}" 2>/dev/null; then   # slurmctld: our jobs go first
      scancel --quiet --user="$(id -un)" 2>/dev/null
      local end=$((SECONDS + 10))
      while [[ -n $(squeue -h -o %i 2>/dev/null) ]] && ((SECONDS < end)); do sleep 0.5; done
    fi
    kill "${daemons[@]}" 2>/dev/null
    for _ in $(seq 20); do kill -0 "${daemons[@]}" 2>/dev/null || break; sleep 0.25; done
    kill -9 "${daemons[@]}" 2>/dev/null
  fi
  [[ -f $work/munge/munged.pid ]] && kill "$(cat "$work/munge/munged.pid")" 2>/dev/null
  local left; left=$(held)
  [[ -n $left ]] && kill -9 $left 2>/dev/null
  daemons=() watchdog=""
}
trap 'stop_cluster; pkill -9 -f "$work/" 2>/dev/null; rm -rf "$work"' EXIT
trap 'exit 1' INT TERM
skip() {  # the checks so far count; skip only if they passed
  echo "slurm: the cluster part is skipped: $*"
  [[ $fail -eq 0 ]] || { finish slurm; exit 1; }
  exit 77
}

# --- 1. docs/farm.md shows the job scripts as they are ---
for f in bake-array.sbatch merge-reports.sbatch; do
  /usr/bin/python3 -c 'import sys
page, script = open(sys.argv[1]).read(), open(sys.argv[2]).read()
sys.exit(0 if "```sh\n" + script + "```" in page else 1)' "$src/docs/farm.md" "$slurm_dir/$f" &&
    ok || bad "docs/farm.md does not show scripts/slurm/$f verbatim (in a sh block)"
done
# a task resubmitted alone without QF_SHARDS refuses to guess N
SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_TASK_MIN=2 SLURM_ARRAY_TASK_MAX=2 SLURM_ARRAY_TASK_COUNT=1 \
  bash "$slurm_dir/bake-array.sbatch" x.json out 2>"$work/err"; rc=$?
[[ $rc -eq 2 ]] && grep -q "QF_SHARDS" "$work/err" && ok || bad "bake-array.sbatch --array=2 alone: exit $rc: $(cat "$work/err")"

# --- 2. the Kubernetes indexed Job: index 0..N-1 (0-based) -> --shard 1/N..N/N (1-based) ---
mkdir -p "$work/stub" "$work/k8s"
printf '#!/bin/sh\nprintf "%%s\\n" "$@" >"$QF_STUB_ARGS"\n' >"$work/stub/qf-bake"; chmod +x "$work/stub/qf-bake"
/usr/bin/python3 - "$src/docs/farm.md" "$work/stub" "$work/k8s" >"$work/k8s/shards" 2>"$work/k8s/err" <<'PY'
import os, re, subprocess, sys, textwrap, yaml
page, stub, out = sys.argv[1:4]
blocks = [textwrap.dedent(body) for _, body in re.findall(r"^( *)```yaml\n(.*?)^\1```", open(page).read(), re.S | re.M)]
docs = [d for b in blocks if "JOB_COMPLETION_INDEX" in b for d in yaml.safe_load_all(b)]
job = next(d for d in docs if d.get("kind") == "Job" and d["spec"].get("completionMode") == "Indexed")
n, c = job["spec"]["completions"], job["spec"]["template"]["spec"]["containers"][0]
env = {e["name"]: str(e["value"]) for e in c.get("env", [])}
assert int(env["QF_SHARDS"]) == n, f"QF_SHARDS {env['QF_SHARDS']} != completions {n}"
def expand(s, vars):  # the kubelet's $(VAR) expansion of command and args ($$ escapes $)
    return re.sub(r"\$(\$|\(([A-Za-z_][A-Za-z0-9_.-]*)\))",
                  lambda m: "$" if m.group(1) == "$" else vars.get(m.group(2), m.group(0)), s)
for i in range(n):
    vars = dict(env, JOB_COMPLETION_INDEX=str(i))  # set by the Job controller in every pod
    argv = [expand(a, vars) for a in c.get("command", []) + c.get("args", [])]
    args_file = f"{out}/args-{i}"
    subprocess.run(argv, check=True, env=dict(os.environ, **vars, PATH=stub + ":" + os.environ["PATH"], QF_STUB_ARGS=args_file))
    args = open(args_file).read().split("\n")
    assert args[0] == "batch", f"index {i}: {args}"
    print(args[args.index("--shard") + 1])
PY
rc=$?
n=$(wc -l <"$work/k8s/shards")
[[ $rc -eq 0 && $n -ge 2 && $(tr '\n' ' ' <"$work/k8s/shards") == "$(for i in $(seq "$n"); do printf '%s ' "$i/$n"; done)" ]] && ok ||
  bad "the indexed Job of docs/farm.md gives shards $(tr '\n' ' ' <"$work/k8s/shards")(exit $rc: $(tail -3 "$work/k8s/err"))"
# qf-bake takes each of those shards: every asset of a manifest in exactly one of them
"$bake" generate octahedron -n 200 -o "$work/k8s/p.ply" -q
list=$(for i in $(seq 25); do printf '{"input": "p.ply", "name": "a%02d"},' "$i"; done)
printf '{"output": "out", "assets": [%s]}\n' "${list%,}" >"$work/k8s/m.json"
while read -r s; do "$bake" batch "$work/k8s/m.json" --shard "$s" --dry-run --no-cache 2>&1 || echo "exit $? for --shard $s"; done \
  <"$work/k8s/shards" >"$work/k8s/dry"
grep -E '^qf-bake batch: would bake a[0-9]+$' "$work/k8s/dry" >"$work/k8s/taken"   # the list after each shard's progress lines
[[ $(wc -l <"$work/k8s/taken") == 25 && $(sort -u "$work/k8s/taken" | wc -l) == 25 ]] && ok ||
  bad "the indexed Job's shards take every asset once: $(wc -l <"$work/k8s/taken") taken; $(grep exit "$work/k8s/dry" | head -3)"

# --- 3. a one-node cluster: this host is controller and compute node ---
models=${QF_MODELS:-$HOME/.cache/quasiflat/models}
[[ -f $models/elephant.off ]] || skip "models not fetched (scripts/fetch-models.sh)"
[[ $(id -u) -eq 0 ]] || skip "not root: slurmd runs jobs as their user only as root (CI runs as root)"
for c in munged slurmctld slurmd sbatch; do command -v $c >/dev/null || skip "$c not installed (scripts/install-deps.sh: slurm-wlm, munge)"; done
node=$(hostname -s)
mkdir -p "$work/munge" "$work/state" "$work/spool" "$work/log" "$work/logs"
head -c 1024 /dev/urandom >"$work/munge/munge.key"; chmod 600 "$work/munge/munge.key"
munged -f --key-file="$work/munge/munge.key" --socket="$work/munge/munge.socket" --pid-file="$work/munge/munged.pid" \
  --seed-file="$work/munge/seed" --log-file="$work/log/munged.log" >"$work/log/munged.err" 2>&1 ||
  skip "munged cannot start here: $(tail -2 "$work/log/munged.err" "$work/log/munged.log" 2>/dev/null | tr '\n' ' ')"
read -r ctld_port slurmd_port < <(/usr/bin/python3 -c 'import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])') || skip "no free TCP port on 127.0.0.1"
mem=$(awk '/^MemTotal/ {print int($2 / 1024)}' /proc/meminfo)
export SLURM_CONF=$work/slurm.conf
# Memory is neither consumed nor enforced (CR_Core, no cgroups); the node claims at least the 8G
# that bake-array.sbatch asks for, and slurmd reports the configured figures (config_overrides).
cat >"$SLURM_CONF" <<EOF
ClusterName=qftest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$work/munge/munge.socket
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SwitchType=switch/none
MpiDefault=none
MailProg=/bin/true
SlurmdParameters=config_overrides
ReturnToService=2
MinJobAge=3600
KillWait=5
NodeName=$node NodeAddr=127.0.0.1 CPUs=2 RealMemory=$((mem > 9000 ? mem : 9000)) State=UNKNOWN
PartitionName=qf Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -D -f "$SLURM_CONF" >"$work/log/slurmctld.out" 2>&1 & daemons+=($!)
slurmd -D -N "$node" -f "$SLURM_CONF" >"$work/log/slurmd.out" 2>&1 & daemons+=($!)
# If this shell dies without its trap (SIGKILL), the daemons and their jobs go with it.
( trap '' INT TERM; cd /; while kill -0 $$ 2>/dev/null; do sleep 2; done
  kill -9 "${daemons[@]}" "$(cat "$work/munge/munged.pid" 2>/dev/null)" $(held) 2>/dev/null; rm -rf "$work" ) >/dev/null 2>&1 &
watchdog=$!; disown "$watchdog"
for _ in $(seq 60); do
  [[ $(sinfo -h -n "$node" -o %T 2>/dev/null) == idle ]] && break
  kill -0 "${daemons[@]}" 2>/dev/null || break
  sleep 0.5
done
if [[ $(sinfo -h -n "$node" -o %T 2>/dev/null) != idle ]]; then
  why=$(cat "$work/log/slurmctld.out" "$work/log/slurmd.out" 2>/dev/null | grep -E 'fatal|error' | grep -v 'state file\|NOTE:' | tail -3 | tr '\n' ' ')
  # our configuration's fault is a failure; anything else this container does not allow is a skip
  if grep -qiE 'fatal:.*(slurm\.conf|parse|unrecognized|invalid)' "$work"/log/slurm* 2>/dev/null; then
    bad "the test's slurm.conf is rejected: $why"; finish slurm; exit
  fi
  skip "the Slurm daemons do not come up in this container (node: $(sinfo -h -n "$node" -o %T 2>/dev/null)): ${why:-see slurmd/slurmctld logs}"
fi
echo "slurm: one-node cluster up (Slurm $(sinfo -V | cut -d' ' -f2), node $node, ports $ctld_port/$slurmd_port)"

jobid() { sed 's/;.*//'; }                        # sbatch --parsable prints ID[;CLUSTER]
states() { scontrol -o show job "$1" | sed -E 's/.*ArrayTaskId=([^ ]*).*JobState=([^ ]*).*ExitCode=([^ ]*).*/\1:\2:\3/; s/.*JobState=([^ ]*).*ExitCode=([^ ]*).*/\1:\2/' | sort -n | tr '\n' ' '; }
wait_jobs() {  # wait_jobs SECONDS JOBID...: until none of them is pending or running
  local end=$((SECONDS + $1)); shift
  while [[ -n $(squeue -h -j "$(IFS=,; echo "$*")" -o %i 2>/dev/null) ]]; do
    ((SECONDS < end)) || { bad "jobs $* still queued after the deadline: $(squeue -h -j "$(IFS=,; echo "$*")")"; return 1; }
    sleep 0.3
  done
}
logs() { tail -n 5 "$work"/logs/slurm-*.out 2>/dev/null | head -40; }

# --- 4. the manifest, and its unsharded bake (the reference) ---
printf '{"output": "baked", "defaults": {"ldi": 128},\n "assets": [%s]}\n' \
  "\"$models/oni.pwn\", \"$models/kitten.xyz\", \"$models/sphere_20k.xyz\", \"$models/elephant.off\"" >"$work/models.json"
names="['oni', 'kitten', 'sphere_20k', 'elephant']"
"$bake" batch "$work/models.json" -o "$work/ref" -j 2 -q; rc=$?
[[ $rc -eq 0 ]] && ok || bad "unsharded batch: exit $rc"
listing "$work/ref" >"$work/ref.sums"
[[ $(grep -c manifest.json "$work/ref.sums") == 4 ]] && ok || bad "the reference has 4 assets"

# --- 5. the array job as docs/farm.md submits it, and the merge after it ---
export PATH=$(cd "$(dirname "$bake")" && pwd):$PATH             # qf-bake on the nodes' PATH (sbatch passes the environment on)
cd "$work/logs"                                  # slurm-%A_%a.out land here
start=$SECONDS
arr=$(sbatch --parsable --array=1-3 "$slurm_dir/bake-array.sbatch" "$work/models.json" "$work/baked" "$work/amg-cache" | jobid)
mrg=$(sbatch --parsable --dependency=afterany:$arr "$slurm_dir/merge-reports.sbatch" "$work/baked" 3 | jobid)
wait_jobs 150 "$arr" "$mrg"
echo "slurm: array of 3 + merge in $((SECONDS - start)) s"
[[ $(states "$arr") == "1:COMPLETED:0:0 2:COMPLETED:0:0 3:COMPLETED:0:0 " && $(states "$mrg") == "COMPLETED:0:0 " ]] && ok ||
  bad "array $arr: $(states "$arr"); merge $mrg: $(states "$mrg"); $(logs)"
listing "$work/baked" | cmp -s - "$work/ref.sums" && ok ||
  bad "the array's outputs differ from the unsharded batch: $(listing "$work/baked" | diff - "$work/ref.sums" | head -5)"
[[ $(field "$work/baked/batch-report.json" '([a["name"] for a in r["assets"]], r["totals"]["baked"], r["missing_shards"])') == "($names, 4, [])" ]] && ok ||
  bad "merged report lists every asset: $(field "$work/baked/batch-report.json" '[(a["name"], a["status"]) for a in r["assets"]]' 2>&1)"
validate "$work/baked/batch-report.json" "$schemas/batch-report.schema.json"
ls "$work/baked"/batch-report-{1,2,3}-of-3.json >/dev/null && ok || bad "one report per shard"

# --- 6. a task cancelled mid-bake, resubmitted alone ---
rm -f "$work"/logs/*
arr=$(sbatch --parsable --array=1-3 "$slurm_dir/bake-array.sbatch" "$work/models.json" "$work/baked2" "$work/amg-cache2" | jobid)
mrg=$(sbatch --parsable --dependency=afterany:$arr "$slurm_dir/merge-reports.sbatch" "$work/baked2" 3 | jobid)
# shard 1/3 is oni then elephant: cancel it once oni is done and elephant is baking
end=$((SECONDS + 90))
until [[ -f $work/baked2/oni/manifest.json ]] || ((SECONDS > end)); do sleep 0.1; done
mid=$([[ -f $work/baked2/oni/manifest.json && ! -f $work/baked2/elephant/manifest.json ]] && echo yes)
scancel "${arr}_1"
wait_jobs 150 "$arr" "$mrg"
[[ $mid == yes && $(states "$arr") == "1:CANCELLED:0:15 2:COMPLETED:0:0 3:COMPLETED:0:0 " ]] && ok ||
  bad "task 1 cancelled mid-bake (oni done, elephant not: $mid): $(states "$arr")"
[[ ! -f $work/baked2/elephant/manifest.json && ! -f $work/baked2/batch-report-1-of-3.json ]] && ok || bad "the cancelled task's shard is unfinished"
pgrep -f "$work/models.json" >/dev/null && bad "bake processes outlive the cancelled task: $(pgrep -af "$work/models.json")" || ok
[[ $(states "$mrg") == "FAILED:1:0 " ]] && grep -q "missing shards: \[1\]" "$work"/logs/slurm-"$mrg".out && ok ||
  bad "the merge after a cancelled task exits 1 naming shard 1: $(states "$mrg"): $(cat "$work"/logs/slurm-"$mrg".out)"
arr=$(QF_SHARDS=3 sbatch --parsable --array=1 "$slurm_dir/bake-array.sbatch" "$work/models.json" "$work/baked2" "$work/amg-cache2" | jobid)
mrg=$(sbatch --parsable --dependency=afterany:$arr "$slurm_dir/merge-reports.sbatch" "$work/baked2" 3 | jobid)
wait_jobs 150 "$arr" "$mrg"
[[ $(states "$arr") == "1:COMPLETED:0:0 " && $(states "$mrg") == "COMPLETED:0:0 " ]] && ok ||
  bad "resubmitted task $arr: $(states "$arr"); merge $mrg: $(states "$mrg"); $(logs)"
listing "$work/baked2" | cmp -s - "$work/ref.sums" && ok ||
  bad "cancelled + resubmitted differs from the unsharded batch: $(listing "$work/baked2" | diff - "$work/ref.sums" | head -5)"
leftovers() { find "$work/baked2" -name '.qf-*' -o -name '*.tmp-*' -o -name '.*.qf-*'; }  # .NAME.qf-*: core/output_folder.h
[[ -z $(leftovers) ]] && ok || bad "staging left: $(leftovers)"
[[ $(field "$work/baked2/batch-report.json" '([a["name"] for a in r["assets"]], [a["status"] for a in r["assets"]][0::3], r["missing_shards"])') == \
   "($names, ['up to date', 'baked'], [])" ]] && ok ||
  bad "merged report after the resubmission: $(field "$work/baked2/batch-report.json" '[(a["name"], a["status"]) for a in r["assets"]]' 2>&1)"
cd "$work"
finish slurm
