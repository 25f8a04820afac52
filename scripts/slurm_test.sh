#!/usr/bin/env bash
# End-to-end test of the render-farm recipe (docs/render-farm.md) on Slurm:
#
#   scripts/slurm_test.sh [SPECTRACE [SCENE [SPP [N]]]]
#
#   SPECTRACE  spectrace binary          (default: target/release/spectrace)
#   SCENE      scene file                (default: tests/reference/cornell/scene.xml, 96 × 96)
#   SPP        samples per pixel         (default: 64)
#   N          number of parts           (default: 4)
#
# It installs slurm-wlm and munge if they are missing (Debian/Ubuntu, as root), starts a
# one-node cluster on localhost (munged, slurmctld, slurmd, config in a temporary folder) unless
# `sinfo` already answers, submits docs/slurm/render-parts.sbatch as an array of N tasks and
# docs/slurm/merge.sbatch with --dependency=afterok on it, waits for both, renders the same
# image once without --part, and checks with OpenImageIO's idiff that the merged image's pixels
# are bit-identical to the single render's. Exit status 0 on success, 1 on any failure. The
# daemons it started are stopped on exit.
#
# Environment:
#   SEED=7                 sampler seed of every render
#   SPECTRACE_ARGS=        further render options for the parts and the single render
#   SPECTRACE_STANDIN=1    test the Slurm plumbing with a stand-in for `render --part` and
#                          `merge` (a shell wrapper written to the work folder: each part writes
#                          a small marker file, the merge checks that all N markers are there
#                          with the same settings, then renders the full image with SPECTRACE)
#   SLURM_TEST_TIMEOUT=600 seconds to wait for the jobs
#   SLURM_TEST_WORKDIR=    work folder (default: a new folder under /tmp); on a real multi-node
#                          cluster it must be on a filesystem every node sees
#   KEEP_WORKDIR=1         keep the work folder after a success (it is always kept on failure)
set -euo pipefail

log() { printf '[slurm_test] %s\n' "$*"; }
die() { printf '[slurm_test] FAIL: %s\n' "$*" >&2; exit 1; }

case "${1:-}" in -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac

