#!/usr/bin/env bash
# Install what is missing, build in build/, then run the whole ctest suite.
# Extra arguments go to ctest, e.g. ./test.sh -L thermal  or  ./test.sh -LE stability
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
"$root/scripts/setup.sh"
# Layering: mechanics and thermal never include each other; coupling rooms include downwards only.
"$root/scripts/check_layers.sh"
cd "$root/build"
ctest --output-on-failure -j "$(nproc)" --timeout 600 "$@"
