#!/bin/sh
# The README's and docs' screenshots and plan pictures (docs/images/), made
# again by the GUI test the way a user makes them: run it (build/, `ctest -R
# freecad_gui`, about 4 minutes under xvfb) unless --copy-only is given, then
# copy what it saved. Run after a change to the operation's page, the
# pictures or the demos; look at each picture before committing them.
set -eu
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${PLUNGE_BUILD_DIR:-$ROOT/build}
ART=$BUILD/test-artifacts
if [ "${1:-}" != --copy-only ]; then
  (cd "$BUILD" && ctest -R '^freecad_gui$' --output-on-failure)
fi
# docs/images name <- the GUI test's artifact
while read -r name artifact; do
  [ -f "$ART/$artifact" ] || { echo "refresh_doc_images: $ART/$artifact is missing (run the GUI test)" >&2; exit 1; }
  cp "$ART/$artifact" "$ROOT/docs/images/$name"
  echo "docs/images/$name <- $artifact"
done <<'MAP'
freecad_3d.png plunge_rough_3d.png
plunge_rough_gui.png plunge_rough_gui.png
plunge_rough_panel.png plunge_rough_panel.png
job_panel.png job_panel.png
example_simulated.png example_simulated.png
stock_left_window.png example_showStock.png
deep_pocket_plan.svg example/deep_pocket.svg
deep_pocket_stock.svg example/deep_pocket-stock.svg
MAP
