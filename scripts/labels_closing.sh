#!/usr/bin/env bash
# scripts/labels_closing.sh - the figures of issue 11's closing note (docs/labels.md section 9):
#   1. the paper's three cases (10.5 Hz / 3.7 mm, 10.2 and 9.8 Hz / 4.0 mm) at 3, 4 and 15
#      elements: label, lambda +- sigma, evidence and certificate (transient runs of the
#      inputs/moon_shaw_*.nml decks, the mesh set by overrides of &beam n_elem and &stops node);
#      1b. the 4-element cases again with the paper's integrator, certified against the exact run;
#   2. the 4.0 mm line 8.4-11.0 Hz (inputs/sweep_line_4mm.nml, 261 points swept up) run twice,
#      certification off and on, one after the other in this one run: labels, certificate
#      counts per label, and the CPU seconds of both (sum of the points' seconds_label and
#      seconds_certify from the result files) and their ratio.
#
# Usage:
#   scripts/labels_closing.sh [OUTDIR]          (default results/labels_closing)
#   GAPBEAM=/path/to/gapbeam scripts/labels_closing.sh [OUTDIR]
# Prints the summary (also OUTDIR/summary.txt). OMP_NUM_THREADS=1 unless set: CPU seconds of
# one core. Cost: about 10 CPU minutes (release build).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "${root}"
out=${1:-results/labels_closing}
# shellcheck source=setup.sh
source "${root}/scripts/setup.sh" >/dev/null
export OPENBLAS_NUM_THREADS=1
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
if [[ -n ${GAPBEAM:-} ]]; then
   exe=${GAPBEAM}
