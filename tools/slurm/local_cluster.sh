#!/bin/sh
# A single-node Slurm cluster on this machine, for tests and trials of `prism farm slurm`:
#   tools/slurm/local_cluster.sh start DIR   # prints the SLURM_CONF to export
#   tools/slurm/local_cluster.sh stop DIR
# Everything (munge key and socket, slurm.conf, spool, logs, pid files) lives in DIR; nothing
# in /etc is changed. Needs root (slurmd runs jobs as their users). Installs the Debian packages
# slurmctld slurmd slurm-client munge when they are missing. Exit code 77: cannot run here.
set -eu
action=${1:?usage: local_cluster.sh start|stop DIR}
dir=$(realpath -m "${2:?usage: local_cluster.sh start|stop DIR}")

stop() {
  for pid in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munge/munged.pid"; do
    [ -f "$pid" ] && kill "$(cat "$pid")" 2>/dev/null || true
  done
  sleep 1
}

case $action in
stop) stop; exit 0 ;;
start) ;;
*) echo "usage: local_cluster.sh start|stop DIR" >&2; exit 2 ;;
esac

if [ "$(id -u)" != 0 ]; then echo "local_cluster.sh: needs root to run slurmd" >&2; exit 77; fi
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null || ! command -v sbatch >/dev/null ||
  ! command -v munged >/dev/null; then
  apt-get install -y -o DPkg::Lock::Timeout=600 slurmctld slurmd slurm-client munge >/dev/null ||
    { echo "local_cluster.sh: cannot install Slurm" >&2; exit 77; }
fi

host=$(hostname -s)
# Two free ports, searched from a start hashed from DIR, so clusters in different directories
# (two test runs at once) neither collide nor take a port another program listens on.
listening() { ss -Htln "sport = :$1" 2>/dev/null | grep -q .; }
port=$((20000 + $(printf %s "$dir" | cksum | cut -d' ' -f1) % 6000 * 2))
while listening "$port" || listening "$((port + 1))"; do port=$((port + 2)); done
mkdir -p "$dir/munge" "$dir/spool/ctld" "$dir/spool/d" "$dir/log"
chmod 700 "$dir/munge"
[ -f "$dir/munge/munge.key" ] || { dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 2>/dev/null; chmod 400 "$dir/munge/munge.key"; }
munged --force --key-file="$dir/munge/munge.key" --socket="$dir/munge/socket" --pid-file="$dir/munge/munged.pid" \
  --log-file="$dir/log/munged.log" --seed-file="$dir/munge/seed"

cat >"$dir/slurm.conf" <<CONF
ClusterName=prism-local
SlurmctldHost=$host
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$dir/munge/socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$dir/spool/ctld
SlurmdSpoolDir=$dir/spool/d
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SchedulerParameters=kill_invalid_depend
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=local Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"
slurmctld -i -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 60); do
  if sinfo -h -o %t 2>/dev/null | grep -q idle; then echo "SLURM_CONF=$SLURM_CONF"; exit 0; fi
  sleep 1
done
echo "local_cluster.sh: the node did not come up; see $dir/log" >&2
stop
exit 77
