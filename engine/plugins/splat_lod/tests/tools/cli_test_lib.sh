# Sourced by the tools' CLI tests (*_cli_test.sh here), after they set `dir` (their output
# folder): a failure count, and a command that must fail with exit code 1 and a message.
failures=0

fail() {  # fail WHAT: counts a failure and says what
  echo "FAIL $1"
  failures=$((failures + 1))
}

expect_failure() {  # expect_failure NAME EXPECTED_TEXT COMMAND [ARGS...]: output in $dir/NAME.log
  local name=$1 text=$2
  shift 2
  local log="$dir/$name.log"
  "$@" >"$log" 2>&1
  local code=$?
  if [ "$code" -ne 1 ]; then
    fail "$name: exit code $code, expected 1"; cat "$log"; return
  fi
  if ! grep -q -- "$text" "$log"; then
    fail "$name: message lacks \"$text\":"; cat "$log"; return
  fi
  echo "ok   $name: $(tail -n 1 "$log")"
}
