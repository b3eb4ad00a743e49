#!/usr/bin/env bash
# The Blender add-on test (tests/blender/addon_test.py) in headless Debian Blender with a fresh user
# configuration; exit 77 (CTest: skipped) when there is no blender.
#   addon_test.sh ZIP CLI [WIDTH SAMPLES KEEP_DIR]
set -euo pipefail
zip=$(realpath "$1") cli=$(realpath "$2") width=${3:-96} samples=${4:-4} keep=${5:+$(realpath -m "$5")}
blender=$(command -v blender || true)
if [[ -z "$blender" ]]; then
  echo "SKIP: no blender on PATH (Debian: apt-get install blender)"
  exit 77
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/jellysim-blender.XXXXXX")
[[ -n "$keep" ]] || trap 'rm -rf "$work"' EXIT
export BLENDER_USER_CONFIG=$work/config BLENDER_USER_SCRIPTS=$work/scripts
mkdir -p "$BLENDER_USER_CONFIG" "$BLENDER_USER_SCRIPTS"
rc=0
cd "$(dirname "$0")/../.."  # the source tree: scenes/obstacles.toml names scenes/rock.txt from there
"$blender" -b --factory-startup --python-exit-code 1 -noaudio \
  --python tests/blender/addon_test.py -- "$zip" "$cli" "$work" "$width" "$samples" || rc=$?
if [[ -n "$keep" && -f "$work/frame.png" ]]; then mkdir -p "$keep" && cp "$work/frame.png" "$keep/"; fi
exit $rc
