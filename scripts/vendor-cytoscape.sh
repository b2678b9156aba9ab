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
DEST="$(cd "$(dirname "$0")/.." && pwd)/src/topostore/http/static"
WORK="$(mktemp -d)"
. "$(dirname "$0")/npm-fetch.sh"
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
fetch_verified "cytoscape" "$VERSION"
cp package/dist/cytoscape.min.js "$DEST/cytoscape.min.js"
cp package/LICENSE "$DEST/cytoscape.LICENSE"
echo "cytoscape@$VERSION" > "$DEST/cytoscape.VERSION"
echo "vendored cytoscape@$VERSION into $DEST"
