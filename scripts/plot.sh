#!/usr/bin/env bash
# scripts/plot.sh - render the figures of one gapbeam run from its gnuplot-ready text files.
#
# Usage:
#   scripts/plot.sh [--format png|pdf|svg] ANALYSIS PREFIX
#   scripts/plot.sh transient results/moon_shaw_10p5hz
#   scripts/plot.sh --format pdf sweep results/sweep_line_4mm     (vector figures for a paper)
#   (scripts/run.sh calls it after a run with the program's `analysis:` and `output:` words)
#
# --format (or GAPBEAM_PLOT_FORMAT): png (default), pdf or svg; every figure is written as
# PREFIX.<figure>.<format> (scripts/terminal.gp sets the terminal). The animation is a GIF
# whatever the format.
# ANALYSIS=transient: PREFIX.history.dat  -> PREFIX.history.png  (scripts/strain_history.gp:
#                                            root strain and stop force against time, paper Fig. 3)
#                     PREFIX.poincare.dat -> PREFIX.poincare.png (scripts/poincare.gp: strain rate
#                                            against strain once per period, paper Figs. 4-9)
#                     PREFIX.shape.dat    -> PREFIX.animation.gif (scripts/animation.gp: the beam
#                                            against its stop over the first 3 periods of history;
#                                            only with &output state_history = .true.)
#                     PREFIX.orbit.dat + PREFIX.supports.dat -> PREFIX.orbit.png (scripts/orbit.gp:
#                                            v against w at each support with its clearance circle;
#                                            two-plane runs, &beam planes = 2)
# ANALYSIS=modes:     PREFIX.shapes.dat (+ PREFIX.modes.dat for the legend's frequencies,
#                     PREFIX.shape_curves.dat for the shapes between the nodes)
#                                         -> PREFIX.shapes.png   (scripts/mode_shapes.gp)
# ANALYSIS=sweep:     PREFIX.bifurcation.dat -> PREFIX.bifurcation.png (scripts/bifurcation.gp:
#                                            Poincare root strain against the forcing frequency,
#                                            or against the amplitude when the sweep has a single
#                                            frequency: distinct values of column 1 of
#                                            PREFIX.sweep.dat)
#                     PREFIX.sweep.dat    -> PREFIX.chaos_map.png (scripts/chaos_map.gp: class of
#                                            each point, chaotic / undecided / period p, over the
#                                            frequency-amplitude plane; a strip for a line sweep)
#                                         -> PREFIX.lyapunov.png (scripts/lyapunov.gp: largest
#                                            Lyapunov exponent with error bars, same x as above)
#                                         -> PREFIX.work_rate_map.png (scripts/work_rate_map.gp:
#                                            normal work rate of all supports, log colour, with the
#                                            regime of each point; grids whose work rate is not all
#                                            zero, e.g. tube maps over the clearance)
#                     (PREFIX may be a shard's, PREFIX.shard_I_of_N, or a merged file's prefix.)
# ANALYSIS=work_precision: PREFIX.wp_<series>.dat (all of them) -> PREFIX.work_precision.png
#                                           (scripts/work_precision.gp: relative final-state error
#                                            against elapsed time, log-log, one line per series, the
#                                            exact integrator as a single marker)
# ANALYSIS=stability: PREFIX.spectral_radius.dat -> PREFIX.spectral_radius.png
#                                           (scripts/spectral_radius.gp: spectral radius of one step
#                                            against omega dt, one curve per method, with the
#                                            theoretical stability limits)
# ANALYSIS=model_size: PREFIX.model_size.dat (+ PREFIX.model_size.txt for the candidates' names)
#                                         -> PREFIX.model_size.png (scripts/model_size.gp: Poincare
#                                            distance to the reference against run time, log-log,
#                                            acceptable candidates filled, tolerance line)
# ANALYSIS=continuation: PREFIX.branches.dat (+ .bifurcations.dat) -> PREFIX.diagram.png
#                                           (scripts/continuation.gp: Poincare root strain of the
#                                            continued orbits, stable solid, unstable dashed, the
#                                            bifurcations marked, over the points of the overlay
#                                            sweep named by &continuation overlay, if it was run)
#                     PREFIX.multipliers.dat -> PREFIX.multipliers.png (scripts/multipliers.gp)
#                     PREFIX.curves.dat (if any curve) -> PREFIX.curves.png
#                                           (scripts/continuation_curves.gp: the curves over the
#                                            overlay sweep's chaos map)
# Any other ANALYSIS (calibrate, ...): nothing to plot; prints nothing, exit status 0.
# Each plot's title is the first line of its .dat file without the leading '# ' (the deck's title).
# Prints `plot: wrote FILE` per figure written. A .dat file that is missing or holds no data row
# (e.g. the deck set `&output write_text = .false.`) is reported on stderr and skipped.
# A figure is written under a temporary name and renamed when gnuplot has succeeded.
# Exit status: 0; 1 when gnuplot is missing or fails; 2 on bad usage.
set -euo pipefail

