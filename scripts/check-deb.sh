#!/usr/bin/env bash
# Builds the Debian package from ./build, installs it with apt-get, and runs the
# installed fetic from an empty directory: `fetic figures` (headless rendering, the
# bundled thesis scene found under /usr/share/fetic) and `fetic solve` of an installed
# scene with every output. Then removes the package. It changes the system it runs on,
# so only CI (.ci/run, on its throwaway Debian 12 machine) runs it, never the test suite.
#
#   scripts/check-deb.sh            on this machine (CI)
#   scripts/check-deb.sh --fresh    in a fresh Debian 12 chroot (debootstrap minbase in
#                                   /tmp/fetic-deb12): proves the Depends are complete
set -euo pipefail
cd "$(dirname "$0")/.."
fresh=false
[ "${1:-}" = "--fresh" ] && fresh=true

[ -f build/CMakeCache.txt ] || { echo "check-deb: build first (scripts/setup.sh)"; exit 1; }
cmake --build build --target fetic fetic_man_page fetic_changelog
rm -f build/fetic_*.deb
(cd build && cpack -G DEB > cpack.log 2>&1) || { cat build/cpack.log; exit 1; }
deb=$(ls "$PWD"/build/fetic_*.deb)
echo "check-deb: built $(basename "$deb") ($(du -k "$deb" | cut -f1) kB)"
dpkg-deb --field "$deb" Depends

# Every library the binary links directly must come from a package the .deb depends on.
depends=$(dpkg-deb --field "$deb" Depends | tr ',|' '\n\n' | sed 's/(.*//; s/ //g' | sort -u)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
dpkg-deb -x "$deb" "$tmp/root"
for lib in $(readelf -d "$tmp/root/usr/bin/fetic" | sed -n 's/.*NEEDED.*\[\(.*\)\]/\1/p'); do
  # (awk reads all its input: an early exit would kill ldconfig with SIGPIPE)
  path=$(ldconfig -p | awk -v l="$lib" '$1 == l && /x86-64/ && !found {print $NF; found = 1}')
  package=$(dpkg -S "$(readlink -f "$path")" 2>/dev/null | awk -F: 'NR == 1 {print $1}' || true)
  [ -z "$package" ] && package=$(dpkg -S "$path" 2>/dev/null | awk -F: 'NR == 1 {print $1}' || true)
  if ! grep -qx "$package" <<<"$depends"; then
    echo "check-deb: $lib ($path, package '$package') is not in the package's Depends"
    exit 1
  fi
done
echo "check-deb: every linked library is covered by Depends"

# The documentation as installed: every relative link of README.md and docs/*.md (pages
# and pictures) resolves inside the package; the man page and the copyright are there.
doc="$tmp/root/usr/share/doc/fetic"
for page in "$doc/README.md" "$doc"/docs/*.md; do
  for link in $(grep -o '](\([^)#]*\)' "$page" | sed 's/^](//; s/)$//' | grep -v '^[a-z]*:' | sort -u); do
    [ -e "$(dirname "$page")/$link" ] ||
      { echo "check-deb: ${page#"$tmp/root"} links to $link, which the package lacks"; exit 1; }
  done
done
test -s "$doc/copyright" && test -s "$doc/changelog.Debian.gz"
zcat "$tmp/root/usr/share/man/man1/fetic.1.gz" | grep '^.SH "FETIC SOLVE"' > /dev/null
test -x "$tmp/root/usr/share/fetic/scripts/vtu_picture.py"
echo "check-deb: documentation links resolve; man page, copyright and helper script installed"
if command -v lintian > /dev/null; then
  lintian --fail-on error "$deb" | tee "$tmp/lintian.txt" || { echo "check-deb: lintian found errors"; exit 1; }
  echo "check-deb: lintian: $(grep -c '^E:' "$tmp/lintian.txt" || true) errors, $(grep -c '^W:' "$tmp/lintian.txt" || true) warnings"
fi

# A pipe into `grep -q` would close as soon as it matched: fetic checks every write and
# ends with status 5 when standard output is closed under it, which pipefail then makes
# this script's failure (it did, at random, on 5 December). grep > /dev/null reads it all.
run_installed() {  # the commands a user runs after installing, from an empty directory
  cat <<'SCRIPT'
set -euo pipefail
work=$(mktemp -d) && cd "$work"
fetic --version
fetic figures --out figures
test "$(ls figures/*.png | wc -l)" -ge 6
fetic scenes | grep two_bars > /dev/null
fetic solve two_bars --load-steps 0:2:5 --json r.json \
  --csv-steps curve.csv --vtu vtu --quiet
test -s r.json && test -s curve.csv && test -s vtu/struts.pvd
fetic bench-render --frames 3 --size 320x200 > /dev/null
fetic solve --help | grep "Exit status" > /dev/null
echo "check-deb: the installed fetic ran from $work"
rm -rf "$work"
SCRIPT
}

if ! $fresh; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get install -y -qq "$deb" > "$tmp/apt.log" 2>&1 || { cat "$tmp/apt.log"; exit 1; }
  status=0
  bash -c "$(run_installed)" || status=$?
  apt-get remove -y -qq fetic > /dev/null
  exit $status
fi

root=/tmp/fetic-deb12
if [ ! -x "$root/usr/bin/apt-get" ]; then
  command -v debootstrap > /dev/null || apt-get install -y -qq debootstrap
  debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian
fi
cp "$deb" "$root/tmp/"
mount -t proc proc "$root/proc"
trap 'umount "$root/proc"; rm -rf "$tmp"' EXIT
chroot "$root" /bin/bash -c "export DEBIAN_FRONTEND=noninteractive; apt-get update -qq &&
  apt-get install -y -qq /tmp/$(basename "$deb") > /tmp/apt.log 2>&1 || { cat /tmp/apt.log; exit 1; }"
chroot "$root" /bin/bash -c "$(run_installed)"
chroot "$root" apt-get remove -y -qq fetic > /dev/null
echo "check-deb: installed and ran in a fresh Debian 12 chroot ($root)"
