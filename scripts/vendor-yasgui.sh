#!/bin/sh
# Vendor YASGUI (SPARQL editor and result table) into the package's static files: the
# inspector's SPARQL console is served offline (robots often have no Internet access, so no CDN).
#
#   make vendor-js            # or: sh scripts/vendor-yasgui.sh [VERSION]
#
# Fetches @triply/yasgui from the npm registry with `npm pack`, checks the tarball against the
# registry's integrity hash, and copies the bundle (YASQE, YASR and their dependencies in one
# script and one style sheet), its MIT license and the licences of the libraries it bundles.
set -eu
VERSION="${1:-4.2.28}"
DEST="$(cd "$(dirname "$0")/.." && pwd)/src/topostore/http/static"
WORK="$(mktemp -d)"
. "$(dirname "$0")/npm-fetch.sh"
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
fetch_verified "@triply/yasgui" "$VERSION"
cp package/build/yasgui.min.js "$DEST/yasgui.min.js"
cp package/build/yasgui.min.css "$DEST/yasgui.min.css"
{
    cat package/LICENSE.txt
    printf '\n\nLibraries bundled in yasgui.min.js (package/build/yasgui.min.js.LICENSE.txt):\n\n'
    cat package/build/yasgui.min.js.LICENSE.txt
} > "$DEST/yasgui.LICENSE"
echo "@triply/yasgui@$VERSION" > "$DEST/yasgui.VERSION"
echo "vendored @triply/yasgui@$VERSION into $DEST"
