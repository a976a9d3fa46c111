#!/usr/bin/env bash
# Two "nodes" on one machine (issue 26 §3): two network namespaces joined by a veth pair,
# Open MPI over TCP between them, a fixed-budget luxtrace run checked bit-identical to one
# rank's, and bench/mpi_collectives over the link. Needs root (it changes the network
# configuration) and no network; it removes the namespaces, the link and its temporary
# files on exit, also after a failure. Not part of ctest. docs/SCALING.md shows the figures.
#
# Usage: sudo bench/two_nodes.sh [--build DIR] [--scene FILE] [--photons N]
#                                [--report-every-photons N] [--repeats K] [--max-bytes SIZE]
#                                [--no-collectives]
#
# How the ranks get into the namespaces: mpirun runs inside lt-node1, the hostfile names the
# two addresses, and Open MPI's rsh launcher starts the daemon (orted) of the other "host"
# through plm_rsh_agent, here a small script that runs the command it is given in the
# namespace holding that address (`ip netns exec lt-node2 sh -c ...`) instead of ssh.
# No sshd, no keys. pml ob1 with btl tcp,self and both the run-time (oob) and the MPI
# traffic restricted to 10.200.0.0/24, so every message between the nodes crosses the veth.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=$root/build
scene=$root/tests/data/run/room.toml
photons=4M
every=200k
max_bytes=16M
collectives=1
repeats=1
seed=7

die() { echo "two_nodes.sh: $*" >&2; exit 2; }
while (($#)); do
    case $1 in
        --build) build=${2:?--build needs a directory}; shift 2 ;;
        --scene) scene=${2:?--scene needs a file}; shift 2 ;;
        --photons) photons=${2:?--photons needs a count}; shift 2 ;;
        --report-every-photons) every=${2:?--report-every-photons needs a count}; shift 2 ;;
        --repeats) repeats=${2:?--repeats needs a count}; shift 2 ;;
        --max-bytes) max_bytes=${2:?--max-bytes needs a size}; shift 2 ;;
        --no-collectives) collectives=0; shift ;;
        -h | --help) sed -n '2,17p' "$0"; exit 0 ;;
        *) die "unknown option '$1' (see --help)" ;;
    esac
done

[[ $(id -u) == 0 ]] || die "needs root: it creates network namespaces and a veth pair (run it with sudo)"
for tool in ip mpirun ss; do
    command -v "$tool" >/dev/null || die "'$tool' not found (Debian: iproute2, openmpi-bin)"
done
py=/usr/bin/python3
"$py" -c 'import h5py, numpy' 2>/dev/null || die "$py with h5py and numpy needed (Debian: python3-h5py)"
lux=$build/src/luxtrace
bench_bin=$build/bench/mpi_collectives
[[ -x $lux ]] || die "$lux: no luxtrace binary (build first, or give --build DIR)"
[[ $collectives == 0 || -x $bench_bin ]] || die "$bench_bin: not built (cmake --build $build --target mpi_collectives, or --no-collectives)"
[[ -f $scene ]] || die "$scene: no such scene file"
scene=$(cd "$(dirname "$scene")" && pwd)/$(basename "$scene")

ns=(lt-node1 lt-node2)
dev=(lt-veth1 lt-veth2)
addr=(10.200.0.1 10.200.0.2)
subnet=10.200.0.0/24
work=$(mktemp -d /tmp/lt-two-nodes.XXXXXX)

