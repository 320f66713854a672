#!/usr/bin/env bash
# Soak test (docs/reliability.md): a long `lodline capture` on a randomised camera path (fast
# zooms, orbits, close-ups inside the bounding sphere), resident memory sampled every second.
#
#   scripts/soak.sh FRAMES [--build-dir DIR] [--model FILE.off] [--size WxH] [--seed N]
#                   [--out DIR] [--max-growth PERCENT]
#
# Uses DIR/lodline (default build-asan, the AddressSanitizer + UBSan build of
# scripts/setup.sh --sanitize; any sanitizer report ends the run with an error). The path is
# generated from --seed (default 1) around the model's bounding box (a plain OFF file,
# default models/knot.off). Writes into --out (default DIR/soak): path.json, capture.mp4,
# metrics.csv, stats.json, rss.csv (seconds, KiB) and summary.txt, and prints the summary:
# frames, wall time, resident memory after warm-up (the first sample past 20% of the run)
# and at the end, and the largest. Fails (exit 1) when the capture fails, a sanitizer
# reports, or, in runs of 1000 frames or more, memory grows by more than --max-growth percent
# (default 10) after warm-up. (A shorter run is mostly warm-up: ASan's quarantine alone
# fills up to 256 MiB. Its memory figures are reported, not checked.)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
frames=""
build_dir="$here/build-asan"
model="$here/models/knot.off"
size=320x240
seed=1
out=""
max_growth=10
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) build_dir=$2; shift ;;
    --model) model=$2; shift ;;
    --size) size=$2; shift ;;
    --seed) seed=$2; shift ;;
    --out) out=$2; shift ;;
    --max-growth) max_growth=$2; shift ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    -*) echo "soak.sh: unknown option '$1'" >&2; exit 2 ;;
    *) frames=$1 ;;
  esac
  shift
done
if ! [[ "$frames" =~ ^[0-9]+$ ]] || [ "$frames" -lt 10 ]; then
  echo "usage: scripts/soak.sh FRAMES (at least 10) [--build-dir DIR] [--model FILE.off] [--size WxH] [--seed N]" >&2
  exit 2
fi
exe="$build_dir/lodline"
[ -x "$exe" ] || { echo "soak.sh: $exe not found (build it: scripts/setup.sh --sanitize --build-dir $build_dir)" >&2; exit 2; }
out=${out:-$build_dir/soak}
mkdir -p "$out"
rm -f "$out"/capture.mp4 "$out"/metrics.csv "$out"/stats.json "$out"/rss.csv "$out"/summary.txt
fps=30

