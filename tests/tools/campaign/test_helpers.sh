# Helpers the campaign's shell tests share (sourced). fail/check count failures in $failures;
# the test exits with it.
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
check() { "$@" || fail "$*"; }
# Whether a process works in a folder under $1 (a run's folder; no procps needed).
running_in() {
  local d c
  for d in /proc/[0-9]*; do
    c=$(readlink "$d/cwd" 2>/dev/null) || continue
    case "$c" in "$1"*) return 0 ;; esac
  done
  return 1
}
