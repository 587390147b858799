# Sourced by tests that kill a run mid-way (cli.study_reductions, cli.study_stream).
# kill_when_grown <file> <bytes> <command...>: runs the command in a session of its own (stdout and stderr dropped),
# kills the whole session with SIGKILL once <file> holds more than <bytes> bytes (or after 20 s), and waits for it.
kill_when_grown() {
  local file=$1 bytes=$2
  shift 2
  setsid "$@" > /dev/null 2>&1 &
  local job=$!
  for _ in $(seq 1 400); do
    [ -f "$file" ] && [ "$(stat -c %s "$file")" -gt "$bytes" ] && break
    sleep 0.05
  done
  pkill -9 -s "$job" 2>/dev/null || true
  for _ in $(seq 1 200); do pgrep -s "$job" > /dev/null || break; sleep 0.05; done
  wait "$job" 2>/dev/null || true
}
