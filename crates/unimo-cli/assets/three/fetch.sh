#!/usr/bin/env bash
# Re-fetches the vendored three.js (the minified ES module build and its MIT licence)
# from npm. The version is pinned: change VERSION, run this, check the page
# (cargo test --test animate), commit. `cargo test` never needs npm.
set -euo pipefail
VERSION=0.170.0
here="$(cd "$(dirname "$0")" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
(cd "$work" && npm pack --silent "three@$VERSION" >/dev/null && tar xzf "three-$VERSION.tgz")
cp "$work/package/build/three.module.min.js" "$here/three.module.min.js"
cp "$work/package/LICENSE" "$here/LICENSE"
echo "$VERSION" > "$here/VERSION"
sha256sum "$here/three.module.min.js"
