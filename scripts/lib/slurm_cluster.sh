# SPDX-License-Identifier: MIT
# shellcheck shell=bash
# A throwaway single-node SLURM cluster on this machine, for the tests of nceig's job arrays
# (tests/cli/cli_slurm.sh) and of any later driver that submits them. Not installed.
#
#   source scripts/lib/slurm_cluster.sh
#   slurm_cluster_start || { echo "$slurm_cluster_error"; exit 77; }
#   sbatch ...; squeue; scontrol ...        # SLURM_CONF points at this cluster
#   slurm_cluster_stop                      # also run on exit, and if the caller is killed
#
# What a caller needs: root (slurmd starts jobs as their user; the packages are installed
# with apt-get when missing: slurm-wlm and munge, Debian 12's archive), and nothing else
# running as this cluster: everything lives in a fresh folder under /tmp (munge key and
# socket, slurm.conf, state, spool, logs), the two SLURM ports are free ones picked here,
# and the daemons are this script's children, never system services.
#
# Choices, for a container without systemd or cgroups. The sandbox these tests were written
# in is a Firecracker VM whose PID 1 is not systemd (systemctl is installed but has nothing to
# talk to); it mounts cgroup v1 controllers (writable by root) and a cgroup2 tree with only
# hugetlb, so Slurm's cgroup plugins cannot be counted on. Hence:
# - the daemons start in the foreground (-D, --foreground) in the background of this shell,
#   not through systemctl;
# - ProctrackType=proctrack/linuxproc (the process tree from /proc) and TaskPlugin=task/none
#   need no cgroup;
# - JobAcctGatherType=jobacct_gather/none, AccountingStorageType=accounting_storage/none: no
#   database (job states come from scontrol, not sacct);
# - SelectType=select/cons_tres with CR_Core: one core per array element, so the node runs
#   as many elements at a time as it has cores;
# - the node's CPUs, sockets, cores, threads and memory are what `slurmd -C` reports, so
#   that slurmd never finds the node smaller than configured (which would drain it);
# - SchedulerParameters=batch_sched_delay=0: the next array element starts about 1 s after
#   one ends (3 s with the default).

slurm_cluster_dir='' slurm_cluster_error=''
slurm_cluster_lib=$(realpath "${BASH_SOURCE[0]}")

# slurm_cluster_install: the daemons and clients, from Debian's archive when missing.
slurm_cluster_install() {
    local program missing=0
    for program in munged slurmctld slurmd sbatch scontrol sinfo; do
        slurm_cluster_which "$program" >/dev/null || missing=1
    done
    ((missing)) || return 0
    if [[ $(id -u) -ne 0 ]] || ! command -v apt-get >/dev/null 2>&1; then
        slurm_cluster_error="slurm-wlm and munge are not installed and this is not root with apt-get"
        return 1
    fi
    local -a apt=(apt-get -o DPkg::Lock::Timeout=300 install -y -qq --no-install-recommends
                  slurm-wlm munge)
    if ! DEBIAN_FRONTEND=noninteractive "${apt[@]}" >/dev/null 2>&1; then
        # a fresh machine may have no package lists yet
        apt-get -o DPkg::Lock::Timeout=300 update -qq >/dev/null 2>&1
        DEBIAN_FRONTEND=noninteractive "${apt[@]}" >/dev/null 2>&1 || {
            slurm_cluster_error="apt-get install slurm-wlm munge failed"
            return 1
        }
    fi
}

# slurm_cluster_which PROGRAM: its path; the daemons live in /usr/sbin, often not on PATH.
slurm_cluster_which() {
    command -v "$1" 2>/dev/null && return 0
    [[ -x /usr/sbin/$1 ]] && { echo "/usr/sbin/$1"; return 0; }
    return 1
}

