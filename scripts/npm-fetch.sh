# Shared by the vendor-*.sh scripts (sourced, not run): fetch_verified PACKAGE VERSION
# fetches PACKAGE@VERSION from the npm registry with `npm pack` into the current folder, checks the
# tarball against the registry's integrity hash and unpacks it into ./package.
fetch_verified() {
    npm pack "$1@$2" --silent > /dev/null
    tarball="$(echo "$1" | sed 's/^@//; s#/#-#')-$2.tgz"
    expected="$(npm view "$1@$2" dist.integrity)"
    actual="sha512-$(openssl dgst -sha512 -binary "$tarball" | base64 -w0)"
    if [ "$expected" != "$actual" ]; then
        echo "integrity mismatch for $1@$2: registry $expected, tarball $actual" >&2
        exit 1
    fi
    tar xzf "$tarball"
}
