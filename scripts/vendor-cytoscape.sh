#!/bin/sh
# Vendor the Cytoscape.js graph library into the package's static files (the live map page
# is served offline: robots often have no Internet access, so no CDN).
#
#   make vendor-js            # or: sh scripts/vendor-cytoscape.sh [VERSION]
#
# Fetches the package from the npm registry with `npm pack`, checks the tarball against the
# registry's integrity hash, and copies dist/cytoscape.min.js and its MIT license.
set -eu
VERSION="${1:-3.34.4}"
DEST="$(cd "$(dirname "$0")/.." && pwd)/src/topostore/static"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
npm pack "cytoscape@$VERSION" --silent > /dev/null
EXPECTED="$(npm view "cytoscape@$VERSION" dist.integrity)"
ACTUAL="sha512-$(openssl dgst -sha512 -binary "cytoscape-$VERSION.tgz" | base64 -w0)"
if [ "$EXPECTED" != "$ACTUAL" ]; then
    echo "integrity mismatch for cytoscape@$VERSION: registry $EXPECTED, tarball $ACTUAL" >&2
    exit 1
fi
tar xzf "cytoscape-$VERSION.tgz"
cp package/dist/cytoscape.min.js "$DEST/cytoscape.min.js"
cp package/LICENSE "$DEST/cytoscape.LICENSE"
echo "cytoscape@$VERSION" > "$DEST/cytoscape.VERSION"
echo "vendored cytoscape@$VERSION into $DEST"
