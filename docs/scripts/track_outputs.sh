#!/usr/bin/env bash
# Writes every `argus track` output on fixed inputs into OUT, so that two builds can be
# compared byte for byte (`diff -r`) before and after a refactor:
#   docs/scripts/track_outputs.sh path/to/argus OUT
# Inputs are made by the same binary (`argus simulate`, fixed seeds) and by this script;
# cases cover every estimator kind, single and multi-target, CSV and pcap, plain and
# smoothed, and some error messages (stderr and exit code are kept too).
set -uo pipefail
BIN=$(realpath "$1"); OUT=$(realpath -m "$2")
HERE=${ARGUS_REPO:-$(cd "$(dirname "$0")/../.." && pwd)}   # the checkout whose docs/examples are used
mkdir -p "$OUT/in"; cd "$OUT"
run() { # name, args...
  local name=$1; shift
  "$BIN" "$@" >"$name.stdout" 2>"$name.stderr"; echo "$?" >"$name.rc"
}
# Inputs.
run sim-gimpo simulate gimpo --seed 4 --out in/gimpo.csv
run sim-rt simulate real-traffic --seed 2 --out in/rt.csv --set duration=900
run sim-rt-pcap simulate real-traffic --seed 2 --out in/rt.pcap --set duration=900
cp "$HERE/docs/examples/two-targets.csv" in/two.csv
{ echo "t,sensor,range,azimuth,elevation"
  for k in $(seq 0 40); do
    awk -v k="$k" 'BEGIN{t=2*k; x=1000+150*t; y=2000+40*t; z=500+10*t;
      r=sqrt(x*x+y*y+z*z); printf "%g,1,%.6f,%.9f,%.9f\n", t, r+3*sin(k), atan2(y,x)+0.0003*cos(k), atan2(z,sqrt(x*x+y*y))+0.0002*sin(2*k)}'
  done; } > in/sph.csv
S1='[[sensor]]
id = 1
position = [0.0, 0.0]
sigma_range = 20.0
sigma_azimuth_deg = 0.1
sigma_elevation_deg = 0.05
'
RT="$HERE/docs/examples/real-traffic.toml"
IMM5='models = [{ kind = "cv", sigma_a = 0.1 }, { kind = "ct", sigma_a = 0.5, rate_deg = 3.0 }, { kind = "ct", sigma_a = 0.5, rate_deg = -3.0 }]
markov = [[0.9, 0.05, 0.05], [0.1, 0.9, 0.0], [0.1, 0.0, 0.9]]'
IMM2='models = [{ kind = "cv", sigma_a = 0.5 }, { kind = "cv", sigma_a = 10.0 }]
markov = [[0.95, 0.05], [0.05, 0.95]]'
cfg() { printf '%s\n' "$2" > "in/$1.toml"; }
cfg kf "$S1
[estimator]
kind = \"kf-converted\"
sigma_a = 2.0"
cfg ekf "$S1
[estimator]
kind = \"ekf\"
sigma_a = 2.0"
cfg imm3 "$S1
[estimator]
kind = \"imm\"
$IMM5"
cfg multi "$S1
[estimator]
kind = \"multi-imm\"
$IMM2"
cfg air "$S1
[estimator]
kind = \"aircraft-imm\""
# Single target: gimpo (2-D polar) with every kind, plain and smoothed; 3-D with KF/EKF.
for k in kf ekf imm3 multi air; do
  run "single-$k" track --config "in/$k.toml" --plots in/gimpo.csv --out "single-$k.csv"
  run "single-$k-smooth" track --config "in/$k.toml" --plots in/gimpo.csv --out "single-$k-smooth.csv" --smooth
  run "single-$k-lag" track --config "in/$k.toml" --plots in/gimpo.csv --out "single-$k-lag.csv" --smooth-lag 3
done
for k in kf ekf; do
  run "sph-$k" track --config "in/$k.toml" --plots in/sph.csv --out "sph-$k.csv"
  run "sph-$k-smooth" track --config "in/$k.toml" --plots in/sph.csv --out "sph-$k-smooth.csv" --smooth