# Bounding box of the OFF model -> centre and radius.
read -r cx cy cz radius < <(awk '
  /^[[:space:]]*#/ || NF == 0 { next }
  state == 0 { state = 1; if ($1 ~ /OFF$/ && NF == 1) next; if ($1 ~ /OFF$/) { $1 = "" ; $0 = $0 } }
  state == 1 { nv = $1; state = 2; next }
  state == 2 && nv > 0 {
    for (i = 1; i <= 3; ++i) { if (n == 0 || $i < lo[i]) lo[i] = $i; if (n == 0 || $i > hi[i]) hi[i] = $i }
    ++n; if (--nv == 0) exit
  }
  END {
    if (n == 0) { print "0 0 0 0"; exit }
    dx = hi[1] - lo[1]; dy = hi[2] - lo[2]; dz = hi[3] - lo[3]
    printf "%.6g %.6g %.6g %.6g\n", (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2, (lo[3] + hi[3]) / 2, sqrt(dx*dx + dy*dy + dz*dz) / 2
  }' "$model")
if awk -v r="$radius" 'BEGIN { exit !(r > 0) }'; then :; else
  echo "soak.sh: cannot read a bounding box from $model (a plain OFF file is needed)" >&2; exit 2
fi

# Randomised path: a key every half second; each second picks an orbit step, a fast zoom
# (distance x/÷ up to 8 within half a second), or a close-up (eye 0.3-0.6 radii from a point
# on the model's bounding sphere, inside it).
duration=$(awk -v f="$frames" -v fps=$fps 'BEGIN { printf "%.6f", f / fps }')
awk -v seed="$seed" -v dur="$duration" -v cx="$cx" -v cy="$cy" -v cz="$cz" -v r="$radius" '
  function key(t, ex, ey, ez, tx, ty, tz, fov) {
    printf "%s    {\"time\": %.4f, \"eye\": [%.6g, %.6g, %.6g], \"target\": [%.6g, %.6g, %.6g], \"fov\": %.1f}",
      (nkeys++ ? ",\n" : ""), t, ex, ey, ez, tx, ty, tz, fov
  }
  BEGIN {
    srand(seed); pi = 3.14159265358979
    az = 0; el = 0.3; dist = 3.0
    printf "{\"keys\": [\n"
    for (t = 0; t <= dur + 0.5; t += 0.5) {
      u = rand()
      if (u < 0.45) { az += 0.6 + rand(); el = -1.2 + 2.4 * rand() }                 # orbit
      else if (u < 0.8) { dist = dist * (rand() < 0.5 ? 1.0 / (2 + 6 * rand()) : 2 + 6 * rand());
                          if (dist < 0.4) dist = 0.4; if (dist > 40) dist = 40 }     # fast zoom
      else {                                                                           # close-up
        a = 2 * pi * rand(); b = -1.2 + 2.4 * rand(); d = 0.3 + 0.3 * rand()
        px = cx + 0.8 * r * cos(b) * sin(a); py = cy + 0.8 * r * sin(b); pz = cz + 0.8 * r * cos(b) * cos(a)
        key(t, px + d * r * cos(b) * sin(a), py + d * r * sin(b), pz + d * r * cos(b) * cos(a), px, py, pz, 25 + 40 * rand())
        continue
      }
      key(t, cx + dist * r * cos(el) * sin(az), cy + dist * r * sin(el), cz + dist * r * cos(el) * cos(az), cx, cy, cz, 35)
    }
    printf "\n]}\n"
  }' > "$out/path.json"

export EGL_PLATFORM=surfaceless
unset DISPLAY WAYLAND_DISPLAY
export LSAN_OPTIONS="suppressions=$here/scripts/lsan.supp:print_suppressions=0"
export ASAN_OPTIONS="detect_odr_violation=0:abort_on_error=0${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
start=$(date +%s.%N)
"$exe" capture "$model" --path "$out/path.json" --fps $fps --frames "$frames" --size "$size" --msaa 1 \
  -o "$out/capture.mp4" --metrics "$out/metrics.csv" --stats "$out/stats.json" --cache-dir "$out/cache" \
  >"$out/stdout.txt" 2>"$out/stderr.txt" &
pid=$!
echo "seconds,rss_kib" > "$out/rss.csv"
while kill -0 "$pid" 2>/dev/null; do
  rss=$(awk '/^VmRSS:/ { print $2 }' "/proc/$pid/status" 2>/dev/null || true)
  [ -n "$rss" ] && echo "$(awk -v s="$start" -v n="$(date +%s.%N)" 'BEGIN { printf "%.1f", n - s }'),$rss" >> "$out/rss.csv"
  sleep 1
done
status=0
wait "$pid" || status=$?
wall=$(awk -v s="$start" -v n="$(date +%s.%N)" 'BEGIN { printf "%.0f", n - s }')

done_frames=$(awk -F, 'NR > 1 { n++ } END { print n + 0 }' "$out/metrics.csv" 2>/dev/null || echo 0)
read -r warm_t warm_rss end_t end_rss max_rss samples < <(awk -F, -v w="$wall" '
  NR == 1 { next }
  { t[++n] = $1; r[n] = $2; if ($2 > mx) mx = $2 }
  END {
    if (n == 0) { print "0 0 0 0 0 0"; exit }
    k = 1; while (k < n && t[k] < 0.2 * w) ++k
    print t[k], r[k], t[n], r[n], mx, n
  }' "$out/rss.csv")
growth=$(awk -v a="$warm_rss" -v b="$end_rss" 'BEGIN { if (a > 0) printf "%.1f", 100 * (b - a) / a; else print "0" }')
reports=$(grep -c -E "ERROR: AddressSanitizer|runtime error:|ERROR: LeakSanitizer" "$out/stderr.txt" || true)
{
  echo "soak: $frames frames requested, $done_frames captured, ${wall} s wall, exit status $status"
  echo "soak: model $model, ${size}, seed $seed, $(grep -c '"time"' "$out/path.json") path keys"
  echo "soak: RSS after warm-up ${warm_rss} KiB (at ${warm_t} s), at the end ${end_rss} KiB (at ${end_t} s), largest ${max_rss} KiB, ${samples} samples; growth ${growth}%"
  echo "soak: sanitizer reports: $reports"
} | tee "$out/summary.txt"
fail=0
[ "$status" -eq 0 ] || { echo "soak: capture failed:" >&2; tail -5 "$out/stderr.txt" >&2; fail=1; }
[ "$reports" -eq 0 ] || { echo "soak: sanitizer reports in $out/stderr.txt" >&2; fail=1; }
[ "$done_frames" -eq "$frames" ] || { echo "soak: $done_frames of $frames frames captured" >&2; fail=1; }
if [ "$frames" -lt 1000 ]; then
  echo "soak: memory growth not checked (fewer than 1000 frames: the run is mostly warm-up)"
elif awk -v g="$growth" -v m="$max_growth" 'BEGIN { exit !(g > m) }'; then
  echo "soak: memory grew ${growth}% after warm-up (more than ${max_growth}%)" >&2; fail=1
fi
exit $fail
