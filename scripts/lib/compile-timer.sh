#!/usr/bin/env bash
# A compiler launcher that times each compile: `FREMOND_COMPILE_TIMES=FILE` in the environment of
# the build scripts appends "SECONDS OBJECT" to FILE for every object built (through ccache where
# it is installed), to find the translation units that cost the most.
start=$(date +%s%N)
if command -v ccache >/dev/null; then ccache "$@"; else "$@"; fi
rc=$?
object=unknown
prev=""
for a in "$@"; do
  [ "$prev" = -o ] && object=$a
  prev=$a
done
ms=$((($(date +%s%N) - start) / 1000000))
printf "%d.%03d %s\n" $((ms / 1000)) $((ms % 1000)) "$object" >>"${FREMOND_COMPILE_TIMES:-/dev/null}"
exit $rc
