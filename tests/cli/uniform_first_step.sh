#!/usr/bin/env bash
# The paper's Section-6 variant (uniform first step) exists for c2ps and rts only: the scheme names
# c2ps-u and rts-u are the same as --uniform-first-step with c2ps and rts, and the flag with any
# other scheme is a usage error (exit 2, one line naming the command, then the usage), never
# accepted and ignored. Args: <polarview executable> <repository root>.
set -euo pipefail
exe=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$exe" shape globe --valence 8 --links 5 -o "$tmp/globe.obj"

# usage_error CMD ARGS...: exit 2, first line the one-line error, the usage after it, no output.
usage_error() {
  local command=$1
  shift
  set +e
  "$exe" "$command" "$@" > "$tmp/out" 2> "$tmp/err"
  local rc=$?
  set -e
  [ $rc -eq 2 ] || fail "$command $*: exit $rc, expected 2"
  [ "$(head -n 1 "$tmp/err")" = "polarview: $command: --uniform-first-step applies to c2ps and rts only" ] ||
    fail "$command $*: error line '$(head -n 1 "$tmp/err")'"
  sed -n 2p "$tmp/err" | grep -q "^usage: polarview $command " || fail "$command $*: no usage after the error"
  [ ! -s "$tmp/out" ] || fail "$command $*: printed on stdout"
}
for scheme in cc bps; do
  usage_error refine "$tmp/globe.obj" -o "$tmp/out.obj" --scheme $scheme --levels 1 --uniform-first-step
  [ ! -e "$tmp/out.obj" ] || fail "refine --scheme $scheme --uniform-first-step wrote its output"
  usage_error pole "$tmp/globe.obj" --scheme $scheme --uniform-first-step --json
  usage_error bench "$tmp/globe.obj" --scheme $scheme --levels 1 --reps 1 --uniform-first-step --json
done
# The flag before the scheme is judged with the scheme too.
usage_error refine "$tmp/globe.obj" --uniform-first-step -o "$tmp/out.obj" --levels 1 --scheme cc

# c2ps-u and rts-u: the same output as the flag, and not the same as without it.
for scheme in c2ps rts; do
  "$exe" refine "$tmp/globe.obj" -o "$tmp/named.obj" --scheme $scheme-u --levels 2
  "$exe" refine "$tmp/globe.obj" -o "$tmp/flag.obj" --scheme $scheme --uniform-first-step --levels 2
  "$exe" refine "$tmp/globe.obj" -o "$tmp/plain.obj" --scheme $scheme --levels 2
  cmp -s "$tmp/named.obj" "$tmp/flag.obj" || fail "--scheme $scheme-u differs from --scheme $scheme --uniform-first-step"
  if cmp -s "$tmp/named.obj" "$tmp/plain.obj"; then fail "--scheme $scheme-u is plain $scheme"; fi
  "$exe" pole "$tmp/globe.obj" --scheme $scheme-u --json | python3 -c "
import json,sys; p=json.load(sys.stdin)['poles']; assert len(p)==2 and p[0]['scheme']=='$scheme-u', p"
  "$exe" bench "$tmp/globe.obj" --scheme $scheme-u --levels 1 --reps 1 --json | python3 -c "
import json,sys; d=json.load(sys.stdin); assert d['scheme']=='$scheme-u' and d['out_faces']>0, d"
done
# pole without --scheme is c2ps: the flag applies.
"$exe" pole "$tmp/globe.obj" --uniform-first-step --json > /dev/null
# bps-u is no scheme.
set +e
"$exe" refine "$tmp/globe.obj" -o "$tmp/out.obj" --scheme bps-u --levels 1 2> /dev/null; rc=$?
set -e
[ $rc -eq 2 ] || fail "--scheme bps-u: exit $rc, expected 2"
grep -q "c2ps-u" <<< "$("$exe" --help)" || fail "the usage does not name c2ps-u"
echo "uniform_first_step: ok"
