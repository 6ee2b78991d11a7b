#!/usr/bin/env bash
# Install what is missing, build in build/, then run a scene (default: the built-in paper bed).
# Usage: ./run.sh [SCENE.toml] [tmdem run options...]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
"$root/scripts/setup.sh"
exec "$root/build/tmdem" run "$@"