# Ends what still runs in our namespaces (an orted left by a failed mpirun), then deletes
# them; deleting a namespace deletes its end of the veth pair, and so the pair.
teardown() {
    for n in "${ns[@]}"; do
        if [[ -e /run/netns/$n ]]; then
            local pids
            mapfile -t pids < <(ip netns pids "$n" || true)
            ((${#pids[@]} == 0)) || kill "${pids[@]}" 2>/dev/null || true
            ip netns del "$n" 2>/dev/null || true
        fi
    done
}
watcher=
# shellcheck disable=SC2317  # reached through the trap
cleanup() {
    local status=$?
    [[ -z $watcher ]] || kill "$watcher" 2>/dev/null || true
    teardown
    rm -rf "$work"
    exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# Idempotent: a namespace of an earlier run killed with -9 is removed first.
teardown
for i in 0 1; do ip netns add "${ns[$i]}"; done
ip link add "${dev[0]}" netns "${ns[0]}" type veth peer name "${dev[1]}" netns "${ns[1]}"
for i in 0 1; do
    ip -n "${ns[$i]}" addr add "${addr[$i]}/24" dev "${dev[$i]}"
    ip -n "${ns[$i]}" link set lo up
    ip -n "${ns[$i]}" link set "${dev[$i]}" up
done
echo "nodes: ${ns[0]} ${addr[0]} (${dev[0]}) <-> ${ns[1]} ${addr[1]} (${dev[1]}), veth pair"

cat >"$work/agent" <<EOF
#!/bin/sh
# plm_rsh_agent: Open MPI calls it as 'agent HOST COMMAND...', as it would call ssh.
host=\$1; shift
case \$host in
    ${addr[0]}) exec ip netns exec ${ns[0]} /bin/sh -c "\$*" ;;
    ${addr[1]}) exec ip netns exec ${ns[1]} /bin/sh -c "\$*" ;;
    *) echo "two_nodes agent: no namespace for host '\$host'" >&2; exit 1 ;;
esac
EOF
chmod +x "$work/agent"
printf '%s slots=2\n%s slots=2\n' "${addr[0]}" "${addr[1]}" >"$work/hosts"

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# --map-by node: rank r on node r mod 2. (The commas below are Open MPI's lists.)
# shellcheck disable=SC2054
mpi=(ip netns exec "${ns[0]}" mpirun --hostfile "$work/hosts" --map-by node --bind-to none
     --mca plm_rsh_agent "$work/agent" --mca plm_rsh_no_tree_spawn 1
     --mca oob_tcp_if_include "$subnet" --mca pml ob1 --mca btl tcp,self --mca btl_tcp_if_include "$subnet")

veth_bytes() {  # "rx tx" of node 1's end, as the namespace counts them
    ip netns exec "${ns[0]}" cat "/sys/class/net/${dev[0]}/statistics/rx_bytes" \
        "/sys/class/net/${dev[0]}/statistics/tx_bytes" | tr '\n' ' '
}
now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { print b - a }'; }

echo
echo "== where the ranks run (network namespace, interface and address on the subnet)"
for n in 2 4; do
    # shellcheck disable=SC2016  # expanded by each rank's shell
    "${mpi[@]}" -n "$n" /bin/sh -c 'n=$1; set -- $(ip -br -4 addr show to "$2")
        echo "  rank $OMPI_COMM_WORLD_RANK of $n in $(ip netns identify $$) (${1%@*} $3)"' sh "$n" "$subnet" |
        sort -k2n
done

# Watches node 2 while a run goes on, until told to stop: its established TCP connections
# to node 1 and the processes that own them (ss -p).
watch_tcp() {
    local out=$1 stop=$2
    while [[ ! -e $stop && -e /run/netns/${ns[1]} ]]; do
        ip netns exec "${ns[1]}" ss -Htnp state established dst "${addr[0]}" >>"$out" || true
        sleep 0.2
    done
}

# A run whose output goes to a log (shown if it fails); sets "took" to its wall time.
timed_run() {  # name command...
    local name=$1 t0 t1
    shift
    t0=$(now)
    if ! "$@" run "$scene" --photons "$photons" --seed "$seed" --threads 1 --report-every-photons "$every" \
        --quiet --output "$work/$name.h5" >"$work/$name.log" 2>&1; then
        cat "$work/$name.log" >&2
        die "the run '$name' failed"
    fi
    t1=$(now)
    took=$(elapsed "$t0" "$t1")
}

run_two_nodes() {  # name ranks
    local name=$1 n=$2 before after
    before=$(veth_bytes)
    rm -f "$work/$name.stop" "$work/$name.tcp"
    watch_tcp "$work/$name.tcp" "$work/$name.stop" &
    watcher=$!
    timed_run "$name" "${mpi[@]}" -n "$n" "$lux"
    touch "$work/$name.stop"
    wait "$watcher"
    watcher=
    after=$(veth_bytes)
    read -r rx0 tx0 <<<"$before"
    read -r rx1 tx1 <<<"$after"
    printf '  %s: %d ranks over TCP, wall %.2f s; veth %s: %d bytes received, %d sent\n' \
        "$name" "$n" "$took" "${dev[0]}" $((rx1 - rx0)) $((tx1 - tx0))
}

echo
echo "== luxtrace run $(basename "$scene"), $photons photons, seed $seed, reductions every $every photons, 1 thread per rank"
for ((r = 1; r <= repeats; ++r)); do
    ((repeats == 1)) || echo " repeat $r of $repeats"
    timed_run one "$lux"
    printf '  one: 1 rank, no MPI launcher, wall %.2f s\n' "$took"
    timed_run shm mpirun -n 2 --bind-to none --mca pml ob1 --mca btl self,vader --mca oob_tcp_if_include lo "$lux"
    printf '  shm: 2 ranks on one node over shared memory (for comparison), wall %.2f s\n' "$took"
    run_two_nodes two 2
    run_two_nodes four 4
done
for name in two four; do
    echo "  TCP connections node 2 -> node 1 seen during the last '$name' run (ss in ${ns[1]}):"
    awk '{ proc = $NF; sub(/.*\(\("/, "", proc); sub(/".*/, "", proc); print "    " $3 " -> " $4 "  " proc }' \
        "$work/$name.tcp" | sort -u
done

# Every integer dataset outside /history and /checkpoint (the tallies: counts, sums of
# squares, replicate and direct counts, the mesh's indices) and the photon count, bit for
# bit. Float datasets are listed too; they are estimates made from those counts.
compare() {
    "$py" - "$@" <<'PY'
import sys, h5py, numpy as np
a, b = (h5py.File(p, "r") for p in sys.argv[1:3])
def datasets(f):
    out = {}
    def visit(name, obj):
        if isinstance(obj, h5py.Dataset) and not name.startswith(("history", "checkpoint")):
            out[name] = obj
    f.visititems(visit)
    return out
da, db = datasets(a), datasets(b)
bad, ints, total, floats_same, floats = 0, 0, 0, 0, 0
if int(a.attrs["photons"]) != int(b.attrs["photons"]):
    print("    photons differ"); bad += 1
for name in sorted(set(da) | set(db)):
    if name not in da or name not in db:
        print(f"    {name}: only in one file"); bad += 1; continue
    x, y = da[name], db[name]
    if x.dtype.kind in "iu":
        ints += 1
        same = x.shape == y.shape and np.array_equal(x[()], y[()])
        if x.dtype.kind == "u" and x.dtype.itemsize == 8:
            total += int(x[()].sum(dtype=np.uint64))
        if not same:
            print(f"    {name}: differs"); bad += 1
    elif x.dtype.kind == "f":
        floats += 1
        floats_same += x.shape == y.shape and x[()].tobytes() == y[()].tobytes()
print(f"    {ints} integer datasets, {'all identical' if bad == 0 else f'{bad} differ'} "
      f"(uint64 sum {total}); {floats_same} of {floats} float datasets bit-identical; "
      f"photons {int(a.attrs['photons'])}, ranks {int(a.attrs['ranks'])} and {int(b.attrs['ranks'])}")
sys.exit(1 if bad or total == 0 else 0)
PY
}
status=0
for other in shm two four; do
    echo "  one vs $other:"
    compare "$work/one.h5" "$work/$other.h5" || status=1
done
[[ $status == 0 ]] && echo "  tallies bit-identical: 1 rank = 2 ranks on one node = 2 and 4 ranks on two nodes" ||
    echo "  FAIL: the tallies differ"

if [[ $collectives == 1 ]]; then
    echo
    echo "== mpi_collectives, 2 ranks, one per node, TCP over the veth (up to $max_bytes per rank)"
    before=$(veth_bytes)
    "${mpi[@]}" -n 2 "$bench_bin" --max-bytes "$max_bytes"
    after=$(veth_bytes)
    read -r rx0 tx0 <<<"$before"
    read -r rx1 tx1 <<<"$after"
    echo "  veth ${dev[0]}: $((rx1 - rx0)) bytes received, $((tx1 - tx0)) sent"
fi
exit $status
