#!/usr/bin/env bash
# Copies mesh files or label volumes into a libFuzzer corpus for
# tests/fuzz/fuzz_mesh.cpp or tests/fuzz/fuzz_label_volume.cpp. Those
# targets take the extension of their temporary file from an input's first
# byte, so each file goes in with that byte in front; the files in
# tests/data/ stay files of their own format, which any tool opens.
# Usage: scripts/fuzz_corpus.sh mesh|label CORPUS_DIR FILE...
# (docs/fuzzing.md). Files already in the corpus are left as they are.
set -euo pipefail
kind=$1 corpus=$2
shift 2
mkdir -p "$corpus"
for file in "$@"; do
    [ -f "$file" ] || continue
    # The index into the target's kExtensions, as an octal escape.
    case "$kind:${file,,}" in
        mesh:*.ply) byte='\000' ;;
        mesh:*.off) byte='\001' ;;
        mesh:*.obj) byte='\002' ;;
        mesh:*.stl) byte='\003' ;;
        label:*.nrrd) byte='\000' ;;
        label:*.nhdr) byte='\001' ;;
        label:*.nii) byte='\002' ;;
        label:*.nii.gz) byte='\003' ;;
        *) continue ;;  # a data file a header names, or anything else
    esac
    target="$corpus/$(basename "$file")"
    [ -e "$target" ] || { printf "$byte"; cat "$file"; } >"$target"
done
