#!/usr/bin/env bash
# Installs a build into a temporary prefix and packs it as a .deb, then checks that both run
# from another directory: `lodline render` of the default model (found beside the installed
# program) and `import lodline`. The .deb is unpacked with dpkg -x into a temporary root; its
# declared dependencies must be installed packages here. Run by CTest (InstallAndPackage).
#
#   scripts/check_install.sh BUILD_DIR
set -euo pipefail
build=$(cd "${1:?usage: check_install.sh BUILD_DIR}" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export XDG_CACHE_HOME="$tmp/cache"
py=/usr/bin/python3

cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
mkdir "$tmp/elsewhere"
cd "$tmp/elsewhere"
"$tmp/prefix/bin/lodline" render -o prefix.png --size 160x120 --stats prefix.json
grep -q '"faces": 69120' prefix.json || { echo "check_install: the installed default model was not rendered" >&2; exit 1; }
test -f "$tmp/prefix/share/lodline/models/machine.json"
test -f "$tmp/prefix/share/doc/lodline/README.md"
if ls "$tmp"/prefix/lib/python3/dist-packages/lodline*.so >/dev/null 2>&1; then
  PYTHONPATH="$tmp/prefix/lib/python3/dist-packages" "$py" -c "
import lodline
f = lodline.render('$tmp/prefix/share/lodline/models/knot.off', size=(64, 48))
assert f.image.shape == (48, 64, 4), f.image.shape
print('check_install: prefix: python module renders', f.stats['lod']['active_faces'], 'faces')"
fi

(cd "$build" && cpack -G DEB -B "$tmp/deb" >/dev/null)
deb=$(ls "$tmp"/deb/lodline_*.deb)
depends=$(dpkg-deb -f "$deb" Depends)
echo "check_install: $(basename "$deb") depends on: $depends"
for lib in libpng16 libopenmesh libglfw3 libegl-mesa0 ffmpeg python3-numpy; do
  case "$depends" in *"$lib"*) ;; *) echo "check_install: $lib is not among the .deb's dependencies" >&2; exit 1 ;; esac
done
# Every declared dependency (first of each alternative, version aside) is a package installed here.
IFS=',' read -ra deps <<<"$depends"
for d in "${deps[@]}"; do
  name=$(sed -E 's/^ *([^ |(]+).*/\1/' <<<"$d")
  dpkg-query -W -f='${Status}' "$name" 2>/dev/null | grep -q "install ok installed" ||
    { echo "check_install: dependency $name is not installed" >&2; exit 1; }
done
dpkg -x "$deb" "$tmp/root"
"$tmp/root/usr/bin/lodline" render -o deb.png --size 160x120
test -s deb.png
if ls "$tmp"/root/usr/lib/python3/dist-packages/lodline*.so >/dev/null 2>&1; then
  PYTHONPATH="$tmp/root/usr/lib/python3/dist-packages" "$py" -c "import lodline; print('check_install: .deb: import lodline', lodline.__version__)"
fi
cmp -s prefix.png deb.png || { echo "check_install: the prefix and the .deb render differently" >&2; exit 1; }
echo "check_install: ok"
