#!/bin/sh
# bench/lammps_side_by_side.sh -- bond throughput of pd_bench and LAMMPS PERI on the same scene.
# Scene (both codes): simple-cubic box of N^3 nodes, dx = 2^-10 m (binary-exact coordinates, so
# the bonds at |xi| = delta exactly are found by both codes), delta = m dx, E = 200 GPa, nu = 1/4,
# rho = 7850 kg/m^3, S velocity-Verlet steps, no bond breaking.
#   ours:   pd_bench --what step (pd::Explicit::step: force + integration), PMB and LPS, T threads;
#   LAMMPS: lmp (package PERI), peri/pmb (and peri/lps with --lammps-lps), 1 MPI rank, fix nve;
#           time = "Loop time" of `run` (setup, i.e. bond-family construction, excluded); a run
#           whose compute damage/atom is not 0 throughout is refused (lammps_peri.in says why).
# One bond update = one bond force evaluation in one step, bonds = ordered pairs i->j: LAMMPS'
# fix PERI_NEIGH keeps every partner of every atom ("total # of bonds" in its log), and
# pair peri/pmb visits each of them once per step, as we do. Both counts are printed and must
# agree. Rate = bonds * steps / time. --repeat R runs R interleaved rounds (every configuration of
# both codes once per round, one process each) and keeps the fastest run of each configuration:
# on a shared machine, a burst of other work then spoils one round, not all repeats at once.
# Usage: lammps_side_by_side.sh PD_BENCH [--sizes "20 30 40"] [--m 3] [--steps 100] [--repeat 3]
#        [--threads "1 2"] [--lammps-lps] [--reuse-lammps CSV] [--out DIR]
# --reuse-lammps takes the LAMMPS rows of an earlier side_by_side.csv instead of running lmp
# (to compare several pd_bench builds against one set of LAMMPS runs).
# Writes DIR/side_by_side_runs.csv (every run, with its round and the 1-min load average),
# DIR/side_by_side.csv (fastest run per configuration) and prints the table with the ratios.
# Without `lmp` on PATH (Debian package lammps) the LAMMPS runs are skipped with a message;
# the environment variable LMP overrides the executable (LMP= forces the skip).
set -eu

usage() { echo "usage: $0 PD_BENCH [--sizes \"20 30 40\"] [--m 3] [--steps 100] [--repeat 3] [--threads \"1 2\"] [--lammps-lps] [--reuse-lammps CSV] [--out DIR]" >&2; exit 2; }
[ $# -ge 1 ] || usage
PD_BENCH=$1; shift
SIZES="20 30 40"; M=3; STEPS=100; REPEAT=3; THREADS="1 2"; LAMMPS_LPS=0; OUT=bench_out; REUSE=
while [ $# -gt 0 ]; do
    case $1 in
        --sizes) SIZES=$2; shift 2 ;;
        --m) M=$2; shift 2 ;;
        --steps) STEPS=$2; shift 2 ;;
        --repeat) REPEAT=$2; shift 2 ;;
        --threads) THREADS=$2; shift 2 ;;
        --lammps-lps) LAMMPS_LPS=1; shift ;;
        --reuse-lammps) REUSE=$2; shift 2 ;;
        --out) OUT=$2; shift 2 ;;
        *) echo "$0: error: unknown option '$1'" >&2; exit 2 ;;
    esac
done
[ -x "$PD_BENCH" ] || { echo "$0: error: pd_bench '$PD_BENCH' is not an executable" >&2; exit 2; }
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
CSV=$OUT/side_by_side.csv

DX=0.0009765625                                   # 2^-10 m
E=200e9; NU=0.25                                  # Pa, -
K=$(awk -v E=$E -v nu=$NU 'BEGIN { printf "%.17g", E / (3 * (1 - 2 * nu)) }')   # bulk modulus [Pa]
G=$(awk -v E=$E -v nu=$NU 'BEGIN { printf "%.17g", E / (2 * (1 + nu)) }')       # shear modulus [Pa]
# PMB micromodulus c = 18 K / (pi delta^4) [N/m^6] (Silling & Askari 2005; models/pmb.hpp).
C=$(awk -v K=$K -v d=$DX -v m=$M 'BEGIN { D = m * d; printf "%.17g", 18 * K / (atan2(0, -1) * D^4) }')
# LAMMPS bonds r^2 <= cut^2: cut = delta (1 + 1e-10), the tolerance of pd::build_bonds.
CUT=$(awk -v d=$DX -v m=$M 'BEGIN { printf "%.17g", m * d * (1 + 1e-10) }')
VOL=$(awk -v d=$DX 'BEGIN { printf "%.17g", d * d * d }')

RUNS=$OUT/side_by_side_runs.csv
HEADER="code,model,n,nodes,bonds,steps,threads,wall_s,bond_updates_per_s"
echo "$HEADER,round,load1" > "$RUNS"

LMP=${LMP-$(command -v lmp || true)}              # LMP= (empty) forces the skip
if [ -n "$REUSE" ]; then
    [ -r "$REUSE" ] || { echo "$0: error: cannot read '$REUSE'" >&2; exit 2; }
    grep '^lammps,' "$REUSE" | sed 's/$/,reused,/' >> "$RUNS" || true
    echo "lammps_side_by_side: LAMMPS rows taken from $REUSE (same m, dx, steps required)."
    LMP=
elif [ -n "$LMP" ]; then
    rm -f "$OUT"/lammps_*.log
else
    echo "lammps_side_by_side: lmp not found (install the Debian package 'lammps'); LAMMPS runs skipped, ours only."
fi

