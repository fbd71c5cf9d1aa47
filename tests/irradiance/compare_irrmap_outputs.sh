#!/bin/sh
# Runs two builds' irrmap (and vs11 run / translate) over the same inputs and flags and compares the
# files they write: byte for byte (cmp), an EXR file but for its capDate (the second it was written),
# and coeffs.json, the sh_*.json exports and irrmap batch's records as JSON without the fields that
# measure time (compare_irrmap_outputs.py names them). For a change that should not change irrmap's
# output (issue 32's restructuring): build irrmap and vs11 of the base commit into one build
# directory and of the change into another, then
#   tests/irradiance/compare_irrmap_outputs.sh BASE_BUILD NEW_BUILD
# A build directory holds the irrmap and vs11 executables (in its irradiance and vm folders). The inputs are made here (PFM and Radiance
# files by compare_irrmap_outputs.py; an EXR cross and a DDS cube by the new irrmap). A case whose
# flags the base build does not know (exit 2 from it only) is listed as such, not compared. What each
# side prints on stderr is compared with its numbers masked, and listed, not counted. About 2 minutes
# on 2 cores. Not in CI: it needs two builds.
# Exits 0 when every compared file is identical, 1 (listing each difference) otherwise, 2 on misuse.
set -eu
if [ $# -ne 2 ]; then
  echo "usage: $0 BASE_BUILD NEW_BUILD (build directories holding irradiance/irrmap and vm/vs11)" >&2
  exit 2
fi
base_build=$(cd "$1" && pwd)
new_build=$(cd "$2" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
helper="$here/compare_irrmap_outputs.py"
python=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
in="$work/in"
mkdir -p "$in" "$work/base" "$work/new"

# Inputs: every file layout irrmap reads by aspect ratio or by --layout, as PFM and Radiance files.
"$python" "$helper" make-inputs "$in"
"$new_build/irradiance/irrmap" studio --face-size 16 --no-ground-truth --map-size 16 --out "$in/gen_exr" >/dev/null
"$new_build/irradiance/irrmap" studio --face-size 16 --no-ground-truth --map-size 16 --map-format dds \
  --out "$in/gen_dds" >/dev/null
cp "$in/gen_exr/irradiance.exr" "$in/cross.exr"
cp "$in/gen_exr/constants.vsh" "$in/sh9_constants.vsh"
cp "$in/gen_dds/irradiance.dds" "$in/cube.dds"
rm -rf "$in/gen_exr" "$in/gen_dds"

all_exports=three,filament,unity,gltf,glsl,hlsl
mesh_dir=/usr/share/assimp/models/PLY
# name|irrmap arguments (the output folder is added). Small faces keep the whole run near a minute.
cat >"$work/cases" <<EOF
sky_jit|sky --face-size 32
sky_ref|sky --face-size 32 --engine ref
sky_batch|sky --face-size 32 --engine batch
gradient_gl|gradient --face-size 32 --engine gl
sky_gl|sky --face-size 32 --engine gl
studio|studio --face-size 32
spot|spot --face-size 32
gradient|gradient --face-size 32
constant|constant --face-size 32
sky_threads|sky --face-size 64 --threads 2 --map-size 64 --error-normals 500 --sphere-size 64
studio_level|studio --face-size 64 --level 3
sky_max_error|sky --face-size 32 --max-error 0.02
spot_relative|spot --face-size 32 --error-metric relative
sky_rms|sky --face-size 32 --error-metric rms
order0|sky --face-size 32 --level 1 --order order0
order1|sky --face-size 32 --level 1 --order order1
zh3|sky --face-size 32 --level 1 --order zh3 --engine ref
order2|sky --face-size 32 --level 1 --order order2 --engine batch
spot_hanning|spot --face-size 32 --window hanning --window-width 3
spot_lanczos|spot --face-size 32 --window lanczos
spot_dering|spot --face-size 32 --window dering
spot_nonneg|spot --face-size 32 --window nonneg
coefficients_only|sky --face-size 32 --coefficients-only --sh-export $all_exports
no_ground_truth|studio --face-size 32 --no-ground-truth --map-size 16
map_exr|studio --face-size 32 --no-ground-truth --map-format exr --sh-export $all_exports
map_dds|studio --face-size 32 --no-ground-truth --map-format dds --sh-export $all_exports
map_ktx2|studio --face-size 32 --no-ground-truth --map-format ktx2 --sh-export $all_exports
map_ktx|studio --face-size 32 --no-ground-truth --map-format ktx --sh-export $all_exports
map_hdr_faces|studio --face-size 32 --no-ground-truth --map-format hdr-faces --sh-export $all_exports
latlong_pfm|$in/latlong.pfm --face-size 32 --sh-export $all_exports
latlong_hdr|$in/latlong.hdr --face-size 32 --engine ref
latlong_level|$in/latlong.pfm --layout latlong --face-size 16 --level 1 --engine batch
hcross|$in/hcross.pfm --sh-export $all_exports
vcross|$in/vcross.pfm
hstrip|$in/hstrip.pfm --engine ref
vstrip|$in/vstrip.pfm --engine batch
faces|$in/face_{face}.pfm --sh-export three,unity
angular|$in/angular.pfm --layout angular --face-size 16
exr_cross|$in/cross.exr --map-format dds
dds_cube|$in/cube.dds --coefficients-only --sh-export $all_exports
mesh|studio --face-size 16 --mesh $mesh_dir/cube.ply
mesh_normals|studio --face-size 16 --mesh $mesh_dir/cube.ply --compute-normals --no-ground-truth
usage_error|sky --layout sideways
missing_file|$in/no_such_file.pfm
square_needs_layout|$in/angular.pfm
EOF

differences=0
identical=0
skipped=""
messages=""
note() { echo "$*" >>"$work/report"; }
: >"$work/report"

# Runs "$@" for each build with the same output path (coeffs.json's provenance names no output
# folder, but a message may), then moves the side's folder aside.
run_both() {
  name=$1; tool=$2; shift 2
  for side in base new; do
    if [ $side = base ]; then build=$base_build; else build=$new_build; fi
    rm -rf "$work/out"; mkdir -p "$work/out"
    set +e
    (cd "$work/out" && "$build/$tool" "$@") >"$work/out.stdout" 2>"$work/out.stderr"
    echo $? >"$work/out.rc"
    set -e
    mkdir -p "$work/$side/$name"
    mv "$work/out" "$work/$side/$name/files"
    mv "$work/out.stdout" "$work/out.stderr" "$work/out.rc" "$work/$side/$name/"
  done
  base_rc=$(cat "$work/base/$name/out.rc"); new_rc=$(cat "$work/new/$name/out.rc")
  if [ "$base_rc" != "$new_rc" ]; then
    if [ "$base_rc" = 2 ]; then
      skipped="$skipped $name"
      note "$name: the base build refuses these flags (exit 2), the new one exits $new_rc: not compared"
      return
    fi
    differences=$((differences + 1))
    note "$name: exit status $base_rc (base) against $new_rc (new)"
  fi
  compare_folder "$name"
  compare_messages "$name"
}

# What each side printed on stderr (warnings, errors, batch's summary), every number masked (the
# summary's times and rates): listed for reading, not counted, as no file holds it.
compare_messages() {
  for side in base new; do
    sed 's/[0-9][0-9.]*/N/g' "$work/$side/$1/out.stderr" >"$work/$side.messages"
  done
  if ! cmp -s "$work/base.messages" "$work/new.messages"; then
    messages="$messages $1"
    note "$1: stderr (numbers masked) differs:"
    diff "$work/base.messages" "$work/new.messages" | grep '^[<>]' | head -4 | cut -c1-200 | sed 's/^/    /' \
      >>"$work/report"
  fi
}

compare_folder() {
  name=$1
  b="$work/base/$name/files"; n="$work/new/$name/files"
  (cd "$b" && find . -type f | sort) >"$work/base.list"
  (cd "$n" && find . -type f | sort) >"$work/new.list"
  if ! cmp -s "$work/base.list" "$work/new.list"; then
    differences=$((differences + 1))
    note "$name: different files written: $(diff "$work/base.list" "$work/new.list" | grep '^[<>]' | tr '\n' ' ')"
  fi
  for f in $(comm -12 "$work/base.list" "$work/new.list"); do
    if cmp -s "$b/$f" "$n/$f"; then
      identical=$((identical + 1))
    else
      case $f in
        *.json | *.jsonl)
          if "$python" "$helper" compare "$b/$f" "$n/$f" >"$work/json.diff"; then
            identical=$((identical + 1))
            continue
          fi
          ;;
        *.exr)
          if "$python" "$helper" compare-exr "$b/$f" "$n/$f"; then
            identical=$((identical + 1))
            continue
          fi
          : >"$work/json.diff"
          ;;
        *) : >"$work/json.diff" ;;
      esac
      differences=$((differences + 1))
      note "$name/${f#./}: differs"
      sed 's/^/    /' "$work/json.diff" >>"$work/report"
    fi
  done
}

