#!/usr/bin/env bash
# `airr render`, `sweep`, `tolerance`, `viewzone --full` and `predict-preset` under mpirun (Open MPI, one machine,
# more ranks than cores): 2 and 3 ranks (an odd split) write the files one process writes (PNG
# byte for byte; EXR with the image's components equal in every channel; the tolerance CSV,
# statistics and histograms; the zone's and sweeps' CSV and maps); a rank killed mid-run ends the
# job within seconds with an error and leaves no output file; --shard under mpirun is refused; a
# Pareto front's searches split; a command that does not split (export-gltf) runs on rank 0 alone.
set -euo pipefail
airr="$1"
default_scene="$2/assets/scenes/default.json"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# One machine, any user (containers run as root), no shared-memory copy through ptrace.
export OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpi=(mpirun --oversubscribe)
args=(--spp 8 --set observer.width=80 --set observer.height=61)

"$airr" render "$default_scene" -o "$tmp/one.png" "${args[@]}" 2>/dev/null
"$airr" render "$default_scene" -o "$tmp/one.exr" "${args[@]}" --components 2>/dev/null
for n in 2 3; do
  "${mpi[@]}" -np $n "$airr" render "$default_scene" -o "$tmp/ranks$n.png" "${args[@]}" 2>"$tmp/log$n"
  cmp "$tmp/one.png" "$tmp/ranks$n.png" || { echo "$n ranks: the PNG differs from one process's"; exit 1; }
  "${mpi[@]}" -np $n "$airr" render "$default_scene" -o "$tmp/ranks$n.exr" "${args[@]}" --components 2>/dev/null
  idiff -fail 0 -failpercent 0 -warn 0 "$tmp/one.exr" "$tmp/ranks$n.exr" >"$tmp/idiff$n" ||
    { cat "$tmp/idiff$n"; echo "$n ranks: the EXR differs from one process's"; exit 1; }
  grep -q "render ($n ranks).*100.0%" "$tmp/log$n" || { cat "$tmp/log$n"; echo "$n ranks: no progress for the job"; exit 1; }
  echo "$n ranks: the same files as one process"
done

# A small tolerance study: the samples' CSV, the printed statistics and the histograms as one
# process's.
cat >"$tmp/spec.json" <<SPEC
{"format": "airr-design", "version": 1, "scene": "$default_scene",
 "objectives": [{"metric": "r50_mm", "goal": "minimise"}, {"metric": "visible_fraction", "goal": "maximise"}],
 "constraints": [{"metric": "r50_mm", "max": 0.5}],
 "search": {"psf_samples": 5000},
 "tolerances": [{"key": "retroreflectors.0.pose.pitch_deg", "sd": 0.5}, {"key": "floating_distance_mm", "sd": 5}],
 "tolerance": {"samples": 40, "seed": 3}}