load1() { cut -d' ' -f1 /proc/loadavg; }

# ours MODEL N T ROUND -> appends a row
ours() {
    line=$("$PD_BENCH" --model "$1" --n "$2" --m "$M" --steps "$STEPS" --threads "$3" --what step \
           --dx "$DX" --no-header)
    echo "ours,$1,$2,${line#*,},$4,$(load1)" >> "$RUNS"
}

# lammps STYLE N ROUND -> appends a row (bonds from LAMMPS' own log)
lammps() {
    log=$OUT/lammps_$1_n$2.log
    OMP_NUM_THREADS=1 "$LMP" -in "$HERE/lammps_peri.in" -log "$log" -screen none \
        -var N "$2" -var dx "$DX" -var cut "$CUT" -var vol "$VOL" -var style "$1" \
        -var c "$C" -var K "$K" -var G "$G" -var steps "$STEPS" -var repeat 1 > /dev/null
    awk -v style="$1" -v n="$2" -v steps="$STEPS" -v round="$3" -v load="$(load1)" '
        /total # of bonds =/ { bonds = $NF }
        /^Step / { thermo = 1; next }
        /^Loop time of/ { t = $4; atoms = $(NF - 1); thermo = 0 }
        thermo && NF == 4 && $3 + 0 > 0 { damaged = $3 }  # c_dmax of compute damage/atom (lammps_peri.in)
        END {
            if (t == "" || bonds == "") { print "lammps_side_by_side: no loop time in log" > "/dev/stderr"; exit 1 }
            if (damaged != "") { print "lammps_side_by_side: LAMMPS " style " n " n ": bonds broke (max damage " damaged "), not a reference" > "/dev/stderr"; exit 1 }
            printf "lammps,%s,%s,%s,%s,%s,1,%.6f,%.4e,%s,%s\n", style, n, atoms, bonds, steps, t, bonds * steps / t, round, load
        }' "$log" >> "$RUNS"
}

r=1
while [ "$r" -le "$REPEAT" ]; do
    for n in $SIZES; do
        for t in $THREADS; do
            ours pmb "$n" "$t" "$r"
            ours lps "$n" "$t" "$r"
        done
        if [ -n "$LMP" ]; then
            lammps pmb "$n" "$r"
            if [ "$LAMMPS_LPS" = 1 ]; then lammps lps "$n" "$r"; fi
        fi
    done
    r=$((r + 1))
done

# Fastest run per configuration (code, model, N, threads), in order of first appearance.
echo "$HEADER" > "$CSV"
awk -F, -v OFS=, '
    NR == 1 { next }
    { key = $1 FS $2 FS $3 FS $7
      if (!(key in best)) order[++nk] = key
      if (!(key in best) || $8 + 0 < best[key] + 0) { best[key] = $8; row[key] = $1 OFS $2 OFS $3 OFS $4 OFS $5 OFS $6 OFS $7 OFS $8 OFS $9 } }
    END { for (a = 1; a <= nk; a++) print row[order[a]] }' "$RUNS" >> "$CSV"

# Table: rate [bond updates/s]; per core = rate / threads; ratios to LAMMPS on 1 core.
echo
echo "Side by side: m = $M, dx = $DX m, $STEPS steps, fastest of $REPEAT rounds; bond updates/s, bonds = ordered pairs i->j"
awk -F, '
    NR == 1 { next }
    { rate[$1 "," $2 "," $3 "," $7] = $9; bonds[$1 "," $3] = $5; nodes[$3] = $4
      if (!($3 in seen)) { seen[$3] = 1; order[++nn] = $3 }
      if ($1 == "ours" && !($7 in tseen)) { tseen[$7] = 1; th[++nt] = $7 } }
    function ratio(r, t, ref) { return ref == "" ? "-" : sprintf("%.2f", r / t / ref) }
    END {
        printf "%-4s %-7s %-9s %-7s %-5s %-7s %12s %12s %12s %12s\n", "N", "nodes", "bonds", "code", "model",
               "threads", "updates/s", "per core", "x LMP pmb", "x LMP same"
        for (a = 1; a <= nn; a++) {
            n = order[a]
            lp = rate["lammps,pmb," n ",1"]; ll = rate["lammps,lps," n ",1"]
            if (lp != "" && bonds["ours," n] != bonds["lammps," n])
                printf "WARNING: bond counts differ at N = %s: ours %s, LAMMPS %s\n", n, bonds["ours," n], bonds["lammps," n]
            for (b = 1; b <= nt; b++) for (mi = 1; mi <= 2; mi++) {
                model = mi == 1 ? "pmb" : "lps"; t = th[b]; r = rate["ours," model "," n "," t]
                if (r == "") continue
                printf "%-4s %-7s %-9s %-7s %-5s %-7s %12.3e %12.3e %12s %12s\n", n, nodes[n], bonds["ours," n], "ours",
                       model, t, r, r / t, ratio(r, t, lp), ratio(r, t, model == "pmb" ? lp : ll)
            }
            if (lp != "") printf "%-4s %-7s %-9s %-7s %-5s %-7s %12.3e %12.3e %12s %12s\n", n, nodes[n], bonds["lammps," n],
                                 "LAMMPS", "pmb", 1, lp, lp, "1", "1"
            if (ll != "") printf "%-4s %-7s %-9s %-7s %-5s %-7s %12.3e %12.3e %12s %12s\n", n, nodes[n], bonds["lammps," n],
                                 "LAMMPS", "lps", 1, ll, ll, ratio(ll, 1, lp), "1"
        }
    }' "$CSV"
echo "CSV: $CSV (all runs: $RUNS)"
