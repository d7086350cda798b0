#!/usr/bin/env bash
# Vendors the 3D viewer that HTML reports embed (app/HtmlReport): three.js
# from the npm registry at a pinned version, checked against the registry's
# sha512 integrity, into DEST (default build/vendor/three). Its UMD build
# (build/three.min.js, the global THREE) and the matching OrbitControls
# (examples/js/controls/OrbitControls.js) are plain scripts, so a report can
# inline them and open from file:// with no network. 0.147.0 is the last
# release that ships both. Idempotent: a present, matching copy is kept.
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
dest=${1:-$repo_root/build/vendor/three}
version=0.147.0
integrity=sha512-LPTOslYQXFkmvceQjFTNnVVli2LaVF6C99Pv34fJypp8NbQLbTlu3KinZ0zURghS5zEehK+VQyvWuPZ/Sm8fzw==

if [ -f "$dest/VERSION" ] && [ "$(cat "$dest/VERSION")" = "$version $integrity" ]; then
  exit 0
fi
if ! command -v npm >/dev/null; then
  echo "vendor_viewer.sh: npm is missing (Debian: apt-get install npm)" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && npm pack --silent "three@$version" >/dev/null)
tarball="$work/three-$version.tgz"
actual="sha512-$(openssl dgst -sha512 -binary "$tarball" | base64 -w0)"
if [ "$actual" != "$integrity" ]; then
  echo "vendor_viewer.sh: three@$version does not match its pinned integrity" >&2
  exit 1
fi
tar -xzf "$tarball" -C "$work" package/build/three.min.js \
  package/examples/js/controls/OrbitControls.js package/LICENSE
mkdir -p "$dest"
cp "$work/package/build/three.min.js" "$work/package/examples/js/controls/OrbitControls.js" \
  "$work/package/LICENSE" "$dest/"
echo "$version $integrity" > "$dest/VERSION"
echo "setup: vendored three.js $version into $dest"