SPEC
"$airr" tolerance "$tmp/spec.json" -o "$tmp/tol1.csv" --png "$tmp/h1" 2>/dev/null | grep -v "layouts (\|wrote" >"$tmp/tol1.out"
for n in 2 3; do
  "${mpi[@]}" -np $n "$airr" tolerance "$tmp/spec.json" -o "$tmp/tol$n.csv" --png "$tmp/h$n" 2>/dev/null |
    grep -v "layouts (\|wrote" >"$tmp/tol$n.out"
  cmp "$tmp/tol1.csv" "$tmp/tol$n.csv" || { echo "$n ranks: the tolerance CSV differs"; exit 1; }
  cmp "$tmp/tol1.out" "$tmp/tol$n.out" || { diff "$tmp/tol1.out" "$tmp/tol$n.out"; exit 1; }
  for f in "$tmp"/h1/*.png; do cmp "$f" "$tmp/h$n/$(basename "$f")" || exit 1; done
  echo "$n ranks: the same tolerance study as one process ($(($(wc -l <"$tmp/tol1.csv") - 1)) samples)"
done

# The full viewing zone: its CSV and maps as one process's.
zone=(viewzone "$default_scene" --full --grid 5 --spp 4)
"$airr" "${zone[@]}" -o "$tmp/zone1.csv" --png "$tmp/zone1.png" >/dev/null 2>&1
for n in 2 3; do
  "${mpi[@]}" -np $n "$airr" "${zone[@]}" -o "$tmp/zone$n.csv" --png "$tmp/zone$n.png" >/dev/null 2>&1
  cmp "$tmp/zone1.csv" "$tmp/zone$n.csv" || { echo "$n ranks: the full viewing zone's CSV differs"; exit 1; }
  for f in "$tmp"/zone1*.png; do cmp "$f" "${f/zone1/zone$n}" || exit 1; done
  echo "$n ranks: the same full viewing zone as one process"
done

# Sweeps, by the model PSF and by rendered edges: the CSV and the map as one process's.
for route in "--psf" "--spp 4"; do
  sweep=(sweep "$default_scene" --vary floating_distance=150:250:100 --vary tilt=0:10:10 $route --set observer.width=96 --set observer.height=96)
  "$airr" "${sweep[@]}" -o "$tmp/sweep1.csv" --png "$tmp/sweep1.png" >/dev/null 2>&1
  for n in 2 3; do
    "${mpi[@]}" -np $n "$airr" "${sweep[@]}" -o "$tmp/sweep$n.csv" --png "$tmp/sweep$n.png" >/dev/null 2>&1
    cmp "$tmp/sweep1.csv" "$tmp/sweep$n.csv" || { echo "$n ranks: the sweep ($route) differs"; exit 1; }
    cmp "$tmp/sweep1.png" "$tmp/sweep$n.png" || { echo "$n ranks: the sweep's map ($route) differs"; exit 1; }
  done
  echo "2 and 3 ranks: the same sweep ($route) as one process"
done

# A predicted preset (the bench's measurements, the fit, the comparison): the same measurements,
# preset and table as one process; the other ranks' working copies of the data are gone.
predict=(predict-preset --sheet "$2/assets/sheets/prism-rf-ay-like.json" --samples 5000 --fit-samples 5000)
# The preset without what differs by nature (run time, the data folder's name).
preset_numbers() {
  python3 -c 'import json,re,sys; p=json.load(open(sys.argv[1])); p["provenance"]["fit"].pop("seconds"); print(re.sub(r"p[0-9]_(bench|shifts)", "DATA", json.dumps(p, sort_keys=True)))' "$1"
}
(cd "$tmp" && "$airr" "${predict[@]}" -o p1.json 2>/dev/null | grep -v "run time\|wrote" | sed "s/p1_bench/DATA/" >p1.out)
for n in 2 3; do
  mkdir "$tmp/scratch$n"
  (cd "$tmp" && TMPDIR="$tmp/scratch$n" "${mpi[@]}" -x TMPDIR -np $n "$airr" "${predict[@]}" -o p$n.json 2>"$tmp/plog$n" |
    grep -v "run time\|wrote" | sed "s/p${n}_bench/DATA/" >p$n.out)
  cmp "$tmp/p1.out" "$tmp/p$n.out" || { diff "$tmp/p1.out" "$tmp/p$n.out"; echo "$n ranks: the prediction differs"; exit 1; }
  [ "$(preset_numbers "$tmp/p1.json")" = "$(preset_numbers "$tmp/p$n.json")" ] ||
    { echo "$n ranks: the predicted preset differs"; exit 1; }
  for f in "$tmp"/p1_bench/*.csv "$tmp"/p1_bench/fit.json; do
    cmp "$f" "$tmp/p${n}_bench/$(basename "$f")" || { echo "$n ranks: $(basename "$f") differs"; exit 1; }
  done
  for f in "$tmp"/p1_bench/*.exr; do idiff -fail 0 -failpercent 0 -warn 0 "$f" "$tmp/p${n}_bench/$(basename "$f")" >/dev/null || exit 1; done
  [ -z "$(ls -A "$tmp/scratch$n")" ] || { ls "$tmp/scratch$n"; echo "$n ranks: working copies left behind"; exit 1; }
  grep -q "predict ($n ranks)" "$tmp/plog$n" || { cat "$tmp/plog$n"; echo "$n ranks: no progress for the job"; exit 1; }
  echo "$n ranks: the same predicted preset, measurements and comparison as one process"
done

# A Pareto front's searches split across the ranks: the same evaluations, front and scene as one
# process's, reported once.
cat >"$tmp/opt.json" <<SPEC
{"format": "airr-design", "version": 1, "scene": "$default_scene",
 "variables": [{"key": "tilt_deg", "min": 0, "max": 60}],
 "objectives": [{"metric": "size_y_mm", "goal": "minimise"}, {"metric": "size_z_mm", "goal": "minimise"}],
 "pareto": {"points": 5}, "search": {"global_evaluations": 20, "local_evaluations": 10}}
SPEC
"$airr" optimise "$tmp/opt.json" -o "$tmp/best1.json" >/dev/null 2>&1
for n in 2 3; do
  "${mpi[@]}" -np $n "$airr" optimise "$tmp/opt.json" -o "$tmp/best$n.json" >"$tmp/opt$n.out" 2>/dev/null
  for f in .json _evaluations.csv _pareto.csv _pareto.png; do
    cmp "$tmp/best1$f" "$tmp/best$n$f" || { echo "optimise under $n ranks: best$n$f differs"; exit 1; }
  done
  [ "$(grep -c "^wrote" "$tmp/opt$n.out")" = 1 ] || { cat "$tmp/opt$n.out"; echo "optimise reported more than once"; exit 1; }
  echo "optimise under $n ranks: the same front ($(($(wc -l <"$tmp/best1_evaluations.csv") - 1)) evaluations) and scene"
done

# A command that does not split (export-gltf) runs on rank 0 alone: one report, the same file.
"$airr" export-gltf "$default_scene" -o "$tmp/one.glb" >/dev/null 2>&1
"${mpi[@]}" -np 2 "$airr" export-gltf "$default_scene" -o "$tmp/two.glb" >"$tmp/gltf2.out" 2>"$tmp/gltf2.err"
cmp "$tmp/one.glb" "$tmp/two.glb" || { echo "export-gltf under 2 ranks wrote another file"; exit 1; }
[ "$(grep -c "^wrote" "$tmp/gltf2.out")" = 1 ] || { cat "$tmp/gltf2.out"; echo "export-gltf reported more than once"; exit 1; }
grep -q "rank 0 runs it alone" "$tmp/gltf2.err" || { cat "$tmp/gltf2.err"; exit 1; }
echo "export-gltf under 2 ranks: rank 0 alone, the same file"

# --shard is for separate processes, not for an MPI job's ranks.
if "${mpi[@]}" -np 2 "$airr" render "$default_scene" -o "$tmp/x.exr" "${args[@]}" --shard 0/2 2>"$tmp/shard.log"; then
  echo "--shard under mpirun was not refused"; exit 1
fi
grep -q "error: --shard: not under mpirun" "$tmp/shard.log" || { cat "$tmp/shard.log"; exit 1; }

# A rank killed mid-run: the job ends with an error, without the output file.
"${mpi[@]}" -np 2 "$airr" render "$default_scene" -o "$tmp/killed.png" --spp 100000 \
  --set observer.width=128 --set observer.height=128 >"$tmp/killed.log" 2>&1 &
job=$!
victim=""
for _ in $(seq 100); do
  victim=$(pgrep -f "killed.png" | while read -r p; do
    [ "$(ps -o comm= -p "$p")" = airr ] && grep -qz "OMPI_COMM_WORLD_RANK=1" "/proc/$p/environ" && echo "$p"
  done | head -1) || true
  [ -n "$victim" ] && break
  sleep 0.1
done
[ -n "$victim" ] || { kill $job; echo "rank 1 never started"; exit 1; }
sleep 1
kill -9 "$victim"
start=$(date +%s)
for _ in $(seq 300); do kill -0 $job 2>/dev/null || break; sleep 0.1; done
if kill -0 $job 2>/dev/null; then kill -9 $job; echo "the job still ran 30 s after a rank was killed"; exit 1; fi
status=0
wait $job || status=$?
[ $status -ne 0 ] || { cat "$tmp/killed.log"; echo "the job exited 0 after a rank was killed"; exit 1; }
[ ! -e "$tmp/killed.png" ] || { echo "an output file was left after a rank was killed"; exit 1; }
echo "a killed rank ended the job in $(($(date +%s) - start)) s with exit code $status and no output"
