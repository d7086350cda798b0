#!/usr/bin/env bash
# A sweep of hostile-user cases against a dfrecon binary: huge, endless,
# deeply nested, special (FIFO, /dev/zero, /dev/full) and mis-encoded inputs,
# options that ask for absurd precision, and tampered batch records.
#
# Usage: scripts/hostile_sweep.sh DFRECON_BINARY WORKDIR
#
# WORKDIR is made fresh (an existing one is removed only if an earlier sweep
# made it); every generated input and output goes there. Prints a TSV table to
# stdout, one row per case:
#
#   case  expect  exit  seconds  verdict  first line of stderr (160 bytes)
#
# and a last line "# N passed, M failed of K". Each command runs with
# `ulimit -v 4000000` (KiB, about 4 GB, on dfrecon itself) under
# `timeout 60`. Verdict PASS: ended before the timeout, not by a signal
# (exit < 128), with an expected exit code ("0|1|2" lists several, "any" is
# any exit < 128), and for exit 2 with stderr naming the offending file (its
# basename); some cases check more (a batch's other entry written, no file
# named "-.csv", ...). Otherwise FAIL with the reasons. The script exits 0
# whatever the verdicts (it is a report); 1 only for a usage error.
#
# Cases that only wait (FIFOs nobody writes) run in the background, all at
# once; the rest run one after the other, so that the whole sweep stays
# within a few minutes even where many cases hang. Cases that need pydicom
# (DICOM image series, an edited RTSTRUCT) are SKIPped without it.
#
# SWEEP_ONLY="case_max_error case_latin1 ..." runs only those case functions
# (with the setup), for working on the script. Needs bash 5, coreutils
# (timeout, truncate), mkfifo, awk, perl; python3 for the JSON checks.
set -u

# ---------------------------------------------------------------- settings ---

TIMEOUT_S=60          # per command
MEM_KIB=4000000       # ulimit -v for every command
STDERR_BYTES=160      # of the first stderr line in the table

usage() {
    echo "usage: $0 DFRECON_BINARY WORKDIR" >&2
    exit 1
}
[ $# -eq 2 ] || usage
BIN=$(readlink -f -- "$1") || usage
[ -x "$BIN" ] || { echo "$0: $1 is not an executable" >&2; exit 1; }
W=$2
case $W in "" | / | "$HOME" | "$HOME/") echo "$0: refusing WORKDIR '$W'" >&2; exit 1 ;; esac
if [ -e "$W" ]; then
    if [ -f "$W/.hostile_sweep" ]; then
        chmod -R u+w -- "$W" 2>/dev/null
        rm -rf -- "$W"
    elif [ -n "$(ls -A -- "$W" 2>/dev/null)" ]; then
        echo "$0: $W exists and was not made by this script; give a new folder" >&2
        exit 1
    fi
fi
mkdir -p -- "$W" && W=$(readlink -f -- "$W") || exit 1
touch "$W/.hostile_sweep"
mkdir -p "$W/.rows" "$W/.logs"

REPO=$(cd "$(dirname -- "$0")/.." && pwd)
EXAMPLES=$REPO/examples

# A python with pydicom for the DICOM cases; any python3 for the JSON checks.
PY=""
for p in /usr/bin/python3 python3; do
    if command -v "$p" >/dev/null 2>&1; then PY=$(command -v "$p"); break; fi
done
PYDICOM=""
for p in /usr/bin/python3 python3; do
    if command -v "$p" >/dev/null 2>&1 && "$p" -c 'import pydicom' 2>/dev/null; then
        PYDICOM=$(command -v "$p"); break
    fi
done

# ------------------------------------------------------------------ helpers ---

# limited OUT ERR CMD...: CMD under the memory cap and the timeout, in a
# subshell so the cap applies to CMD (and timeout) only, with its standard
# output and error to the files OUT and ERR (so the shell's own "Segmentation
# fault" note goes to the script's stderr, not to ERR). No core files. A
# first word `dfr` stands for the binary with -q (no progress, no warnings).
limited() {
    local out=$1 err=$2
    shift 2
    local cmd=("$@")
    [ "${cmd[0]}" = dfr ] && cmd=("$BIN" -q "${cmd[@]:1}")
    (
        ulimit -v "$MEM_KIB"
        ulimit -c 0
        exec timeout -k 5 "$TIMEOUT_S" "${cmd[@]}" >"$out" 2>"$err"
    )
}

now() { echo "${EPOCHREALTIME/,/.}"; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }

# The logs of the case now running: $W/.logs/ID.out, .err
log_out() { echo "$W/.logs/$1.out"; }
log_err() { echo "$W/.logs/$1.err"; }

# emit_row ID EXPECT EXIT SECONDS VERDICT STDERR_FILE: one line of the table
# (to this case's row file; the table is put together at the end).
emit_row() {
    local first=""
    [ -f "$6" ] && first=$(head -n 1 -- "$6" | tr '\t\r' '  ' | head -c "$STDERR_BYTES")
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$1" "$2" "$3" "$4" "$5" "$first" >>"$ROWFILE"
}

# exit_expected RC EXPECT: whether RC is one of EXPECT ("0|1|2", "any").
exit_expected() {
    [ "$2" = any ] && return 0
    local e
    IFS='|' read -ra es <<<"$2"
    for e in "${es[@]}"; do [ "$1" = "$e" ] && return 0; done
    return 1
}