script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)

if [[ ${1:-} == -h || ${1:-} == --help ]]; then
   sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"
   exit 0
fi
fmt=${GAPBEAM_PLOT_FORMAT:-png}
if [[ ${1:-} == --format ]]; then
   fmt=${2:-}
   shift 2 || true
elif [[ ${1:-} == --format=* ]]; then
   fmt=${1#--format=}
   shift
fi
case ${fmt} in
   png | pdf | svg) ;;
   *)
      printf "plot: error: format '%s': expected png, pdf or svg\n" "${fmt}" >&2
      exit 2
      ;;
esac
if [[ $# -ne 2 || -z $2 ]]; then
   printf 'usage: scripts/plot.sh [--format png|pdf|svg] ANALYSIS PREFIX   (e.g. transient results/moon_shaw_10p5hz)\n' >&2
   exit 2
fi
analysis=$1
prefix=$2

case ${analysis} in
   transient | modes | sweep | work_precision | stability | model_size | continuation) ;;
   *) exit 0 ;;
esac

if ! command -v gnuplot >/dev/null 2>&1; then
   printf 'plot: error: gnuplot is not installed (Debian/Ubuntu: apt-get install gnuplot-nox;' >&2
   printf ' or source scripts/setup.sh); no plots of %s\n' "${prefix}" >&2
   exit 1
fi