while IFS='|' read -r name args; do
  # shellcheck disable=SC2086  # the arguments are words
  run_both "$name" irradiance/irrmap $args --out case_out
done <"$work/cases"

# irrmap batch over every input file (records sorted by input: threads finish in any order).
batch_inputs="$in/latlong.pfm $in/latlong.hdr $in/hcross.pfm $in/vcross.pfm $in/hstrip.pfm $in/vstrip.pfm $in/cross.exr $in/cube.dds"
# shellcheck disable=SC2086
run_both batch irradiance/irrmap batch $batch_inputs -o records.jsonl --per-file per --face-size 16 --threads 2
# shellcheck disable=SC2086
run_both batch_level irradiance/irrmap batch $batch_inputs -o records.jsonl --level 1 --error-metric rms --threads 1
# shellcheck disable=SC2086
run_both batch_order irradiance/irrmap batch $batch_inputs -o records.jsonl --order auto --window hanning

# vs11 run over every program (every input register v0..v15 from one CSV, every constant from one
# file) under both float rules and each CPU engine, the paper's program with the constants irrmap
# wrote, and vs11 translate of every program to each target under both float rules.
inputs=""
for register in $(seq 0 15); do inputs="$inputs --input v$register=$in/vertices.csv"; done
for program in "$repo"/programs/*.vsh; do
  p=$(basename "$program" .vsh)
  for rules in d3d9 legacy; do
    for engine in ref batch jit; do
      # shellcheck disable=SC2086
      run_both "run_${p}_${engine}_$rules" vm/vs11 run "$program" $inputs --consts "$in/constants.vsh" \
        --engine $engine --float-rules $rules --out out.csv
    done
    for target in glsl330 glsles300 glsles310 spirv; do
      run_both "translate_${p}_${target}_$rules" vm/vs11 translate "$program" --to $target \
        --float-rules $rules -o shader.out
    done
  done
done
run_both run_sh9_irrmap_constants vm/vs11 run "$repo/programs/sh9_irradiance.vsh" --fragment \
  --consts "$in/sh9_constants.vsh" --sphere 200 --sphere-reg v0 --out out.csv

cat "$work/report"
echo "$identical files identical, $differences differences${skipped:+; not compared (flags the base lacks):$skipped}"
echo "${messages:+stderr differs (not counted):$messages}"
[ "$differences" = 0 ]