# judge RC SECONDS EXPECT NAME ERRFILE: prints the reasons for a FAIL (empty
# when the run passes). NAME: the basename stderr must contain on exit 2
# (empty: none required).
judge() {
    local rc=$1 secs=$2 expect=$3 name=$4 err=$5
    if [ "$rc" -eq 124 ] || { [ "$rc" -eq 137 ] && awk -v s="$secs" -v t="$TIMEOUT_S" 'BEGIN { exit !(s >= t) }'; }; then
        echo "timeout"
    elif [ "$rc" -ge 128 ]; then
        echo "signal $((rc - 128))"
    elif ! exit_expected "$rc" "$expect"; then
        echo "exit $rc"
    elif [ "$rc" -eq 2 ] && [ -n "$name" ] && ! LC_ALL=C grep -qF -- "$name" "$err"; then
        echo "no file named"
    fi
}

# run_case ID EXPECT NAME CMD...: runs CMD (limited, in WORKDIR), judges it and
# emits its row. Optional variables for one call:
#   FEED=FUNCTION   standard input from FUNCTION's output (else /dev/null)
#   STDOUT=FILE     standard output to FILE (else the case's .out log)
#   CHECK=FUNCTION  run afterwards with the exit code as $1; whatever it prints
#                   (one reason a line) makes the case FAIL
#   SHOW_EXPECT=TEXT  the expect column, where EXPECT alone would mislead
# Sets RC to CMD's exit code.
run_case() {
    local id=$1 expect=$2 name=$3
    shift 3
    local out err t0 t1 secs reasons extra
    out=$(log_out "$id")
    err=$(log_err "$id")
    [ -n "${STDOUT:-}" ] && out=$STDOUT
    t0=$(now)
    if [ -n "${FEED:-}" ]; then
        "$FEED" | limited "$out" "$err" "$@"
        RC=${PIPESTATUS[1]}
    else
        limited "$out" "$err" "$@" </dev/null
        RC=$?
    fi
    t1=$(now)
    secs=$(elapsed "$t0" "$t1")
    reasons=$(judge "$RC" "$secs" "$expect" "$name" "$err")
    if [ -n "${CHECK:-}" ]; then
        extra=$("$CHECK" "$RC" 2>&1)
        [ -n "$extra" ] && reasons=${reasons:+$reasons$'\n'}$extra
    fi
    local verdict=PASS
    [ -n "$reasons" ] && verdict="FAIL ($(echo "$reasons" | paste -sd ';' | sed 's/;/; /g'))"
    emit_row "$id" "${SHOW_EXPECT:-$expect}" "$RC" "$secs" "$verdict" "$err"
}

# prep ID CMD...: a preparatory dfrecon run (limited, logged as ID); sets RC.
prep() {
    local id=$1
    shift
    limited "$(log_out "$id")" "$(log_err "$id")" "$@" </dev/null
    RC=$?
}

# skip_row ID WHY
skip_row() {
    printf '%s\t-\t-\t-\tSKIP (%s)\t\n' "$1" "$2" >>"$ROWFILE"
}

# json_ok FILE: prints why FILE is not valid UTF-8 JSON (nothing if it is).
json_ok() {
    [ -n "$PY" ] || return 0
    "$PY" - "$1" <<'EOF' 2>&1 | tail -n 1
import json, sys
try:
    json.loads(open(sys.argv[1], "rb").read().decode("utf-8"))
except Exception as e:
    print("stdout not UTF-8 JSON: %s" % type(e).__name__)
EOF
}

# A new batch output folder DIR/out of one finished entry "a" (torus.slices),
# for the cases that tamper with its record. Prints the folder.
fresh_batch_out() {
    local d=$W/$1
    mkdir -p "$d"
    cp "$W/base/m.csv" "$W/base/torus.slices" "$d/"
    cp -r "$W/base/out" "$d/out"
    echo "$d"
}

# sparse FILE SIZE: a sparse file of SIZE (truncate's syntax).
sparse() { rm -f -- "$1"; truncate -s "$2" -- "$1"; }

# nested N OPEN CLOSE: N opening then N closing strings.
nested() {
    printf '%*s' "$1" '' | tr ' ' "$2"
    printf '%*s' "$1" '' | tr ' ' "$3"
}

# -------------------------------------------------------------------- setup ---

# setup_step NAME CMD...: a dfrecon run making an input; a comment line if it
# fails.
setup_step() {
    local name=$1
    shift
    limited "$W/.logs/setup-$name.out" "$W/.logs/setup-$name.err" "$@" </dev/null ||
        echo "# setup: $name failed: $(head -n 1 "$W/.logs/setup-$name.err" | head -c 200)"
}

# Inputs every case may use, in WORKDIR: the examples, a y surface, a label
# volume with its table and as a segmentation, an RTSTRUCT, a finished batch.
setup() {
    cd "$W" || return 1
    cp "$EXAMPLES"/torus.slices "$EXAMPLES"/y.slices "$EXAMPLES"/two-rois.slices .
    setup_step y.ply dfr reconstruct y.slices -o y.ply
    setup_step two.nrrd dfr rasterize two-rois.slices --all --voxel-mm 1 -o two.nrrd
    setup_step two.seg.nrrd dfr rasterize two-rois.slices --all --voxel-mm 1 -o two.seg.nrrd
    setup_step torus.dcm dfr convert torus.slices -o torus.dcm
    mkdir -p base
    cp torus.slices base/
    printf 'input,id\ntorus.slices,a\n' >base/m.csv
    setup_step base-batch dfr batch base/m.csv -o base/out
    [ -f base/out/a/record.json ] || echo "# setup: no base/out/a/record.json: the record cases will fail"
}