done
# Multi-target, rotating: the real-traffic example with each estimator, CSV and pcap.
for est in kf-converted ekf imm multi-imm aircraft-imm; do
  case $est in
    imm|multi-imm) extra="$IMM2" ;;
    *) extra="sigma_a = 2.0" ;;
  esac
  [ "$est" = aircraft-imm ] && extra=""
  sed -e "s/^kind = \"aircraft-imm\"/kind = \"$est\"\n$(printf '%s' "$extra" | sed ':a;N;$!ba;s/\n/\\n/g')/" \
      -e '/^ct_sigma_omega_deg/d' "$RT" > "in/rt-$est.toml"
  [ "$est" = aircraft-imm ] && cp "$RT" "in/rt-$est.toml"
  run "rt-$est" track --config "in/rt-$est.toml" --plots in/rt.csv --out "rt-$est.csv"
  run "rt-$est-pcap" track --config "in/rt-$est.toml" --plots in/rt.pcap --out "rt-$est-pcap.csv"
  run "rt-$est-smooth" track --config "in/rt-$est.toml" --plots in/rt.csv --out "rt-$est-smooth.csv" --smooth
done
run rt-lag track --config "in/rt-aircraft-imm.toml" --plots in/rt.csv --out rt-lag.csv --smooth-lag 3
# JPDA and track score on the rotating picture.
sed -e 's/^association = "gnn"/association = "jpda"\np_detection = 0.9\nclutter_density = 1e-9/' "$RT" > in/rt-jpda.toml
run rt-jpda track --config in/rt-jpda.toml --plots in/rt.csv --out rt-jpda.csv
# Synchronous scans: the docs example (JPDA) and GNN / score variants.
cp "$HERE/docs/examples/tracker.toml" in/two.toml
run two track --config in/two.toml --plots in/two.csv --out two.csv
run two-smooth track --config in/two.toml --plots in/two.csv --out two-smooth.csv --smooth
sed -e 's/^association = "jpda"/association = "gnn"/' -e '/^p_detection/d' -e '/^clutter_density/d' -e '/^max_exact_events/d' in/two.toml > in/two-gnn.toml
run two-gnn track --config in/two-gnn.toml --plots in/two.csv --out two-gnn.csv
for est in ekf imm multi-imm aircraft-imm; do
  case $est in
    imm|multi-imm) extra="$IMM2" ;;
    ekf) extra="sigma_a = 2.0" ;;
    *) extra="" ;;
  esac
  awk -v est="$est" -v extra="$extra" '/^kind = "kf-converted"/{print "kind = \"" est "\""; if (extra != "") print extra; next} /^sigma_a /{next} {print}' in/two-gnn.toml > "in/two-$est.toml"
  run "two-$est" track --config "in/two-$est.toml" --plots in/two.csv --out "two-$est.csv"
  run "two-$est-smooth" track --config "in/two-$est.toml" --plots in/two.csv --out "two-$est-smooth.csv" --smooth
done
# Errors: a bad key, a bad plot line, an unknown sensor, a missing file.
printf '%s\n[estimator]\nkind = "kf-converted"\nsigma_a = -1\n' "$S1" > in/bad1.toml
run err-config track --config in/bad1.toml --plots in/gimpo.csv --out err1.csv
{ head -5 in/gimpo.csv; echo "9999,1,abc,0.1"; } > in/badplot.csv
run err-plot track --config in/kf.toml --plots in/badplot.csv --out err2.csv
{ head -3 in/gimpo.csv; tail -n +4 in/gimpo.csv | head -3 | sed 's/^\([^,]*\),1,/\1,7,/'; } > in/badsensor.csv
run err-sensor track --config in/kf.toml --plots in/badsensor.csv --out err3.csv
run err-missing track --config in/kf.toml --plots in/nothing.csv --out err4.csv
run err-multi-sensor track --config in/rt-kf-converted.toml --plots in/badsensor.csv --out err5.csv
# Summaries name the paths given: keep them relative (the same in every OUT).
ls "$OUT" | wc -l
