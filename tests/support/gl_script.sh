# Sourced by the command-line tests that render: `. "$repo/tests/support/gl_script.sh" "$@"` after
# setting exe and repo. Re-runs the script under Xvfb when there is no display; gives $work (a
# temporary folder removed at exit), fail (counts a failure and says it) and $failures.
if [ -z "${DISPLAY:-}" ]; then
  exec xvfb-run -a -s "-screen 0 1600x900x24" bash "$0" "$@"
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
