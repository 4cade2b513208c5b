# A private single-node Slurm cluster for the tests, sourced by them: munge with its own
# key and socket, slurmctld and slurmd on free loopback ports, every file (config, state,
# spool, logs, pid files) under one temporary folder; no systemd, no /etc. Run as root.
#   cluster_start DIR   starts it; on failure returns 1 with the reason in $cluster_error
#   cluster_idle SECS   waits until no job is left (true) or SECS have passed
#   cluster_job_state ID  COMPLETED, FAILED, CANCELLED … (of every task of an array, one per line)
#   cluster_stop        cancels what is left, stops the daemons, removes nothing
# After cluster_start, SLURM_CONF is exported: sbatch, squeue and the jobs use this cluster.

cluster_dir=""
cluster_error=""

# cluster_free_ports N: N distinct free loopback ports, one per line. All sockets are held
# open until every port is drawn: ports drawn one call at a time can repeat (a closed
# port is free again), and slurmctld and slurmd on one port answer each other's messages.
cluster_free_ports() {
  python3 -c 'import socket, sys
socks = [socket.socket() for _ in range(int(sys.argv[1]))]
for s in socks: s.bind(("127.0.0.1", 0))
print("\n".join(str(s.getsockname()[1]) for s in socks))' "$1"
}

# cluster_wait SECONDS COMMAND...: true once COMMAND succeeds, polled every 0.2 s.
cluster_wait() {
  local deadline=$((SECONDS + $1)); shift
  until "$@" > /dev/null 2>&1; do
    [ $SECONDS -lt $deadline ] || return 1
    sleep 0.2
  done
}

cluster_node_idle() { test "$(sinfo -h -N -n kt1 -o %t 2> /dev/null)" = idle; }

cluster_start() {
  cluster_dir=$1
  local d=$cluster_dir c
  for c in munged mungekey slurmctld slurmd sbatch sinfo squeue scontrol scancel; do
    command -v "$c" > /dev/null || { cluster_error="$c is not installed (scripts/install-deps.sh)"; return 1; }
  done
  [ "$(id -u)" -eq 0 ] || { cluster_error="the test cluster runs its daemons as root (SlurmUser=root)"; return 1; }
  mkdir -p "$d/munge" "$d/state" "$d/spool/slurmd-kt1" "$d/log"
  # munged wants its key private and its socket's folder searchable by all.
  chmod 755 "$d" "$d/munge"
  mungekey -c -k "$d/munge/munge.key" 2> "$d/log/mungekey.err" ||
    { cluster_error="mungekey: $(head -1 "$d/log/mungekey.err")"; return 1; }
  munged --key-file="$d/munge/munge.key" --socket="$d/munge/munge.socket" --pid-file="$d/munge/munged.pid" \
         --log-file="$d/log/munged.log" --seed-file="$d/munge/munged.seed" 2> "$d/log/munged.err" ||
    { cluster_error="munged: $(tail -1 "$d/log/munged.err")"; return 1; }
  cluster_wait 10 test -S "$d/munge/munge.socket" || { cluster_error="munged made no socket"; return 1; }

  # The node as slurmd sees this machine (CPUs, sockets, memory), named kt1 on loopback.
  local node ports
  ports=($(cluster_free_ports 2))
  node=$(slurmd -C 2> /dev/null | head -1 | sed 's/^NodeName=[^ ]*/NodeName=kt1/')
  [ -n "$node" ] || { cluster_error="slurmd -C printed no node line"; return 1; }
  cat > "$d/slurm.conf" << EOF
ClusterName=keyturn-test
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=${ports[0]}
SlurmdPort=${ports[1]}
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$d/munge/munge.socket
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool/slurmd-%n
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd.pid
SlurmctldLogFile=$d/log/slurmctld.log
SlurmdLogFile=$d/log/slurmd.log
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
MpiDefault=none
ReturnToService=2
# A stage whose predecessor failed is cancelled, not left pending forever.
DependencyParameters=kill_invalid_depend
$node NodeHostname=localhost NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=kt Nodes=kt1 Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF=$d/slurm.conf
  slurmctld -D > "$d/log/slurmctld.out" 2>&1 &
  slurmd -D -N kt1 > "$d/log/slurmd.out" 2>&1 &
  # (A first start has no state files yet; slurmctld logs that as an error, so it is left out.)
  if ! cluster_wait 60 cluster_node_idle; then
    cluster_error="node kt1 not idle after 60 s (state '$(sinfo -h -N -o %t 2>&1 | head -1)'); slurmctld: $(grep -h -i error "$d/log/slurmctld.log" "$d/log/slurmctld.out" 2> /dev/null | grep -v 'Could not open .* state file' | head -1) slurmd: $(grep -i -m1 'error\|fatal' "$d/log/slurmd.log" 2> /dev/null)"
    return 1
  fi
}

cluster_no_jobs() { test -z "$(squeue -h -o %i 2> /dev/null)"; }
cluster_idle() { cluster_wait "$1" cluster_no_jobs; }
cluster_job_state() { scontrol -o show job "$1" | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p'; }

cluster_stop() {
  [ -n "$cluster_dir" ] || return 0
  local d=$cluster_dir f pid
  scancel --quiet --user=root 2> /dev/null
  cluster_idle 20
  for f in "$d/slurmd.pid" "$d/slurmctld.pid" "$d/munge/munged.pid"; do
    pid=$(cat "$f" 2> /dev/null) || continue
    kill "$pid" 2> /dev/null && cluster_wait 20 sh -c "! kill -0 $pid"
  done
  cluster_dir=""
}