# -------------------------------------------------------------------- cases ---
# One function per case (or per small group of rows that build on each other).
# Each runs in its own subshell with WORKDIR as the current folder.

# 1. Absurdly small --max-error: refuse it (1, 2) or do it, but no crash, no
#    exhausted memory (3).
case_max_error() {
    local e
    for e in 1e-16 1e-12 1e-8 1e-4; do
        run_case "simplify-max-error-$e" "0|1|2" y.ply dfr simplify y.ply --max-error "$e" -o "simplify-$e.ply"
    done
    for e in 1e-16 1e-12 1e-8 1e-4; do
        run_case "reconstruct-max-error-$e" "0|1|2" y.slices dfr reconstruct y.slices --max-error "$e" -o "reconstruct-$e.ply"
    done
}

# 2a. A batch entry whose worker process crashes (the test hook
#     DFRECON_BATCH_WORKER_CRASH_ENTRY raises SIGSEGV there; older builds
#     ignore it): the batch ends, the other entries are written, and the
#     crashed one has a record the report shows.
check_crash_isolated() {
    [ -f batch-crash/out/c/record.json ] || echo "entry c has no record"
    [ -f batch-crash/out/b/record.json ] || echo "the crashed entry b has no record"
}
case_batch_worker_crash() {
    mkdir -p batch-crash
    cp torus.slices batch-crash/
    printf 'input,id\ntorus.slices,a\ntorus.slices,b\ntorus.slices,c\n' >batch-crash/m.csv
    DFRECON_BATCH_WORKER_CRASH_ENTRY=b CHECK=check_crash_isolated \
        run_case batch-worker-crash "0|3" "" dfr batch batch-crash/m.csv -o batch-crash/out
}

# 2. A batch whose first entry asks for --max-error 1e-16: the batch ends and
#    the second entry is written; the same on a rerun. One entry at a time
#    (-j 1), so the second runs after the first, whatever befell it.
check_second_entry() {
    # A bad manifest runs nothing, by design (docs/cli.md): a refusal naming
    # the row and key is as good as running the entry that is fine.
    if [ "$1" -eq 2 ] && LC_ALL=C grep -q 'm.csv:2: cell 3 (max-error)' "$(log_err "$CASE")"; then
        return 0
    fi
    [ -f batch-max-error/out/normal/record.json ] || echo "entry 2 has no record"
    [ -f batch-max-error/out/normal/torus.ply ] || echo "entry 2 has no mesh"
}
case_batch_max_error() {
    mkdir -p batch-max-error
    cp y.slices torus.slices batch-max-error/
    printf 'input,id,max-error\ny.slices,tiny,1e-16\ntorus.slices,normal,\n' >batch-max-error/m.csv
    CASE=batch-max-error-1e-16 CHECK=check_second_entry run_case batch-max-error-1e-16 any "" dfr batch batch-max-error/m.csv -o batch-max-error/out -j 1
    CASE=batch-max-error-1e-16-rerun CHECK=check_second_entry run_case batch-max-error-1e-16-rerun any "" dfr batch batch-max-error/m.csv -o batch-max-error/out -j 1
}

# 3. A record whose "error" nests 100 000 levels deep.
case_record_nested() {
    local d
    d=$(fresh_batch_out record-nested)
    perl -0pi -e 's/^  "error": null/"  \"error\": " . ("[" x 100000) . ("]" x 100000)/me' "$d/out/a/record.json"
    run_case batch-report-record-nested-100000 2 record.json dfr batch-report "$d/out"
    run_case batch-rerun-record-nested-100000 any "" dfr batch "$d/m.csv" -o "$d/out"
}

# 4. A record that is a FIFO nobody writes (runs in the background).
check_entry_reported() {
    LC_ALL=C grep -q '^a: ' "$(log_out batch-rerun-record-fifo)" || echo "entry a not reported"
}
case_record_fifo() {
    local d
    d=$(fresh_batch_out record-fifo)
    rm "$d/out/a/record.json"
    mkfifo "$d/out/a/record.json"
    run_case batch-report-record-fifo 2 record.json dfr batch-report "$d/out"
    CHECK=check_entry_reported run_case batch-rerun-record-fifo any "" dfr batch "$d/m.csv" -o "$d/out"
}

# 5. A record that is a link to /dev/zero.
case_record_dev_zero() {
    local d
    d=$(fresh_batch_out record-zero)
    rm "$d/out/a/record.json"
    ln -s /dev/zero "$d/out/a/record.json"
    run_case batch-report-record-dev-zero 2 record.json dfr batch-report "$d/out"
    run_case batch-rerun-record-dev-zero any "" dfr batch "$d/m.csv" -o "$d/out"
}