else
   fpm build --profile release >/dev/null
   exe=$(fpm run gapbeam --profile release --runner echo 2>/dev/null | tail -n 1)
   [[ ${exe} == /* ]] || exe=${root}/${exe}
fi
mkdir -p "${out}"
summary=${out}/summary.txt
{
   echo "labels_closing: $(date -u +%Y-%m-%dT%H:%MZ), commit $(git rev-parse --short HEAD)" \
        "$(git diff --quiet && echo clean || echo modified), ${OMP_NUM_THREADS} thread(s)," \
        "$(nproc --all) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
   echo "executable: ${exe}"
   echo
   echo "== 1. The paper's cases: label, lambda +- sigma (1/s), evidence, certificate"
} >"${summary}"

for case in 10p5hz 10p2hz 9p8hz; do
   for n in 3 4 15; do
      name=${case}_${n}el
      /usr/bin/time -f '%U %e' -o "${out}/${name}.time" "${exe}" "inputs/moon_shaw_${case}.nml" \
         "&beam n_elem = ${n} /" "&stops node = $((n + 1)) /" \
         "&job output = '${out}/${name}' /" --quiet >"${out}/${name}.out" 2>"${out}/${name}.err"
      {
         echo "-- ${case}, ${n} elements ($(head -c 40 "${out}/${name}.time" | \
            awk '{printf "%s s CPU, %s s wall for the whole run", $1, $2}'))"
         grep -E '^(forcing|method|attractor|evidence|certificate|cpu):' "${out}/${name}.out"
      } >>"${summary}"
   done
done

{
   echo
   echo "== 1b. The paper's cases, 4 elements, with the paper's integrator (Newmark, half-step"
   echo "   residual 1 %, fixed-point stop force): the certificate's accuracy check is the exact run"
} >>"${summary}"
for case in 10p5hz 10p2hz 9p8hz; do
   name=${case}_4el_paper
   /usr/bin/time -f '%U %e' -o "${out}/${name}.time" "${exe}" "inputs/moon_shaw_${case}.nml" \
      "&solver method = 'newmark', step_control = 'half_step', half_step_tolerance = 0.01, stop_solution = 'fixed_point' /" \
      "&job output = '${out}/${name}' /" --quiet >"${out}/${name}.out" 2>"${out}/${name}.err"
   {
      echo "-- ${case}, 4 elements, paper's integrator ($(head -c 40 "${out}/${name}.time" | \
         awk '{printf "%s s CPU, %s s wall for the whole run", $1, $2}'))"
      grep -E '^(attractor|evidence|certificate|cpu):' "${out}/${name}.out"
   } >>"${summary}"
done

line=("inputs/sweep_line_4mm.nml"
   "&sweep frequency_start_hz = 8.4, frequency_end_hz = 11.0, n_frequency = 261, checkpoint = .false., progress = .false. /")
for cert in off on; do
   flag=$([[ ${cert} == on ]] && echo .true. || echo .false.)
   /usr/bin/time -f '%U %e' -o "${out}/line_${cert}.time" "${exe}" "${line[@]}" \
      "&diagnostics certify = ${flag} /" "&job output = '${out}/line_4mm_cert_${cert}' /" \
      --quiet >"${out}/line_${cert}.out" 2>"${out}/line_${cert}.err" || true
done

python3 - "${out}" >>"${summary}" <<'EOF'
import sys, collections
import h5py, numpy as np
out = sys.argv[1]
def load(cert):
    with h5py.File(f"{out}/line_4mm_cert_{cert}.h5", "r") as f:
        s = f["sweep"]
        txt = lambda k: [x.decode() if isinstance(x, bytes) else str(x) for x in s[k][()]]
        return dict(f=s["frequency_hz"][()], label=txt("label_text"),
                    cert=s["certificate"][()], sl=s["seconds_label"][()],
                    sc=s["seconds_certify"][()], lyap=s["lyapunov"][()],
                    status=s["status"][()], reason=txt("certificate_reason"))
def times(cert):
    u, e = open(f"{out}/line_{cert}.time").read().split()[:2]
    return float(u), float(e)
off, on = load("off"), load("on")
print()
print("== 2. The 4.0 mm line, 8.4-11.0 Hz, 261 points swept up (inputs/sweep_line_4mm.nml)")
for name, d in (("certification off", off), ("certification on", on)):
    c = collections.Counter(d["label"])
    print(f"{name}: labels " + ", ".join(f"{k} {v}" for k, v in sorted(c.items())))
print("labels equal in both runs at", sum(a == b for a, b in zip(off["label"], on["label"])),
      "of", len(on["label"]), "points")
print("certificates (certification on), per label: certified / disputed")
per = collections.defaultdict(lambda: [0, 0, 0])
for l, c in zip(on["label"], on["cert"]):
    per[l][{1: 0, 2: 1}.get(int(c), 2)] += 1
for l in sorted(per):
    print(f"  {l:12s} {per[l][0]:4d} certified, {per[l][1]:4d} disputed"
          + (f", {per[l][2]} none" if per[l][2] else ""))
tot = [sum(v[i] for v in per.values()) for i in range(3)]
print(f"  {'all':12s} {tot[0]:4d} certified, {tot[1]:4d} disputed")
print("chaotic bands (certification on, labels along the line):")
f = on["f"]; lab = on["label"]; i = 0
while i < len(f):
    if lab[i] == "chaotic":
        j = i
        while j + 1 < len(f) and lab[j + 1] == "chaotic":
            j += 1
        nd = sum(1 for k in range(i, j + 1) if on["cert"][k] == 2)
        print(f"  {f[i]:.2f}-{f[j]:.2f} Hz: {j - i + 1} points, {nd} disputed")
        i = j + 1
    else:
        i += 1
print("disputed points:")
for k in range(len(f)):
    if on["cert"][k] == 2:
        print(f"  {f[k]:.2f} Hz {lab[k]}: {on['reason'][k][:150]}")
print()
print("== 3. Cost of certification (CPU seconds, one thread, the two runs above)")
a = float(np.nansum(off["sl"])); b = float(np.nansum(on["sl"])); c = float(np.nansum(on["sc"]))
uo, eo = times("off"); un, en = times("on")
print(f"certification off: labelled runs {a:.1f} s CPU (sum of seconds_label); "
      f"process {uo:.1f} s user, {eo:.1f} s wall")
print(f"certification on:  labelled runs {b:.1f} s + checks {c:.1f} s = {b + c:.1f} s CPU; "
      f"process {un:.1f} s user, {en:.1f} s wall")
print(f"ratio on/off: {(b + c) / a:.2f} (points' CPU), {un / uo:.2f} (process user time); "
      f"checks / labelled run of the same run: {c / b:.2f}")
EOF
cat "${summary}"

# 4. the cost of certifying the single runs above (from their result files)
python3 - "${out}" <<'PYEOF' | tee -a "${summary}"
import sys, glob, os
import h5py
out = sys.argv[1]
print()
print("== 4. Cost of certification of the single runs (CPU s: labelled run, checks, ratio)")
for path in sorted(glob.glob(f"{out}/*el*.h5")):
    with h5py.File(path, "r") as f:
        d = f["diagnostics"]
        sl, sc = float(d["seconds_label"][()]), float(d["seconds_certify"][()])
        am = d["accuracy_method"][()]
        am = am.decode() if isinstance(am, bytes) else str(am)
    name = os.path.basename(path)[:-3]
    print(f"  {name:18s} label {sl:6.3f} s, checks {sc:6.3f} s, ratio (label + checks) / label "
          f"{(sl + sc) / sl:4.2f}; accuracy check: {am or 'none (the run was exact)'}")
PYEOF
