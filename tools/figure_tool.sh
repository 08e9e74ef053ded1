# Shared by the tools that regenerate measured figures (tools/lutz_figures.sh,
# tools/lean_table.sh); sourced from the repository root.
#
#   figure_tool_start "$0" "$@"   --help prints the caller's header comment and exits; sets
#                                 `threads` (the first argument, default all cores; anything else
#                                 is a usage error) and `bin` (OCEANREF_BIN resolved by the caller
#                                 before its cd, or build/src/oceanref, built when missing) and
#                                 `work` (a temporary folder, removed on exit)
#   measured_on THREADS SECONDS   "Measured DATE on CPU (THREADS threads), commit C[ with
#                                 uncommitted changes], SECONDS s."
figure_tool_start() {
  local script=$1
  shift
  case "${1:-}" in
    -h | --help)
      sed -n '2,/^set -euo/p' "$script" | sed '$d; s/^# \{0,1\}//'
      exit 0
      ;;
  esac
  threads=${1:-$(nproc)}
  [[ "$threads" =~ ^[1-9][0-9]*$ ]] && [ $# -le 1 ] || {
    echo "usage: $script [THREADS]" >&2
    exit 2
  }
  if [ -z "${bin:-}" ]; then
    bin=$PWD/build/src/oceanref
    [ -x "$bin" ] || bash tools/build.sh build >&2
  fi
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
}

measured_on() {
  local cpu commit dirty=""
  cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
  commit=$(git rev-parse --short HEAD)
  [ -n "$(git status --porcelain --untracked-files=no)" ] && dirty=" with uncommitted changes"
  echo "Measured $(date +%F) on ${cpu:-unknown} ($1 threads), commit $commit$dirty, $2 s."
}
