#!/usr/bin/env bash
# Two figures about the shape of the code, reproducible on any checkout (docs/design.md,
# "Measuring the code's shape"):
#   1. the longest functions of a folder (default src/app), from universal-ctags' start and
#      end lines (lambdas are counted inside the function that holds them);
#   2. the blocks of six or more lines that a folder (default src/) holds twice: windows of
#      six consecutive lines (blank lines, lone braces and preprocessor lines left out) that
#      occur in two or more places, compared twice: exactly (after trimming whitespace) and
#      by shape (every name, number and string literal replaced by a placeholder, so a loop
#      pasted with other variable names counts); overlapping windows are merged into one
#      block per place.
#
#   scripts/code_metrics.sh [--functions DIR] [--duplicates DIR] [--top N] [--min-lines N]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$here"
fn_dir=src/app
dup_dir=src
top=10
min_lines=6
while [ $# -gt 0 ]; do
  case "$1" in
    --functions) fn_dir=$2; shift ;;
    --duplicates) dup_dir=$2; shift ;;
    --top) top=$2; shift ;;
    --min-lines) min_lines=$2; shift ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    *) echo "code_metrics.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
  shift
done
command -v ctags >/dev/null || { echo "code_metrics.sh: needs universal-ctags (Debian package universal-ctags)" >&2; exit 1; }

echo "## Longest functions in $fn_dir (lines, from ctags)"
echo
echo "| lines | function | file:line |"
echo "|---:|---|---|"
find "$fn_dir" -name '*.cpp' -o -name '*.h' | sort |
  xargs ctags -x --c++-kinds=f --fields=+ne --_xformat="%N %F %n %e" 2>/dev/null |
  awk '$1 !~ /^__anon/ && $4 != "" { print $4 - $3 + 1, $1, $2 ":" $3 }' |
  sort -k1,1nr | head -n "$top" | awk '{ printf "| %d | %s | %s |\n", $1, $2, $3 }'
echo

echo "## Blocks of $min_lines or more lines that $dup_dir holds twice"
echo
for mode in exact shape; do
python3 - "$dup_dir" "$min_lines" "$mode" <<'PY'
import os, sys
from collections import defaultdict
import re
root, k, mode = sys.argv[1], int(sys.argv[2]), sys.argv[3]
TOKEN = re.compile(r'"(?:[^"\\]|\\.)*"|\'(?:[^\'\\]|\\.)*\'|\b\d[\w.]*|\b[A-Za-z_]\w*')
KEEP = set('''if else for while do switch case return break continue const auto static inline void bool int
float double size_t uint32_t uint64_t int64_t char struct class namespace template typename using new delete
true false nullptr this operator public private protected virtual override'''.split())
def shape(l):
    if mode == 'exact':
        return l
    return TOKEN.sub(lambda m: m.group(0) if m.group(0) in KEEP else ('S' if m.group(0)[0] in '"\'' else ('0' if m.group(0)[0].isdigit() else 'x')), l)
files = []
for d, _, names in os.walk(root):
    if '/glad' in d:  # generated loader, not ours
        continue
    for n in sorted(names):
        if n.endswith(('.cpp', '.h')):
            files.append(os.path.join(d, n))
lines = {}
windows = defaultdict(list)
for f in sorted(files):
    text = [(i + 1, l.strip()) for i, l in enumerate(open(f, encoding='utf-8', errors='replace'))]
    text = [(i, l) for i, l in text if l and not l.startswith('#') and l not in ('{', '}', '};', '});', ')')]
    lines[f] = text
    for j in range(len(text) - k + 1):
        key = '\n'.join(shape(l) for _, l in text[j:j + k])
        windows[key].append((f, j))
# Window starts that have a twin elsewhere, merged into maximal runs per file.
dup = defaultdict(set)
for key, places in windows.items():
    if len(places) < 2:
        continue
    for f, j in places:
        dup[f].update(range(j, j + k))
blocks = []
for f, idx in dup.items():
    idx = sorted(idx)
    start = prev = idx[0]
    for j in idx[1:] + [None]:
        if j is not None and j == prev + 1:
            prev = j
            continue
        first, last = lines[f][start][0], lines[f][prev][0]
        blocks.append((prev - start + 1, f, first, last))
        if j is not None:
            start = prev = j
blocks.sort(key=lambda b: (-b[0], b[1], b[2]))
total = sum(b[0] for b in blocks)
print(f"{mode}: {len(blocks)} blocks, {total} lines in all (each place counted)\n")
print("| lines | file:first-last |")
print("|---:|---|")
for n, f, a, b in blocks[:40]:
    print(f"| {n} | {f}:{a}-{b} |")
if len(blocks) > 40:
    print(f"| ... | {len(blocks) - 40} more |")
PY
echo
done
