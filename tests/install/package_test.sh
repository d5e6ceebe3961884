#!/usr/bin/env bash
# The .deb as a user gets it: `cpack -G DEB` in the build folder, then the package is unpacked
# into a scratch root (dpkg -x, no root needed) and the installed binary runs on an installed
# example. Also checks Depends (computed by dpkg-shlibdeps) and the maintainer scripts.
# Usage: package_test.sh BUILD_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

fail() { echo "FAIL: $*" >&2; exit 1; }

(cd "$work" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/out" >cpack.log 2>&1) ||
  { cat "$work/cpack.log" >&2; fail "cpack -G DEB failed"; }
debs=("$work"/out/seqc_*.deb)
[ -f "${debs[0]}" ] || fail "no seqc_*.deb in $(ls "$work/out")"
deb=${debs[0]}
version=$(dpkg-deb -f "$deb" Version)
[ "$version" = "@PROJECT_VERSION@" ] || fail "package version '$version', want @PROJECT_VERSION@"
[ "$(basename "$deb")" = "seqc_@PROJECT_VERSION@_$(dpkg --print-architecture).deb" ] ||
  fail "file name $(basename "$deb")"

# Depends comes from the libraries the binary links, not from a hand-kept list.
depends=$(dpkg-deb -f "$deb" Depends)
for lib in libyaml-cpp0.7 libfmt9 libhidapi-hidraw0 libsqlite3-0 libsndfile1 libc6 libstdc++6; do
  [[ $depends == *"$lib"* ]] || fail "Depends lacks $lib: $depends"
done

# Maintainer scripts reload udev; they are shell scripts that parse.
dpkg-deb -e "$deb" "$work/control"
for script in postinst postrm; do
  [ -x "$work/control/$script" ] || fail "$script missing or not executable"
  grep -q "udevadm control --reload-rules" "$work/control/$script" || fail "$script: no reload"
  sh -n "$work/control/$script" || fail "$script does not parse"
done

dpkg-deb -c "$deb" | awk '{print $6}' | sed 's#^\./#/#' | sort >"$work/files"
for f in /usr/bin/seqc /usr/share/seqc/seqc.schema.json /usr/share/man/man1/seqc.1.gz \
  /usr/share/bash-completion/completions/seqc /usr/share/zsh/vendor-completions/_seqc \
  /usr/share/fish/vendor_completions.d/seqc.fish /usr/lib/udev/rules.d/70-seqc.rules \
  /usr/share/doc/seqc/examples/walk.yaml /usr/share/doc/seqc/copyright; do
  grep -qx "$f" "$work/files" || fail "package lacks $f"
done
grep -q '^/usr/local' "$work/files" && fail "package installs under /usr/local"

root="$work/root"
dpkg -x "$deb" "$root"
seqc="$root/usr/bin/seqc"
[ "$("$seqc" --version)" = "seqc @PROJECT_VERSION@" ] || fail "--version: $("$seqc" --version)"
file "$seqc" | grep -q "stripped" || true
"$seqc" check "$root/usr/share/doc/seqc/examples/walk.yaml" >"$work/check.out" ||
  fail "installed seqc cannot check the installed example"
grep -q "43/1020 actions" "$work/check.out" || fail "check said: $(cat "$work/check.out")"
"$seqc" upload "$root/usr/share/doc/seqc/examples/walk.yaml" --port emu:xarm --run \
  2>"$work/upload.err" || fail "upload to emu:xarm failed: $(cat "$work/upload.err")"
grep -q "acknowledged 43 actions" "$work/upload.err" || fail "upload said: $(cat "$work/upload.err")"
grep -q 'TAG+="uaccess"' "$root/usr/lib/udev/rules.d/70-seqc.rules" || fail "rule lacks uaccess"
zcat "$root/usr/share/man/man1/seqc.1.gz" | head -3 | grep -q '^.TH SEQC 1' || fail "man page"

echo "package $(basename "$deb"): $(stat -c %s "$deb") bytes, $(wc -l <"$work/files") entries," \
  "installed binary $(stat -c %s "$seqc") bytes"
echo "Depends: $depends"