# 6. Batch inputs that are huge: a 100 GB sparse .slices, a folder of 20 000
#    files, a folder holding a 100 GB sparse file. Refused (2) quickly.
case_batch_huge_inputs() {
    mkdir -p huge
    sparse huge/huge.slices 100G
    printf 'input,id\nhuge.slices,huge\n' >huge/m-file.csv
    run_case batch-input-sparse-100g 2 huge.slices dfr batch huge/m-file.csv -o huge/out-file
    run_case info-sparse-100g 2 huge.slices dfr info huge/huge.slices

    # A mask stack of 20 000 (empty) images.
    mkdir -p huge/many-files
    (cd huge/many-files && seq -f 'f%05g.png' 1 20000 | xargs touch)
    printf '{"pixelSpacingMm": [1, 1], "sliceSpacingMm": 1, "pattern": "*.png"}\n' >huge/many-files/stack.json
    printf 'input,id\nmany-files,many\n' >huge/m-folder.csv
    run_case batch-input-folder-20000-files 2 many-files dfr batch huge/m-folder.csv -o huge/out-folder

    mkdir -p huge/sparse-folder
    sparse huge/sparse-folder/slice_000.png 100G
    printf '{"pixelSpacingMm": [1, 1], "sliceSpacingMm": 1, "files": ["slice_000.png"]}\n' >huge/sparse-folder/stack.json
    printf 'input,id\nsparse-folder,sparse\n' >huge/m-sparse-folder.csv
    run_case batch-input-folder-sparse-100g 2 sparse-folder dfr batch huge/m-sparse-folder.csv -o huge/out-sparse-folder
}

# 7. A DICOM file: preamble, DICM, then 2 GiB of zeros (sparse).
case_dicom_zeros() {
    head -c 128 /dev/zero >zeros-2g.dcm
    printf 'DICM' >>zeros-2g.dcm
    truncate -s +2G zeros-2g.dcm
    run_case info-dicom-2g-zeros 2 zeros-2g.dcm dfr info zeros-2g.dcm
    # Under the size limit: zeros that DCMTK parses as empty elements.
    head -c 128 /dev/zero >zeros-1000m.dcm
    printf 'DICM' >>zeros-1000m.dcm
    truncate -s 1000M zeros-1000m.dcm
    run_case info-dicom-1000m-zeros 2 zeros-1000m.dcm dfr info zeros-1000m.dcm
    rm -f zeros-2g.dcm zeros-1000m.dcm
}

# 7a. A mesh of 10^5 triangles fanned around one vertex: every pair of them
#     overlaps in its box for the self-intersection check.
case_mesh_fan() {
    /usr/bin/python3 - <<'PY'
import math
n = 200000
with open("fan.off", "w") as f:
    f.write("OFF\n%d %d 0\n0 0 0\n" % (n + 1, n // 2))
    for k in range(n):
        a = 2 * math.pi * k / n
        f.write("%f %f %d\n" % (math.cos(a), math.sin(a), k % 2))
    for k in range(1, n, 2):
        f.write("3 0 %d %d\n" % (k, k + 1))
PY
    run_case mesh-fan-100000-check 2 fan.off dfr check fan.off
    run_case mesh-fan-100000-compare 2 fan.off dfr compare fan.off fan.off
    run_case mesh-fan-100000-segment 2 fan.off dfr segment fan.off -k 2 -o fan-segments.ply
}

# 8. Endless comment lines on standard input.
feed_comments() { yes '#'; }
case_stdin_endless_comments() {
    FEED=feed_comments run_case info-stdin-endless-comments 2 "<stdin>" dfr info -
}

# 9. A JSON manifest of 400 000 entries, one shard of one entry: starts fast.
case_manifest_400k() {
    mkdir -p m400k
    cp torus.slices m400k/
    awk 'BEGIN { printf "["; for (i = 1; i <= 400000; i++) printf "%s{\"input\":\"torus.slices\",\"id\":\"e%d\"}", (i > 1 ? ",\n" : ""), i; print "]" }' >m400k/m.json
    run_case batch-json-400000-entries-one-shard 0 m.json dfr batch m400k/m.json -o m400k/out --shard 0/400000
}

# 10. A reference image series whose headers claim a grid over the label
#     volume limit (65535 x 65535 x 2000); and a small one that must work.
make_ct_series() {  # FOLDER ROWS COLUMNS IMAGES
    "$PYDICOM" - "$@" <<'EOF'
import os, sys
from pydicom.dataset import Dataset, FileMetaDataset
from pydicom.uid import ExplicitVRLittleEndian, generate_uid
folder, rows, cols, n = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
os.makedirs(folder, exist_ok=True)
study, series, frame = generate_uid(), generate_uid(), generate_uid()
for k in range(n):
    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID = "1.2.840.10008.5.1.4.1.1.2"  # CT Image Storage
    meta.MediaStorageSOPInstanceUID = generate_uid()
    meta.TransferSyntaxUID = ExplicitVRLittleEndian
    ds = Dataset()
    ds.file_meta = meta
    ds.SOPClassUID = meta.MediaStorageSOPClassUID
    ds.SOPInstanceUID = meta.MediaStorageSOPInstanceUID
    ds.Modality = "CT"
    ds.PatientName, ds.PatientID = "Sweep^Hostile", "SWEEP1"
    ds.StudyInstanceUID, ds.SeriesInstanceUID, ds.FrameOfReferenceUID = study, series, frame
    ds.Rows, ds.Columns = rows, cols
    ds.PixelSpacing, ds.SliceThickness = [1, 1], 1
    ds.ImageOrientationPatient = [1, 0, 0, 0, 1, 0]
    ds.ImagePositionPatient = [-cols / 2, -rows / 2, -n / 2 + k]
    ds.SamplesPerPixel, ds.PhotometricInterpretation = 1, "MONOCHROME2"
    ds.BitsAllocated, ds.BitsStored, ds.HighBit, ds.PixelRepresentation = 16, 16, 15, 1
    ds.InstanceNumber = k + 1
    ds.is_little_endian, ds.is_implicit_VR = True, False
    ds.save_as(os.path.join(folder, "ct%05d.dcm" % k), write_like_original=False)
EOF
}
case_like_huge_grid() {
    if [ -z "$PYDICOM" ]; then
        skip_row rasterize-like-ct-small "no pydicom"
        skip_row rasterize-like-ct-65535x65535x2000 "no pydicom"
        return
    fi
    make_ct_series ct-small 64 64 40
    run_case rasterize-like-ct-small 0 ct-small dfr rasterize torus.slices --like ct-small -o like-small.nrrd
    make_ct_series ct-65535 65535 65535 2000
    run_case rasterize-like-ct-65535x65535x2000 2 ct-65535 dfr rasterize torus.slices --like ct-65535 -o like-huge.nrrd
}

# 11. A 1 m cube against itself and against a copy 0.5 mm over.
write_cube() {  # FILE SHIFT_X
    awk -v s="$2" 'BEGIN {
        print "OFF"; print "8 12 0"
        for (v = 0; v < 8; v++) {
            x = (v == 1 || v == 2 || v == 5 || v == 6) ? 1000 : 0
            y = (v == 2 || v == 3 || v == 6 || v == 7) ? 1000 : 0
            z = (v >= 4) ? 1000 : 0
            print x + s, y, z
        }
        split("0 2 1|0 3 2|4 5 6|4 6 7|0 1 5|0 5 4|3 7 6|3 6 2|0 4 7|0 7 3|1 2 6|1 6 5", f, "|")
        for (i = 1; i <= 12; i++) print "3 " f[i]
    }' >"$1"
}
case_compare_cube() {
    write_cube cube.off 0
    write_cube cube-shifted.off 0.5
    run_case compare-cube-1m-self "0|2" cube.off dfr compare cube.off cube.off
    run_case compare-cube-1m-shifted "0|2" cube.off dfr compare cube.off cube-shifted.off
}

# 12. 10 000 planes of one triangle of side 0.01 mm, 1 mm apart.
case_tiny_planes() {
    awk 'BEGIN {
        print "dfrecon-slices 1"; print "units mm"; print "roi tiny"
        for (k = 0; k < 10000; k++) {
            print "slice " k; print "contour 3"
            print "0 0"; print "0.01 0"; print "0.005 0.00866"
        }
    }' >tiny-10000.slices
    run_case reconstruct-10000-tiny-planes "0|2" tiny-10000.slices dfr reconstruct tiny-10000.slices -o tiny.ply
}

