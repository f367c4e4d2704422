#!/usr/bin/env bash
# Rebuilds the JavaScript that report.html inlines: three.js and its OrbitControls at the versions
# pinned in src/ramap/report/assets/vendor/package.json, bundled by esbuild into one minified
# script with a global THREE, and three.js's licence beside it. To update: change the versions in
# package.json, run this, rebuild ramap, run the browser test (ctest -R browser_report), commit
# package.json, package-lock.json, three_bundle.min.js and THREE_LICENSE.txt together.
set -euo pipefail
vendor=$(cd "$(dirname "$0")/../src/ramap/report/assets/vendor" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$vendor/package.json" "$vendor/entry.js" "$work/"
[ -f "$vendor/package-lock.json" ] && cp "$vendor/package-lock.json" "$work/"
(cd "$work" && npm install --no-audit --no-fund >/dev/null &&
  npx esbuild entry.js --bundle --minify --format=iife --global-name=THREE \
    --legal-comments=none --outfile=three_bundle.min.js)
cp "$work/three_bundle.min.js" "$vendor/three_bundle.min.js"
cp "$work/node_modules/three/LICENSE" "$vendor/THREE_LICENSE.txt"
cp "$work/package-lock.json" "$vendor/package-lock.json"
echo "update_report_libs: three $(node -p "require('$work/node_modules/three/package.json').version")," \
  "$(wc -c <"$vendor/three_bundle.min.js") bytes in $vendor/three_bundle.min.js"
