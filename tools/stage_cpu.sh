#!/usr/bin/env bash
# stage_cpu.sh NAME COMMAND...: run COMMAND in a cgroup of its own (created if missing, kept, so that the commands
# of one stage add up) and print the cgroup's CPU seconds so far and the command's wall time. The CPU counts every
# process the command starts (Chromium, kernels, sandboxes), whatever else the machine runs. Needs root and a
# cgroup v1 cpuacct or a cgroup v2 hierarchy. make's STAGE_CPU hook: make test STAGE_CPU=tools/stage_cpu.sh
# (STAGE_RUN, which the Makefile sets once per run, keeps one run's stages apart from another's).
set -u
name="make-stage-${STAGE_RUN:-0}-$1"; shift
if [ -d /sys/fs/cgroup/cpuacct ]; then
  cg=/sys/fs/cgroup/cpuacct/$name; read_ns() { cat "$cg/cpuacct.usage"; }
else
  cg=/sys/fs/cgroup/$name; read_ns() { echo $(( $(awk '/^usage_usec/ {print $2}' "$cg/cpu.stat") * 1000 )); }
fi
mkdir -p "$cg" || exit 1
start=$(date +%s%N)
bash -c 'echo $$ > "$1/cgroup.procs" 2>/dev/null || echo $$ > "$1/tasks"; shift; exec "$@"' _ "$cg" "$@"
rc=$?
wall=$(( ($(date +%s%N) - start) / 1000000 ))
ns=$(read_ns)
printf 'STAGE %s: %d.%03d s wall, %d.%01d CPU s in the stage so far (exit %d)\n' "${name#make-stage-*-}" \
  $((wall / 1000)) $((wall % 1000)) $((ns / 1000000000)) $(((ns / 100000000) % 10)) "$rc" >&2
exit $rc