# 13. Latin-1 (0xE9, not UTF-8) in names: simply works (0), or a refusal
#     naming the file (2) where noted.
check_stdout_json() { [ "$1" -eq 0 ] && json_ok "$(log_out "$CASE")"; }
check_report_has_entry() {
    [ -f latin1-batch/out/batch-report.csv ] || { echo "no report CSV"; return; }
    LC_ALL=C grep -q '^latin1,' latin1-batch/out/batch-report.csv || echo "entry not in the report CSV"
}
case_latin1() {
    sed $'s/^roi torus$/roi caf\xe9/' torus.slices >latin1-roi.slices
    CASE=latin1-roi-info-json CHECK=check_stdout_json \
        run_case latin1-roi-info-json "0|2" latin1-roi.slices dfr info latin1-roi.slices --json
    CASE=latin1-roi-reconstruct-all-json CHECK=check_stdout_json \
        run_case latin1-roi-reconstruct-all-json "0|2" latin1-roi.slices dfr reconstruct latin1-roi.slices --all -o latin1-all --json

    # The id rule allows "letters, digits, - _ .": 0xE9 may be refused (2).
    mkdir -p latin1-batch
    cp torus.slices latin1-roi.slices latin1-batch/
    printf 'input,id\ntorus.slices,caf\xe9\n' >latin1-batch/m-id.csv
    run_case latin1-manifest-id "0|2" m-id.csv dfr batch latin1-batch/m-id.csv -o latin1-batch/out-id
    # Latin-1 in a cell that is free text: the ROI name.
    printf 'input,id,roi\nlatin1-roi.slices,latin1,caf\xe9\n' >latin1-batch/m-roi.csv
    run_case latin1-manifest-roi-batch 0 m-roi.csv dfr batch latin1-batch/m-roi.csv -o latin1-batch/out
    CHECK=check_report_has_entry run_case latin1-manifest-roi-batch-report 0 "" dfr batch-report latin1-batch/out

    printf '1 230 120 40 1 1 1 "caf\xe9"\n2 162 48 242 1 1 1 "PTV"\n' >latin1-table.txt
    CASE=latin1-label-table-info-json CHECK=check_stdout_json \
        run_case latin1-label-table-info-json 0 latin1-table.txt dfr info two.nrrd --label-table latin1-table.txt --json

    if [ -f two.seg.nrrd ]; then
        # Replace the first segment's name in the header text (before the
        # blank line; the gzip data after it is left as it is).
        perl -0777 -pe 's/^(.*?\n\n)/ my $h = $1; $h =~ s{^Segment0_Name:=[^\n]*}{Segment0_Name:=caf\xe9}m; $h /se' \
            two.seg.nrrd >latin1.seg.nrrd
    fi
    CASE=latin1-seg-nrrd-name-info-json CHECK=check_stdout_json \
        run_case latin1-seg-nrrd-name-info-json 0 latin1.seg.nrrd dfr info latin1.seg.nrrd --json

    cp torus.slices $'caf\xe9.slices'
    CASE=latin1-file-name-info-json CHECK=check_stdout_json \
        run_case latin1-file-name-info-json 0 $'caf\xe9.slices' dfr info $'caf\xe9.slices' --json
}