# Paths given on the command line are relative to the caller's folder; the defaults to the repo.
abspath() { [[ $1 == /* ]] && printf '%s\n' "$1" || printf '%s\n' "$PWD/$1"; }
REPO=$(cd "$(dirname "$0")/.." && pwd)
SPECTRACE_BIN=$(abspath "${1:-$REPO/target/release/spectrace}")
SCENE=$(abspath "${2:-$REPO/tests/reference/cornell/scene.xml}")
SPP=${3:-64}
N=${4:-4}
SEED=${SEED:-7}
SPECTRACE_ARGS=${SPECTRACE_ARGS:-}
TIMEOUT=${SLURM_TEST_TIMEOUT:-600}
STANDIN=${SPECTRACE_STANDIN:-0}
PARTS_SBATCH=$REPO/docs/slurm/render-parts.sbatch
MERGE_SBATCH=$REPO/docs/slurm/merge.sbatch

[[ -x $SPECTRACE_BIN ]] || die "no spectrace binary at $SPECTRACE_BIN (cargo build --release, or pass its path)"
[[ -f $SCENE ]] || die "no scene file $SCENE"
[[ $SPP =~ ^[1-9][0-9]*$ ]] || die "SPP=$SPP is not a positive integer"
[[ $N =~ ^[1-9][0-9]*$ ]] || die "N=$N is not a positive integer"
[[ -f $PARTS_SBATCH && -f $MERGE_SBATCH ]] || die "missing docs/slurm/*.sbatch"
if [[ $STANDIN != 1 ]]; then # the real binary must know --part and merge
  help=$("$SPECTRACE_BIN" render --help 2>/dev/null || true)
  [[ $help == *--part* ]] ||
    die "$SPECTRACE_BIN has no 'render --part' (not built yet?); SPECTRACE_STANDIN=1 tests the Slurm side alone"
  "$SPECTRACE_BIN" merge --help >/dev/null 2>&1 || die "$SPECTRACE_BIN has no 'merge' command"
fi

WORK=${SLURM_TEST_WORKDIR:-$(mktemp -d /tmp/spectrace-slurm-test.XXXXXX)}
mkdir -p "$WORK/out" "$WORK/logs"
SUCCESS=0
STARTED_MUNGED_PID=   # pids of the daemons this script started, to stop them on exit
STARTED_SLURM=0

cleanup() {
  local rc=$?
  if ((STARTED_SLURM)); then
    log "stopping slurmctld and slurmd"
    scontrol shutdown >/dev/null 2>&1 || true
    local pidfile pid i
    for pidfile in "$WORK/slurm/slurmctld.pid" "$WORK/slurm/slurmd.pid"; do
      [[ -f $pidfile ]] || continue
      pid=$(<"$pidfile")
      for ((i = 0; i < 50; i++)); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
      if kill -0 "$pid" 2>/dev/null; then kill "$pid" 2>/dev/null || true; fi
    done
  fi
  if [[ -n $STARTED_MUNGED_PID ]]; then
    log "stopping munged"
    kill "$STARTED_MUNGED_PID" 2>/dev/null || true
  fi
  if ((SUCCESS)) && [[ -z ${KEEP_WORKDIR:-} && -z ${SLURM_TEST_WORKDIR:-} ]]; then
    rm -rf "$WORK"
  else
    log "work folder kept: $WORK"
  fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# Prints the last lines of every job log, for a failure message.
show_logs() {
  local f
  for f in "$WORK"/logs/*; do
    [[ -f $f ]] || continue
    echo "---- $f" >&2
    tail -n 20 "$f" >&2
  done
}

# --- 1. Slurm and munge -------------------------------------------------------------------------

install_packages() {
  local missing=()
  command -v sbatch >/dev/null && command -v slurmctld >/dev/null && command -v slurmd >/dev/null ||
    missing+=(slurm-wlm)
  command -v munged >/dev/null || missing+=(munge)
  ((${#missing[@]})) || return 0
  ((EUID == 0)) || die "${missing[*]} missing and not root: apt-get install ${missing[*]}"
  command -v apt-get >/dev/null || die "${missing[*]} missing and no apt-get"
  log "installing ${missing[*]} (apt-get)"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq >"$WORK/apt.log" 2>&1 || die "apt-get update failed (see $WORK/apt.log)"
  apt-get install -y -q "${missing[@]}" >>"$WORK/apt.log" 2>&1 ||
    die "apt-get install ${missing[*]} failed (see $WORK/apt.log)"
}

munge_works() { munge -n 2>/dev/null | unmunge >/dev/null 2>&1; }

start_munged() {
  munge_works && return 0
  ((EUID == 0)) || die "munged is not running and only root can start it"
  log "starting munged"
  if [[ ! -s /etc/munge/munge.key ]]; then # the Debian package makes one; make it if it is gone
    if command -v mungekey >/dev/null; then mungekey --create --force; else create-munge-key -f; fi
    chown munge:munge /etc/munge/munge.key
    chmod 0400 /etc/munge/munge.key
  fi
  install -d -o munge -g munge -m 0755 /run/munge # /run is empty in a fresh container
  runuser -u munge -- /usr/sbin/munged || die "munged did not start (see /var/log/munge/munged.log)"
  local i
  for ((i = 0; i < 50; i++)); do munge_works && break; sleep 0.2; done
  munge_works || die "munged started but munge -n | unmunge fails"
  STARTED_MUNGED_PID=$(cat /run/munge/munged.pid 2>/dev/null || true)
}

# Writes a one-node slurm.conf (this machine's CPUs and memory as `slurmd -C` sees them, no
# cgroups, no accounting, every daemon as root) into $WORK/slurm and starts slurmctld and slurmd
# with it. SLURM_CONF points every client command (sinfo, sbatch, ...) at it.
start_slurm() {
  ((EUID == 0)) || die "no Slurm cluster answers sinfo, and only root can start one"
  local conf_dir=$WORK/slurm
  mkdir -p "$conf_dir/state" "$conf_dir/spool"
  local node
  node=$(slurmd -C | head -n 1) # NodeName=<short hostname> CPUs=... RealMemory=...
  [[ $node == NodeName=* ]] || die "slurmd -C printed no node line: $node"
  local name=${node%% *}
  name=${name#NodeName=}
  cat >"$conf_dir/slurm.conf" <<EOF
# One-node test cluster written by scripts/slurm_test.sh
ClusterName=spectrace-test
SlurmctldHost=$name(127.0.0.1)
SlurmUser=root
SlurmctldPort=${SLURM_TEST_CTLD_PORT:-6817}
SlurmdPort=${SLURM_TEST_SLURMD_PORT:-6818}
AuthType=auth/munge
CredType=cred/munge
StateSaveLocation=$conf_dir/state
SlurmdSpoolDir=$conf_dir/spool
SlurmctldPidFile=$conf_dir/slurmctld.pid
SlurmdPidFile=$conf_dir/slurmd.pid
SlurmctldLogFile=$conf_dir/slurmctld.log
SlurmdLogFile=$conf_dir/slurmd.log
PlugStackConfig=$conf_dir/plugstack.conf
# No cgroups (containers rarely allow them) and no accounting database.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
# Cancel a job whose dependency can never be met (a failed part cancels the merge).
SchedulerParameters=kill_invalid_depend
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
  : >"$conf_dir/plugstack.conf" # no SPANK plugins (Debian's default file includes a folder)
  export SLURM_CONF=$conf_dir/slurm.conf
  STARTED_SLURM=1
  log "starting slurmctld and slurmd ($SLURM_CONF)"
  slurmctld -f "$SLURM_CONF" || die "slurmctld did not start: $(tail -n 5 "$conf_dir/slurmctld.log" 2>/dev/null)"
  slurmd -f "$SLURM_CONF" || die "slurmd did not start: $(tail -n 5 "$conf_dir/slurmd.log" 2>/dev/null)"
  local i state=
  for ((i = 0; i < 60; i++)); do
    state=$(sinfo -h -n "$name" -o %T 2>/dev/null || true)
    [[ $state == idle ]] && break
    sleep 0.5
  done
  [[ $state == idle ]] ||
    die "node $name is '${state:-unknown}', not idle; logs: $conf_dir/slurmctld.log, $conf_dir/slurmd.log"
}

install_packages
if timeout 15 sinfo -h >/dev/null 2>&1; then
  log "using the running Slurm cluster (sinfo answers)"
else
  start_munged
  start_slurm
fi
log "$(sinfo --version)"
sinfo | sed 's/^/[slurm_test]   /'

# --- 2. The binary, or its stand-in ------------------------------------------------------------

BIN=$SPECTRACE_BIN
if [[ $STANDIN == 1 ]]; then
  BIN=$WORK/spectrace-standin
  log "SPECTRACE_STANDIN=1: parts and merge by the stand-in $BIN"
  # The stand-in passes everything but `render --part` and `merge` to the real binary. A part
  # writes a marker: line 1 "spectrace-standin-part I/N", then its render arguments (without
  # --part and -o), one a line. The merge checks that it got each of 0..N-1 exactly once with
  # the same N and arguments, then renders the full image with those arguments.
  cat >"$BIN" <<EOF
#!/usr/bin/env bash
set -euo pipefail
REAL='$SPECTRACE_BIN'
EOF
  cat >>"$BIN" <<'EOF'
die() { echo "spectrace-standin: $*" >&2; exit 1; }
if [[ ${1:-} == render && " $* " == *" --part "* ]]; then
  rest=() part= out=
  while (($#)); do
    case $1 in
      --part) part=$2; shift 2 ;;
      -o | --output) out=$2; shift 2 ;;
      *) rest+=("$1"); shift ;;
    esac
  done
  [[ $part =~ ^([0-9]+)/([0-9]+)$ ]] && ((BASH_REMATCH[1] < BASH_REMATCH[2])) || die "bad --part '$part'"
  [[ -n $out ]] || die "no -o"
  { echo "spectrace-standin-part $part"; printf '%s\n' "${rest[@]}"; } >"$out.tmp"
  mv "$out.tmp" "$out"
elif [[ ${1:-} == merge ]]; then
  shift
  parts=() out=
  while (($#)); do
    case $1 in
      -o | --output) out=$2; shift 2 ;;
      *) parts+=("$1"); shift ;;
    esac
  done
  [[ -n $out ]] || die "no -o"
  ((${#parts[@]})) || die "no parts"
  declare -A seen=()
  n= args=
  for p in "${parts[@]}"; do
    head=$(head -n 1 "$p") || die "cannot read $p"
    [[ $head =~ ^spectrace-standin-part\ ([0-9]+)/([0-9]+)$ ]] || die "$p is not a stand-in part"
    i=${BASH_REMATCH[1]} pn=${BASH_REMATCH[2]}
    [[ -z $n || $n == "$pn" ]] || die "$p is part of $pn, others of $n"
    n=$pn
    [[ -z ${seen[$i]:-} ]] || die "part $i given twice"
    seen[$i]=1
    a=$(tail -n +2 "$p")
    [[ -z $args || $args == "$a" ]] || die "$p was rendered with other settings"
    args=$a
  done
  ((${#seen[@]} == n)) || die "got ${#seen[@]} of $n parts"
  mapfile -t render_args <<<"$args"
  exec "$REAL" "${render_args[@]}" -o "$out"
else
  exec "$REAL" "$@"
fi
EOF
  chmod +x "$BIN"
fi

# --- 3. The array of parts and the merge ----------------------------------------------------------

# The job scripts read their settings from the environment, which sbatch passes on.
export SPECTRACE=$BIN SCENE N SEED SPP SPECTRACE_ARGS OUTDIR=$WORK/out OUT=$WORK/out/merged.exr
log "scene $SCENE, spp $SPP, seed $SEED, $N parts, work folder $WORK"
ARRAY_ID=$(sbatch --parsable --array=0-$((N - 1)) --cpus-per-task=1 --chdir="$WORK/out" \
  --output="$WORK/logs/part_%A_%a.log" "$PARTS_SBATCH") || die "sbatch of the parts failed"
ARRAY_ID=${ARRAY_ID%%;*} # --parsable prints "jobid[;cluster]"
MERGE_ID=$(sbatch --parsable --dependency=afterok:"$ARRAY_ID" --chdir="$WORK/out" \
  --output="$WORK/logs/merge_%j.log" "$MERGE_SBATCH") || die "sbatch of the merge failed"
MERGE_ID=${MERGE_ID%%;*}
log "submitted parts as array job $ARRAY_ID, merge as job $MERGE_ID (afterok:$ARRAY_ID)"

# Wait until squeue lists neither job (no accounting: sacct is not available).
deadline=$((SECONDS + TIMEOUT))
while :; do
  if ! queue=$(squeue -h -j "$ARRAY_ID,$MERGE_ID" -o '%i %T %r' 2>&1); then
    # Jobs that finished long ago are forgotten ("Invalid job id"); anything else is an error.
    [[ $queue == *"Invalid job id"* ]] && break
    ((SECONDS < deadline)) || die "squeue keeps failing: $queue"
    sleep 2
    continue
  fi
  [[ -z $queue ]] && break
  if [[ $queue == *DependencyNeverSatisfied* ]]; then # in case the cluster does not cancel it
    scancel "$MERGE_ID" 2>/dev/null || true
    show_logs
    die "a part failed, so the merge job $MERGE_ID can never run"
  fi
  if ((SECONDS >= deadline)); then
    scancel "$ARRAY_ID" "$MERGE_ID" 2>/dev/null || true
    show_logs
    die "jobs not done after ${TIMEOUT}s:"$'\n'"$queue"
  fi
  sleep 1
done

# Every job must have COMPLETED with exit code 0 (scontrol still knows them for MinJobAge, 300 s
# by default; a job it has forgotten is judged by its output below).
bad=$(for id in "$ARRAY_ID" "$MERGE_ID"; do
  scontrol -o show job "$id" 2>/dev/null |
    sed -n 's/^JobId=\([0-9]*\) .*JobState=\([A-Z_]*\) .* ExitCode=\([0-9:]*\) .*/\1 \2 \3/p' |
    awk '$2 != "COMPLETED" || $3 != "0:0"'
done)
if [[ -n $bad ]]; then
  show_logs
  die "jobs that did not complete (job state exit):"$'\n'"$bad"
fi
[[ -f $OUT ]] || { show_logs; die "the merge job finished without writing $OUT"; }
for ((i = 0; i < N; i++)); do
  [[ -f $OUTDIR/part_$i.exr ]] || die "missing part $OUTDIR/part_$i.exr"
done
log "all $N parts and the merge completed: $OUT"

# --- 4. The same render in one piece -----------------------------------------------------------

SINGLE=$WORK/single.exr
single_args=(render "$SCENE" -o "$SINGLE" --seed "$SEED" --spp "$SPP" --quiet)
# shellcheck disable=SC2206  # split on spaces on purpose, as render-parts.sbatch does
[[ -n $SPECTRACE_ARGS ]] && single_args+=($SPECTRACE_ARGS)
log "single render: $SPECTRACE_BIN ${single_args[*]}"
"$SPECTRACE_BIN" "${single_args[@]}" >"$WORK/logs/single.log" 2>&1 ||
  die "the single render failed: $(tail -n 5 "$WORK/logs/single.log")"

# --- 5. Bit-identical pixels ------------------------------------------------------------------

IDIFF=$(command -v idiff || true)
if [[ -z $IDIFF ]]; then
  scripts_dir=$(python3 -c 'import sysconfig; print(sysconfig.get_path("scripts"))' 2>/dev/null || true)
  [[ -x $scripts_dir/idiff ]] && IDIFF=$scripts_dir/idiff
fi
[[ -n $IDIFF ]] || die "idiff not found (pip install OpenImageIO)"
OIIOTOOL=$(dirname "$IDIFF")/oiiotool # installed beside idiff
[[ -x $OIIOTOOL ]] || OIIOTOOL=oiiotool

# Channel names of an EXR, comma-separated (empty if Python's OpenImageIO is missing).
channels() {
  python3 - "$1" <<'EOF' 2>/dev/null || true
import sys
import OpenImageIO as oiio
inp = oiio.ImageInput.open(sys.argv[1])
print(",".join(inp.spec().channelnames))
inp.close()
EOF
}
merged_ch=$(channels "$OUT")
single_ch=$(channels "$SINGLE")
compared=$OUT
if [[ -n $merged_ch && -n $single_ch && $merged_ch != "$single_ch" ]]; then
  # The merged image may keep extra channels (the parts' sums): compare the single render's.
  for c in ${single_ch//,/ }; do
    [[ ,$merged_ch, == *",$c,"* ]] || die "merged image lacks channel $c (merged: $merged_ch; single: $single_ch)"
  done
  log "merged image has extra channels ($merged_ch); comparing the single render's ($single_ch)"
  compared=$WORK/merged_channels.exr
  "$OIIOTOOL" "$OUT" --ch "$single_ch" -o "$compared" || die "oiiotool could not extract $single_ch"
fi
log "comparing: $IDIFF -fail 0 -failpercent 0 -warn 0 $compared $SINGLE"
if ! "$IDIFF" -fail 0 -failpercent 0 -warn 0 "$compared" "$SINGLE" >"$WORK/idiff.txt" 2>&1; then
  cat "$WORK/idiff.txt" >&2
  die "the merge of $N parts is not bit-identical to the single render"
fi
sed 's/^/[slurm_test]   /' "$WORK/idiff.txt"
SUCCESS=1
log "PASS: merge of $N parts (Slurm array job $ARRAY_ID + job $MERGE_ID) is bit-identical to one render"
