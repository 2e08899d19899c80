# Independent runs of an experiment script on every core (sourced, bash):
#   job COMMAND...   starts COMMAND in the background once fewer than WL_JOBS
#                    (default: the number of cores) of the script's jobs run;
#   wait_jobs        waits for them all and fails if one failed.
# Each run writes its own folder, so the results are those of a serial run; CPU
# times measured while others run share the machine (WL_JOBS=1 runs one at a time).
wl_jobs=${WL_JOBS:-$(nproc)}
if ! [[ $wl_jobs =~ ^[1-9][0-9]*$ ]]; then
  echo "WL_JOBS: got '$wl_jobs', expected a positive integer" >&2
  exit 2
fi
wl_pids=()
job() {
  while [ "$(jobs -rp | wc -l)" -ge "$wl_jobs" ]; do wait -n || true; done
  "$@" &
  wl_pids+=("$!")
}
wait_jobs() {
  local pid failed=0
  for pid in "${wl_pids[@]}"; do wait "$pid" || failed=1; done
  wl_pids=()
  return "$failed"
}