# slurm_cluster_free_ports N: N TCP ports in 20000-39999 that nothing listens on (from
# /proc/net/tcp and tcp6); the start retries with others if one is taken meanwhile.
slurm_cluster_free_ports() {
    local used='' port found=0 local_address state
    while read -r _ local_address _ state _; do
        [[ $state == 0A ]] && used+=$((16#${local_address##*:}))$'\n'
    done < <(cat /proc/net/tcp /proc/net/tcp6 2>/dev/null)
    while ((found < $1)); do
        port=$((20000 + RANDOM % 20000))
        grep -qx "$port" <<<"$used" && continue
        used+=$'\n'$port
        echo "$port"
        found=$((found + 1))
    done
}

# slurm_cluster_start: installs when needed, starts munged, slurmctld and slurmd, and waits
# until the node is idle (at most about a minute). Exports SLURM_CONF. On failure:
# slurm_cluster_error says why (with the daemons' last log lines) and everything is stopped.
slurm_cluster_start() {
    slurm_cluster_install || return 1
    local attempt
    for attempt in 1 2 3; do
        slurm_cluster_start_once && return 0
        slurm_cluster_stop
        # a port taken between the pick and the bind: try others; anything else: give up
        [[ $slurm_cluster_error == *"Address already in use"* ]] || return 1
    done
    return 1
}

slurm_cluster_start_once() {
    local dir node=nceig1 host ctld_port node_port hw program
    dir=$(mktemp -d /tmp/nceig-slurm.XXXXXX) || { slurm_cluster_error="mktemp failed"; return 1; }
    slurm_cluster_dir=$dir
    slurm_cluster_error=''
    slurm_cluster_watch
    # munged wants every folder above its socket searchable by all, and its key private.
    chmod 755 "$dir"
    mkdir -m 755 "$dir/run" "$dir/log" "$dir/state" "$dir/spool"
    mkdir -m 700 "$dir/munge"
    head -c 1024 /dev/urandom >"$dir/munge/munge.key"
    chmod 400 "$dir/munge/munge.key"
    : >"$dir/pids"
    for program in munged slurmctld slurmd; do
        slurm_cluster_which "$program" >/dev/null ||
            { slurm_cluster_error="$program not found"; return 1; }
    done

    slurm_cluster_spawn munged "$(slurm_cluster_which munged)" --foreground \
        --socket="$dir/run/munge.socket" --key-file="$dir/munge/munge.key" \
        --log-file="$dir/log/munged.log" --pid-file="$dir/run/munged.pid" \
        --seed-file="$dir/munge/munged.seed"
    slurm_cluster_until 10 '[[ -S $slurm_cluster_dir/run/munge.socket ]]' ||
        { slurm_cluster_fail "munged did not create its socket"; return 1; }

    hw=$("$(slurm_cluster_which slurmd)" -C 2>/dev/null | head -n 1)
    [[ $hw == NodeName=* ]] || { slurm_cluster_fail "slurmd -C failed: $hw"; return 1; }
    hw=$(tr ' ' '\n' <<<"$hw" | grep -E '^(CPUs|Boards|SocketsPerBoard|CoresPerSocket|ThreadsPerCore|RealMemory)=' | paste -sd' ')
    host=$(hostname -s)
    read -r ctld_port node_port < <(slurm_cluster_free_ports 2 | paste -sd' ')
    : >"$dir/plugstack.conf"
    cat >"$dir/slurm.conf" <<EOF
# A single-node cluster for nceig's tests, written by scripts/lib/slurm_cluster.sh.
ClusterName=nceigtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$node_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/run/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
PlugStackConfig=$dir/plugstack.conf
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/builtin
SchedulerParameters=batch_sched_delay=0
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
SlurmctldTimeout=60
SlurmdTimeout=60
InactiveLimit=0
MinJobAge=600
KillWait=5
Waittime=0
NodeName=$node NodeHostname=$host NodeAddr=127.0.0.1 $hw State=UNKNOWN
PartitionName=nceig Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
    export SLURM_CONF=$dir/slurm.conf

    slurm_cluster_spawn slurmctld "$(slurm_cluster_which slurmctld)" -D -f "$SLURM_CONF"
    slurm_cluster_until 30 'scontrol ping 2>/dev/null | grep -q "is UP"' ||
        { slurm_cluster_fail "slurmctld did not answer"; return 1; }
    slurm_cluster_spawn slurmd "$(slurm_cluster_which slurmd)" -D -N "$node" -f "$SLURM_CONF"
    slurm_cluster_until 60 '[[ $(sinfo -h -n nceig1 -o %T 2>/dev/null) == idle ]]' ||
        { slurm_cluster_fail "the node did not become idle ($(sinfo -h -o %T 2>&1))"; return 1; }
}

# slurm_cluster_spawn NAME PROGRAM ARGS...: starts a daemon in the background of this shell,
# its output in log/NAME.out, and records its pid with its start time (so that the stop never
# signals a recycled pid).
slurm_cluster_spawn() {
    local name=$1
    shift
    SLURM_CONF=$slurm_cluster_dir/slurm.conf "$@" </dev/null \
        >"$slurm_cluster_dir/log/$name.out" 2>&1 &
    echo "$! $(slurm_cluster_start_time $!) $name" >>"$slurm_cluster_dir/pids"
}

# slurm_cluster_start_time PID: field 22 of /proc/PID/stat (clock ticks since boot); nothing
# once the process has ended (a zombie counts as ended).
slurm_cluster_start_time() {
    awk '{ sub(/.*\) /, ""); if ($1 != "Z") print $20 }' "/proc/$1/stat" 2>/dev/null
}

# slurm_cluster_until SECONDS CONDITION: polls the bash CONDITION every 0.2 s.
slurm_cluster_until() {
    local deadline=$((SECONDS + $1))
    until eval "$2"; do
        ((SECONDS < deadline)) || return 1
        sleep 0.2
    done
}

# slurm_cluster_fail REASON: slurm_cluster_error = REASON and the daemons' last log lines.
slurm_cluster_fail() {
    local log
    slurm_cluster_error=$1
    for log in "$slurm_cluster_dir"/log/*; do
        [[ -s $log ]] || continue
        slurm_cluster_error+=$'\n'"--- ${log##*/}:"$'\n'"$(grep -v 'pmix' "$log" | tail -n 8)"
    done
}

# slurm_cluster_watch: a guard in its own session that stops the cluster when this shell is
# gone, even by SIGKILL (a CTest timeout), and the EXIT trap for a normal end, which keeps
# whatever EXIT trap the caller had set before.
slurm_cluster_watch() {
    local caller=$$ caller_start previous
    caller_start=$(slurm_cluster_start_time $$)
    previous=$(trap -p EXIT)
    if [[ -z ${slurm_cluster_trap_set:-} ]]; then
        slurm_cluster_previous_exit=''
        [[ -n $previous ]] && eval "slurm_cluster_previous_exit=\$(slurm_cluster_trap_body $previous)"
        trap 'slurm_cluster_stop; eval "$slurm_cluster_previous_exit"' EXIT
        trap 'exit 130' INT
        trap 'exit 143' TERM
        slurm_cluster_trap_set=1
    fi
    setsid bash -c '
        source "$4"
        while [[ -d $1 && $(slurm_cluster_start_time "$2") == "$3" ]]; do sleep 2; done
        slurm_cluster_dir=$1
        slurm_cluster_stop' \
        nceig-slurm-guard "$slurm_cluster_dir" "$caller" "$caller_start" \
        "$slurm_cluster_lib" </dev/null >/dev/null 2>&1 &
}

# slurm_cluster_trap_body trap -- 'TEXT' EXIT: prints TEXT (what `trap -p` quoted).
slurm_cluster_trap_body() { printf '%s' "$3"; }

# slurm_cluster_stop: cancels the jobs, stops slurmd, slurmctld and munged (TERM, then KILL
# after 5 s), ends job steps they left behind, and removes the folder. Safe to call twice,
# or when the start failed half way.
slurm_cluster_stop() {
    local dir=$slurm_cluster_dir pid start name pids=() step
    [[ -n $dir && -d $dir ]] || return 0
    slurm_cluster_dir=''
    if [[ -f $dir/slurm.conf ]]; then
        SLURM_CONF=$dir/slurm.conf timeout 10 scancel --quiet --full --user="$(id -un)" \
            >/dev/null 2>&1
        local deadline=$((SECONDS + 10))
        while [[ -n $(SLURM_CONF=$dir/slurm.conf timeout 5 squeue -h 2>/dev/null) ]] &&
            ((SECONDS < deadline)); do sleep 0.5; done
    fi
    # slurmd first (it returns its node), munged last (the others need it to the end)
    for name in slurmd slurmctld munged; do
        while read -r pid start; do
            [[ $(slurm_cluster_start_time "$pid") == "$start" ]] || continue
            kill -TERM "$pid" 2>/dev/null && pids+=("$pid:$start")
        done < <(awk -v n="$name" '$3 == n { print $1, $2 }' "$dir/pids" 2>/dev/null)
    done
    # job steps (slurmstepd) detach from slurmd; ours carry this cluster's SLURM_CONF
    for step in /proc/[0-9]*; do
        [[ $(cat "$step/comm" 2>/dev/null) == slurmstepd ]] || continue
        tr '\0' '\n' 2>/dev/null <"$step/environ" | grep -qxF "SLURM_CONF=$dir/slurm.conf" &&
            kill -KILL "${step#/proc/}" 2>/dev/null
    done
    local entry waited=0
    for entry in "${pids[@]}"; do
        pid=${entry%%:*} start=${entry#*:}
        while [[ $(slurm_cluster_start_time "$pid") == "$start" ]] && ((waited < 50)); do
            sleep 0.1
            waited=$((waited + 1))
        done
        [[ $(slurm_cluster_start_time "$pid") == "$start" ]] && kill -KILL "$pid" 2>/dev/null
    done
    [[ ${SLURM_CONF:-} == "$dir/slurm.conf" ]] && unset SLURM_CONF
    rm -rf "$dir"
}