# 14. Reports to a full device: a nonzero documented exit (3), not 0.
case_dev_full() {
    STDOUT=/dev/full run_case info-json-to-dev-full "1|2|3|4" "" dfr info torus.slices --json
    STDOUT=/dev/full run_case info-text-to-dev-full "1|2|3|4" "" dfr info torus.slices
    STDOUT=/dev/full run_case reconstruct-json-to-dev-full "1|2|3|4" "" dfr reconstruct torus.slices -o full.ply --json
}

# 15. A JSON manifest entry with a repeated key.
case_manifest_repeated_key() {
    printf '[{"input": "torus.slices", "input": "y.slices"}]\n' >m-repeated-key.json
    run_case manifest-json-repeated-key 2 m-repeated-key.json dfr batch m-repeated-key.json -o out-repeated-key
}

# 16. Label tables with a colour of 1e9 and of nan (line 2): 2 naming file
#     and line.
case_label_table_colours() {
    local c
    for c in 1e9 nan; do
        printf '1 230 120 40 1 1 1 "Left Kidney"\n2 %s 48 242 1 1 1 "PTV"\n' "$c" >"table-colour-$c.txt"
        run_case "label-table-colour-$c" 2 "table-colour-$c.txt:2" dfr info two.nrrd --label-table "table-colour-$c.txt"
    done
}

# 17. batch-report -o -: the table on standard output, no file "-.csv".
check_no_dash_csv() {
    local f
    for f in ./-.csv ./-.json base-dash/out/-.csv base-dash/out/-.json; do
        [ -e "$f" ] && echo "made $f"
    done
    LC_ALL=C grep -q '^entry,roi' "$(log_out batch-report-stdout)" || echo "no CSV on stdout"
}
case_batch_report_stdout() {
    local d
    d=$(fresh_batch_out base-dash)
    CHECK=check_no_dash_csv run_case batch-report-stdout 0 "" dfr batch-report "$d/out" -o -
}

# 18. A record whose mesh is outside its entry folder: a rerun must not trust
#     it; batch-report refuses it (2) or leaves the outside path out (0).
check_report_no_outside() {
    [ "$1" -eq 0 ] || return 0
    LC_ALL=C grep -q 'etc/passwd' "$REC_DIR/out/batch-report.csv" 2>/dev/null && echo "report names the outside path"
}
check_not_skipped() {
    LC_ALL=C grep -q '^a: skipped' "$(log_out "$CASE")" && echo "entry skipped as done"
}
case_record_mesh_outside() {
    local variant path
    for variant in absolute relative; do
        [ $variant = absolute ] && path=/etc/passwd || path=../../../../../../../../../../../../etc/passwd
        REC_DIR=$(fresh_batch_out "record-mesh-$variant")
        sed -i "s|\"mesh\": \"torus.ply\"|\"mesh\": \"$path\"|" "$REC_DIR/out/a/record.json"
        CHECK=check_report_no_outside run_case "batch-report-record-mesh-$variant-outside" "0|2" record.json \
            dfr batch-report "$REC_DIR/out"
        CASE="batch-rerun-record-mesh-$variant-outside" CHECK=check_not_skipped \
            run_case "batch-rerun-record-mesh-$variant-outside" any "" dfr batch "$REC_DIR/m.csv" -o "$REC_DIR/out"
    done
}

# 19. A 300-byte ROI name through a segmentation and a label table: refused
#     when written (2 naming the ROI or file), or read back (0); not written
#     and then refused.
write_then_read() {  # ID OUTPUT
    local id=$1 output=$2 t0 t1 show="write 2|read 0"
    t0=$(now)
    prep "$id-write" dfr rasterize long-name.slices --voxel-mm 1 -o "$output"
    t1=$(now)
    if [ "$RC" -eq 2 ] && LC_ALL=C grep -qE 'long-name.slices|aaaaaaaaaaaaaaaaaaaa' "$(log_err "$id-write")"; then
        emit_row "$id" "$show" "$RC" "$(elapsed "$t0" "$t1")" "PASS (refused when written)" "$(log_err "$id-write")"
    elif [ "$RC" -ne 0 ]; then
        emit_row "$id" "$show" "$RC" "$(elapsed "$t0" "$t1")" "FAIL (write: $(judge "$RC" "$(elapsed "$t0" "$t1")" 2 long-name.slices "$(log_err "$id-write")"))" "$(log_err "$id-write")"
    else
        # Written: the row is the reading back, which must work.
        SHOW_EXPECT=$show run_case "$id" 0 "$output" dfr info "$output"
    fi
}
case_long_roi_name() {
    local name
    name=$(printf '%*s' 300 '' | tr ' ' a)
    sed "s/^roi torus\$/roi $name/" torus.slices >long-name.slices
    write_then_read roi-name-300-seg-nrrd long-name.seg.nrrd
    write_then_read roi-name-300-nrrd-label-table long-name.nrrd
}

