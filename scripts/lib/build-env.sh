# Sourced by the build scripts: the compiler cache and the stage timer they share.
#
# ccache (installed by scripts/install-deps.sh) serves every build tree: the Release tree of
# scripts/test.sh and the sanitizer tree of scripts/sanitize.sh. CCACHE_BASEDIR makes the cached
# objects independent of where the checkout lives, so a fresh clone in another folder compiles
# from the cache of the last one (CI runs in such a clone right after the work).

# FREMOND_CMAKE_LAUNCHER: the -D option that puts ccache in front of the compiler, or nothing.
FREMOND_CMAKE_LAUNCHER=()
if command -v ccache >/dev/null && [ "${FREMOND_NO_CCACHE:-0}" != 1 ]; then
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
  export CCACHE_NOHASHDIR=1          # -g builds: the build folder's name stays out of the hash
  export CCACHE_SLOPPINESS="${CCACHE_SLOPPINESS:-pch_defines,time_macros,include_file_mtime}"
  export CCACHE_MAXSIZE="${CCACHE_MAXSIZE:-5G}"
  FREMOND_CMAKE_LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
# FREMOND_COMPILE_TIMES=FILE: time every compile into FILE (scripts/lib/compile-timer.sh).
if [ -n "${FREMOND_COMPILE_TIMES:-}" ]; then
  FREMOND_CMAKE_LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER="$PWD/scripts/lib/compile-timer.sh")
fi

# stage NAME COMMAND...: runs COMMAND, then prints "stage NAME: N s (ok|FAILED)"; returns its status.
stage() {
  local name=$1 t0 rc
  shift
  t0=$(date +%s)
  if "$@"; then rc=0; else rc=$?; fi
  echo "stage $name: $(($(date +%s) - t0)) s ($([ "$rc" -eq 0 ] && echo ok || echo "FAILED, exit $rc"))"
  return "$rc"
}