# A text as a gnuplot single-quoted string: a quote inside is doubled, nothing else is special.
gp_quote() {
   local s=${1//\'/\'\'}
   printf "'%s'" "${s}"
}

# True when FILE exists and holds at least one data row (a line that is neither blank nor '#').
has_data() {
   [[ -f $1 ]] && grep -q -v -E '^[[:space:]]*(#|$)' -- "$1"
}

# The title of a .dat file: its first line without the leading '#' and blanks.
dat_title() {
   local line=""
   IFS= read -r line <"$1" || true
   line=${line#\#}
   line=${line#"${line%%[![:space:]]*}"}
   printf '%s' "${line}"
}

# render SCRIPT FILE GNUPLOT_ASSIGNMENTS: run gnuplot into FILE.part, rename it to FILE on success.
# FILE is given with the .png suffix; the suffix of the chosen format replaces it (a .gif stays).
render() {
   local script=$1 png=$2 assignments=$3
   if [[ ${png} == *.png ]]; then png="${png%.png}.${fmt}"; fi
   local part="${png}.part"
   local status=0
   gnuplot -e "format=$(gp_quote "${fmt}"); ${assignments}; outfile=$(gp_quote "${part}")" \
      "${script_dir}/${script}" || status=$?
   if [[ ${status} -ne 0 || ! -s ${part} ]]; then
      rm -f -- "${part}"
      printf 'plot: error: gnuplot failed on scripts/%s for %s\n' "${script}" "${png}" >&2
      exit 1
   fi
   mv -f -- "${part}" "${png}"
   printf 'plot: wrote %s\n' "${png}"
}

skip() {
   printf 'plot: %s: missing or without data rows (&output write_text = .false.?); skipped\n' \
      "$1" >&2
}

case ${analysis} in
   transient)
      for kind in history poincare; do
         dat="${prefix}.${kind}.dat"
         if ! has_data "${dat}"; then
            skip "${dat}"
            continue
         fi
         extra=""
         if [[ ${kind} == history ]]; then
            script=strain_history.gp
            # the event-located largest force of each stop (/impacts/peak_force), when python3
            # with h5py can read it: the sampled history under-reads short impacts
            peaks=$(python3 -c 'import sys, h5py; print(" ".join("%.9g" % x for x in h5py.File(sys.argv[1], "r")["impacts/peak_force"][()]))' \
               "${prefix}.h5" 2>/dev/null || true)
            if [[ -n ${peaks} ]]; then extra="; peaks=$(gp_quote "${peaks}")"; fi
         else
            script=poincare.gp
         fi
         render "${script}" "${prefix}.${kind}.png" \
            "datafile=$(gp_quote "${dat}"); plottitle=$(gp_quote "$(dat_title "${dat}")")${extra}"
      done
      # the orbits at the supports, two-plane runs
      if has_data "${prefix}.orbit.dat" && has_data "${prefix}.supports.dat"; then
         title=$(dat_title "${prefix}.orbit.dat")
         title=${title%: orbits at the supports}
         render orbit.gp "${prefix}.orbit.png" \
            "orbitfile=$(gp_quote "${prefix}.orbit.dat"); supportsfile=$(gp_quote "${prefix}.supports.dat"); plottitle=$(gp_quote "${title}")"
      fi
      # the beam in motion, when the run kept its state history
      if has_data "${prefix}.shape.dat"; then
         title=$(dat_title "${prefix}.shape.dat")
         title=${title%: deflected shape*}
         render animation.gp "${prefix}.animation.gif" \
            "datafile=$(gp_quote "${prefix}.shape.dat"); plottitle=$(gp_quote "${title}")"
      fi
      ;;
   modes)
      shapes="${prefix}.shapes.dat"
      modes="${prefix}.modes.dat"
      if ! has_data "${shapes}"; then
         skip "${shapes}"
         exit 0
      fi
      # The shapes file's title line reads '<deck title>: mode shapes (w)'; the plot says that.
      title=$(dat_title "${shapes}")
      title=${title%: mode shapes (w)}
      if has_data "${modes}"; then modes_arg=${modes}; else modes_arg=""; fi
      curves="${prefix}.shape_curves.dat"
      if has_data "${curves}"; then curves_arg=${curves}; else curves_arg=""; fi
      render mode_shapes.gp "${prefix}.shapes.png" \
         "shapesfile=$(gp_quote "${shapes}"); modesfile=$(gp_quote "${modes_arg}"); curvesfile=$(gp_quote "${curves_arg}"); plottitle=$(gp_quote "${title}")"
      ;;
   sweep)
      points="${prefix}.sweep.dat"
      bifurcation="${prefix}.bifurcation.dat"
      if ! has_data "${points}"; then
         skip "${points}"
         exit 0
      fi
      # The points file's title line reads '<deck title>: sweep points (...)'; the plots say
      # what they show themselves.
      title=$(dat_title "${points}")
      title=${title%%: sweep points*}
      # x axis: the frequency, unless the sweep has a single frequency (a line in amplitude).
      n_freq=$(awk '!/^[[:space:]]*(#|$)/ { seen[$1] = 1 } END { n = 0; for (f in seen) n++; print n }' \
         "${points}")
      if [[ ${n_freq} -gt 1 ]]; then xaxis=frequency; else xaxis=amplitude; fi
      # A sweep over other deck variables (issue 11) names them in the header line
      # '# columns: NAME [UNIT], NAME [UNIT], ...': columns 1 and 2 are its x and y axes.
      axes=""
      columns=$(grep -m1 '^# columns:' "${points}" || true)
      col1=$(printf '%s' "${columns#'# columns: '}" | cut -d, -f1 | sed 's/^ *//')
      col2=$(printf '%s' "${columns#'# columns: '}" | cut -d, -f2 | sed 's/^ *//')
      if [[ -n ${col1} && ${col1} != 'frequency [Hz]' ]]; then
         axes+="label1=$(gp_quote "${col1}"); "
      fi
      if [[ -n ${col2} && ${col2} != 'amplitude_pp [m]' ]]; then
         axes+="label2=$(gp_quote "${col2}"); scale2=1.0; "
      fi
      common="${axes}plottitle=$(gp_quote "${title}"); xaxis=$(gp_quote "${xaxis}")"
      if has_data "${bifurcation}"; then
         render bifurcation.gp "${prefix}.bifurcation.png" \
            "datafile=$(gp_quote "${bifurcation}"); ${common}"
      else
         skip "${bifurcation}"
      fi
      render chaos_map.gp "${prefix}.chaos_map.png" \
         "datafile=$(gp_quote "${points}"); ${axes}plottitle=$(gp_quote "${title}")"
      render lyapunov.gp "${prefix}.lyapunov.png" "datafile=$(gp_quote "${points}"); ${common}"
      # the work-rate map, when some point's supports did work (column 18: normal work rate)
      if [[ ${n_freq} -gt 1 ]] && awk '!/^[[:space:]]*(#|$)/ && $18 > 0 { found = 1 } END { exit !found }' \
         "${points}"; then
         render work_rate_map.gp "${prefix}.work_rate_map.png" \
            "datafile=$(gp_quote "${points}"); plottitle=$(gp_quote "${title}")"
      fi
      ;;
   work_precision)
      # One table per series, PREFIX.wp_<series>.dat, title line '<deck title>: <series>'; the
      # script finds them itself. The plot's title: the first table with data rows, less the series.
      first=""
      for dat in "${prefix}".wp_*.dat; do
         if has_data "${dat}"; then
            first=${dat}
            break
         fi
      done
      if [[ -z ${first} ]]; then
         skip "${prefix}.wp_*.dat"
         exit 0
      fi
      title=$(dat_title "${first}")
      title=${title%: *}
      render work_precision.gp "${prefix}.work_precision.png" \
         "prefix=$(gp_quote "${prefix}"); plottitle=$(gp_quote "${title}")"
      ;;
   stability)
      radius="${prefix}.spectral_radius.dat"
      if ! has_data "${radius}"; then
         skip "${radius}"
         exit 0
      fi
      # The title line reads '<deck title>: spectral radius of one step, ...'; the plot says that.
      title=$(dat_title "${radius}")
      title=${title%%: spectral radius*}
      render spectral_radius.gp "${prefix}.spectral_radius.png" \
         "datafile=$(gp_quote "${radius}"); plottitle=$(gp_quote "${title}")"
      ;;
   continuation)
      # The overlay (a sweep prefix, &continuation overlay) is named on the tables' second line.
      branches="${prefix}.branches.dat"
      if ! has_data "${branches}"; then
         skip "${branches}"
         exit 0
      fi
      title=$(dat_title "${branches}")
      overlay=$(sed -n 's/^# overlay: //p' "${branches}" | head -n 1)
      sweep_bif=""
      sweep_pts=""
      if [[ -n ${overlay} ]] && has_data "${overlay}.bifurcation.dat"; then
         sweep_bif="${overlay}.bifurcation.dat"
      fi
      if [[ -n ${overlay} ]] && has_data "${overlay}.sweep.dat"; then
         sweep_pts="${overlay}.sweep.dat"
      fi
      if [[ -n ${overlay} && -z ${sweep_bif} ]]; then
         printf 'plot: overlay %s: no sweep tables (run its sweep deck first); none drawn\n' \
            "${overlay}" >&2
      fi
      # branches of a two-parameter run lie at one amplitude: only that row of a grid sweep
      amp=$(sed -n 's/^# branches at: &forcing amplitude_pp = //p' "${branches}" | head -n 1)
      [[ -n ${amp} ]] || amp=-1
      render continuation.gp "${prefix}.diagram.png" \
         "datafile=$(gp_quote "${branches}"); bifile=$(gp_quote "${prefix}.bifurcations.dat"); sweepfile=$(gp_quote "${sweep_bif}"); sweepname=$(gp_quote "${overlay}"); sweep_amp=${amp}; plottitle=$(gp_quote "${title}")"
      if has_data "${prefix}.multipliers.dat"; then
         render multipliers.gp "${prefix}.multipliers.png" \
            "datafile=$(gp_quote "${prefix}.multipliers.dat"); plottitle=$(gp_quote "${title}")"
      fi
      if has_data "${prefix}.curves.dat"; then
         render continuation_curves.gp "${prefix}.curves.png" \
            "datafile=$(gp_quote "${prefix}.curves.dat"); sweepfile=$(gp_quote "${sweep_pts}"); plottitle=$(gp_quote "${title}")"
      fi
      ;;
   model_size)
      ladder="${prefix}.model_size.dat"
      report="${prefix}.model_size.txt"
      if ! has_data "${ladder}"; then
         skip "${ladder}"
         exit 0
      fi
      # The title line reads '<deck title>: model-size ladder (...)'; the plot says what it shows.
      title=$(dat_title "${ladder}")
      title=${title%%: model-size ladder*}
      # The report gives the candidates' names; without it the points are labelled #<candidate>.
      if [[ -f ${report} ]]; then names=${report}; else names=""; fi
      render model_size.gp "${prefix}.model_size.png" \
         "datafile=$(gp_quote "${ladder}"); namefile=$(gp_quote "${names}"); plottitle=$(gp_quote "${title}")"
      ;;
esac
exit 0