# 20. An RTSTRUCT ROI named GTV "left": converted to .slices (0) and that read
#     back (0).
case_rtstruct_quote() {
    if [ -z "$PYDICOM" ]; then
        skip_row rtstruct-quoted-name-convert "no pydicom"
        skip_row rtstruct-quoted-name-info-result "no pydicom"
        return
    fi
    "$PYDICOM" - torus.dcm rt-quote.dcm <<'EOF' >"$W/.logs/make-rt-quote.log" 2>&1
import sys, pydicom
ds = pydicom.dcmread(sys.argv[1])
ds.StructureSetROISequence[0].ROIName = 'GTV "left"'
ds.save_as(sys.argv[2])
EOF
    run_case rtstruct-quoted-name-convert 0 rt-quote.dcm dfr convert rt-quote.dcm -o rt-quote.slices
    run_case rtstruct-quoted-name-info-result 0 rt-quote.slices dfr info rt-quote.slices
}

# 21. A label table name with control characters: used or refused, not 3.
case_label_table_control() {
    printf '1 230 120 40 1 1 1 "Left\x01Kid\x1b[31mney"\n2 162 48 242 1 1 1 "PTV"\n' >table-control.txt
    run_case label-table-control-chars "0|2" table-control.txt dfr info two.nrrd --label-table table-control.txt
}

# 22. The global --label-table before the subcommand.
case_label_table_global() {
    run_case label-table-global-before-subcommand 0 two.txt "$BIN" -q --label-table two.txt info two.nrrd
}

# 23. More: manifests, label tables, contours, meshes and sidecars that are
#     FIFOs or /dev/zero; deeply nested JSON; a NUL byte in a CSV manifest.
case_fifo_inputs() {  # (background: these only wait)
    mkfifo fifo-manifest.csv fifo-table.txt fifo.slices fifo.ply
    mkdir -p fifo-stack && mkfifo fifo-stack/stack.json
    run_case manifest-fifo 2 fifo-manifest.csv dfr batch fifo-manifest.csv -o out-fifo-manifest
    run_case label-table-fifo 2 fifo-table.txt dfr info two.nrrd --label-table fifo-table.txt
    run_case slices-fifo-info 2 fifo.slices dfr info fifo.slices
    run_case mesh-fifo-check 2 fifo.ply dfr check fifo.ply
    run_case stack-json-fifo-info-folder 2 fifo-stack dfr info fifo-stack
    run_case stack-json-fifo-info-json 2 stack.json dfr info fifo-stack/stack.json
}
case_dev_zero_inputs() {
    ln -sf /dev/zero zero-manifest.csv
    ln -sf /dev/zero zero-table.txt
    ln -sf /dev/zero zero.slices
    run_case manifest-dev-zero 2 zero-manifest.csv dfr batch zero-manifest.csv -o out-zero-manifest
    run_case label-table-dev-zero 2 zero-table.txt dfr info two.nrrd --label-table zero-table.txt
    run_case slices-dev-zero-info 2 zero.slices dfr info zero.slices
}
case_manifest_nested() {
    nested 100000 '[' ']' >m-nested.json
    run_case manifest-json-nested-100000 2 m-nested.json dfr batch m-nested.json -o out-nested
    { printf '[{"input": "torus.slices", "id": '; nested 100000 '[' ']'; printf '}]\n'; } >m-nested-value.json
    run_case manifest-json-value-nested-100000 2 m-nested-value.json dfr batch m-nested-value.json -o out-nested-value
}
case_manifest_nul() {
    printf 'input,id\ntorus.slices,a\0b\n' >m-nul.csv
    run_case manifest-csv-nul-byte 2 m-nul.csv dfr batch m-nul.csv -o out-nul
}

# --------------------------------------------------------------------- main ---

# The cases in table order; "bg:" marks those that only wait (run at once in
# the background).
# ---- issue 63: outputs that would lose data, numbers that are none, expressions
# without bounds, names that break a report page.

check_unchanged() {  # the file named by KEEP equals its copy KEEP.orig
    cmp -s "$KEEP" "$KEEP.orig" || echo "$KEEP was changed"
}
check_char_device() { [ -c /dev/null ] || echo "/dev/null is no longer a device"; }
check_both_sdm_maps() {
    [ -f sdm-case/lung.ply ] && [ -f sdm-case/LUNG_2.ply ] || echo "sdm names collide ignoring case"
}
check_inert_report() {
    [ -n "$PY" ] || return 0
    "$PY" - hostile-names.html <<'EOF' 2>&1 | tail -n 1
import sys
html = open(sys.argv[1], encoding="utf-8").read()
tag = '<script id="dfrecon-data" type="application/json">'
start = html.index(tag) + len(tag)
block = html[start:html.index("</script>", start)]
if any(c in block for c in "<>&"):
    print("markup in the report's data block")
EOF
}

