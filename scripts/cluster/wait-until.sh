# Sourced by scripts that poll: wait_until SECONDS WHAT COMMAND... runs COMMAND every 0.2 s
# until it succeeds, or calls the sourcing script's `fail` after SECONDS. Not a job script:
# the scripts Slurm copies to its nodes (encode-chunk, join) stay self-contained.
wait_until() {
  local seconds=$1 what=$2
  shift 2
  for _ in $(seq 1 $((seconds * 5))); do
    if "$@"; then return 0; fi
    sleep 0.2
  done
  fail "timed out after $seconds s waiting for $what"
}
