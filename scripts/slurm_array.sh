#!/usr/bin/env bash
# A Slurm job array over a file of shell commands, one per line (what `lodline sweep
# --emit-commands` prints, or one `lodline capture --frames A:B` per shard): task i runs
# line i + 1. Submit with as many tasks as lines (docs/experiments.md):
#
#   lodline sweep MODEL --vary ... -o DIR --emit-commands > commands.txt
#   sbatch --array=0-$(( $(wc -l < commands.txt) - 1 ))%16 scripts/slurm_array.sh commands.txt
#   lodline sweep MODEL --vary ... -o DIR --collect      # once every task is done
#
#SBATCH --job-name=lodline
#SBATCH --cpus-per-task=2
#SBATCH --mem=4G
#SBATCH --output=lodline-%A_%a.log
set -euo pipefail
commands=${1:?usage: slurm_array.sh COMMANDS_FILE}
task=${SLURM_ARRAY_TASK_ID:?run under sbatch --array}
line=$(sed -n "$((task + 1))p" "$commands")
[ -n "$line" ] || { echo "slurm_array.sh: $commands has no line $((task + 1))" >&2; exit 2; }
# Headless GL on the node: Mesa's surfaceless EGL platform, no display.
export EGL_PLATFORM=surfaceless
unset DISPLAY
exec bash -c "$line"