case_outputs() {
    cp two-rois.slices hin.slices && cp hin.slices hin.slices.orig
    KEEP=hin.slices CHECK=check_unchanged \
        run_case out-histogram-onto-input 1 "" dfr histogram hin.slices --roi "Left Kidney" --to PTV -o hin.slices
    KEEP=hin.slices CHECK=check_unchanged \
        run_case out-reconstruct-onto-input 1 "" dfr reconstruct hin.slices --all -o hin.slices
    cp y.ply yin.ply && cp yin.ply yin.ply.orig
    KEEP=yin.ply CHECK=check_unchanged \
        run_case out-compare-csv-onto-mesh 1 "" dfr compare yin.ply yin.ply --csv yin.ply
    CHECK=check_char_device \
        run_case out-reconstruct-to-device 1 "" dfr reconstruct y.slices -o /dev/null
    CHECK=check_char_device \
        run_case out-histogram-to-device 1 "" dfr histogram two-rois.slices --roi "Left Kidney" --to PTV -o /dev/null
    rm -f out-fifo.ply && mkfifo out-fifo.ply
    run_case out-reconstruct-to-fifo 1 "" dfr reconstruct y.slices -o out-fifo.ply
    run_case out-same-mesh-and-report 1 "" dfr reconstruct y.slices -o same.ply --report same.ply
    run_case out-same-csv-and-plot 1 "" dfr histogram two-rois.slices --roi "Left Kidney" --to PTV -o same.csv --plot same.csv
    run_case out-case-only-differs 1 "" dfr histogram two-rois.slices --roi "Left Kidney" --to PTV -o case.csv --plot CASE.csv
    mkdir -p sdm-a sdm-b && cp y.ply sdm-a/lung.ply && cp y.ply sdm-b/LUNG.ply
    CHECK=check_both_sdm_maps \
        run_case out-sdm-names-by-case 0 "" dfr sdm sdm-a/lung.ply sdm-b/LUNG.ply --size 256 --no-images -o sdm-case
    sed 's/^roi "Left Kidney"/roi "<\/script><!--<script>x"/' two-rois.slices >hostile-names.slices
    CHECK=check_inert_report \
        run_case report-hostile-names 0 "" dfr reconstruct hostile-names.slices --all -o hostile-out --report hostile-names.html
}

case_numbers_and_expressions() {
    run_case margin-mm-nan 1 "" dfr margin two-rois.slices --roi PTV --mm nan -o m.slices
    run_case margin-min-area-nan 1 "" dfr margin two-rois.slices --roi PTV --mm 2 --min-area nan -o m.slices
    run_case histogram-bin-inf 1 "" dfr histogram two-rois.slices --roi "Left Kidney" --to PTV --bin inf
    run_case compare-jobs-huge 0 "" dfr compare two-rois.slices two-rois.slices -j 4294967295
    run_case combine-nested-60000 1 "" dfr combine two-rois.slices --expr "X = $(printf '(%.0s' $(seq 60000))PTV$(printf ')%.0s' $(seq 60000))" -o c.slices
    run_case combine-union-10000 1 "" dfr combine two-rois.slices --expr "X = PTV$(printf ' | PTV%.0s' $(seq 10000))" -o c.slices
    run_case combine-margins-past-200 1 "" dfr combine two-rois.slices --expr "X = PTV + 150 + 150" -o c.slices
    run_case combine-name-control-char 1 "" dfr combine two-rois.slices --expr $'X\x01Y = PTV + 1' -o c.slices
}

CASES=(
    case_max_error
    case_outputs
    case_numbers_and_expressions
    case_batch_max_error
    case_batch_worker_crash
    case_record_nested
    bg:case_record_fifo
    case_record_dev_zero
    case_batch_huge_inputs
    case_dicom_zeros
    case_mesh_fan
    case_stdin_endless_comments
    case_manifest_400k
    case_like_huge_grid
    case_compare_cube
    case_tiny_planes
    case_latin1
    case_dev_full
    case_manifest_repeated_key
    case_label_table_colours
    case_batch_report_stdout
    case_record_mesh_outside
    case_long_roi_name
    case_rtstruct_quote
    case_label_table_control
    case_label_table_global
    bg:case_fifo_inputs
    case_dev_zero_inputs
    case_manifest_nested
    case_manifest_nul
)

# SWEEP_ONLY="case_a case_b": run only these (for working on the script).
if [ -n "${SWEEP_ONLY:-}" ]; then
    kept=()
    for c in "${CASES[@]}"; do
        for o in $SWEEP_ONLY; do [ "${c#bg:}" = "$o" ] && kept+=("$c"); done
    done
    CASES=("${kept[@]}")
fi

setup

run_one() {  # INDEX FUNCTION
    ROWFILE=$W/.rows/$(printf '%03d' "$1")-$2.tsv
    : >"$ROWFILE"
    (cd "$W" && "$2") >>"$W/.logs/$2.log" 2>&1
}

i=0
for c in "${CASES[@]}"; do
    i=$((i + 1))
    [ "${c#bg:}" != "$c" ] && run_one "$i" "${c#bg:}" &
done
i=0
for c in "${CASES[@]}"; do
    i=$((i + 1))
    [ "${c#bg:}" = "$c" ] && run_one "$i" "$c"
done
wait

printf 'case\texpect\texit\tseconds\tverdict\tstderr\n'
cat "$W"/.rows/*.tsv
awk -F '\t' '
    $5 ~ /^PASS/ { p++ } $5 ~ /^FAIL/ { f++ } $5 ~ /^SKIP/ { s++ }
    END { printf "# %d passed, %d failed of %d%s\n", p, f, p + f + s, (s ? sprintf(" (%d skipped)", s) : "") }
' "$W"/.rows/*.tsv
exit 0
