#!/usr/bin/env bash
# Fails when a source file includes a room it may not see. Every library is a house of rooms,
# lowest first; a room may include its own files and the rooms below it, never above:
#   mechanics/   model -> detection -> contact -> solvers -> integrator
#   thermal/     network -> modes -> system -> integrators -> steady
#                (mechanics and thermal never include each other, nor anything of coupling/)
#   coupling/    common -> output -> scene -> bridge -> run -> studies -> app
#     common      small helpers every room may use (number formatting)
#     output      result files, summary, checkpoints, progress: stands alone
#     scene       scene input: may use mechanics, thermal for the heat-transfer modes'
#                 declarations (ModeRegistry: sections, keys, ranges), and output to read
#                 particles from a result file ([[import]])
#     bridge      contacts -> thermal network: scene, mechanics, thermal
#     run         the time loop: bridge, scene, output
#     studies     studies: run and below
#     app         the program and its commands: everything
# Usage: scripts/check_layers.sh [SOURCE_ROOT]
set -uo pipefail
root="${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}"
cd "$root" || exit 2

mechanics="mechanics/model mechanics/detection mechanics/contact mechanics/solvers mechanics/integrator"
thermal="thermal/network thermal/modes thermal/system thermal/integrators thermal/steady"
declare -A allowed=(
  [mechanics/model]="mechanics/model"
  [mechanics/detection]="mechanics/model mechanics/detection"
  [mechanics/contact]="mechanics/model mechanics/detection mechanics/contact"
  [mechanics/solvers]="mechanics/model mechanics/detection mechanics/contact mechanics/solvers"
  [mechanics/integrator]="mechanics/model mechanics/detection mechanics/contact mechanics/solvers mechanics/integrator"
  [thermal/network]="thermal/network"
  [thermal/modes]="thermal/network thermal/modes"
  [thermal/system]="thermal/network thermal/modes thermal/system"
  [thermal/integrators]="thermal/network thermal/modes thermal/system thermal/integrators"
  [thermal/steady]="thermal/network thermal/modes thermal/system thermal/integrators thermal/steady"
  [coupling/common]="coupling/common"
  [coupling/scene]="$mechanics $thermal coupling/common coupling/output coupling/scene"
  [coupling/output]="coupling/common coupling/output"
  [coupling/bridge]="$mechanics $thermal coupling/common coupling/scene coupling/bridge"
  [coupling/run]="$mechanics $thermal coupling/common coupling/scene coupling/output coupling/bridge coupling/run"
  [coupling/studies]="$mechanics $thermal coupling/common coupling/scene coupling/output coupling/bridge coupling/run coupling/studies"
  [coupling/app]="$mechanics $thermal coupling/common coupling/scene coupling/output coupling/bridge coupling/run coupling/studies coupling/app"
)

# One grep per room, and the include lines taken apart by bash itself: a grep per file and a sed
# and a cut per include line had made this script take 5.5 s of CPU (3.5 user + 2.0 sys), now
# 0.3 s; it runs twice in ./test.sh (a step and the ctest test layers).
include_re='^([^:]+):([0-9]+):[[:space:]]*#[[:space:]]*include[[:space:]]*"([^"]+)"'
bad=0
for layer in "${!allowed[@]}"; do
  [ -d "$layer" ] || { echo "check_layers: missing folder $layer" >&2; bad=1; continue; }
  # Only the files directly in the room's folder (every room is a folder of its own).
  mapfile -d '' files < <(find "$layer" -maxdepth 1 -type f \( -name '*.h' -o -name '*.cpp' \) -print0)
  [ ${#files[@]} -eq 0 ] && continue
  while IFS= read -r line; do
    [[ $line =~ $include_re ]] || continue
    file="${BASH_REMATCH[1]}" number="${BASH_REMATCH[2]}" target="${BASH_REMATCH[3]}"
    case "$target" in
      mechanics/*/* | thermal/*/* | coupling/*/*) rest="${target#*/}"; room="${target%%/*}/${rest%%/*}" ;;
      mechanics/* | thermal/* | coupling/*) room="${target%/*} (no room)" ;;
      *) continue ;;
    esac
    if [[ " ${allowed[$layer]} " != *" $room "* ]]; then
      echo "check_layers: $file:$number includes \"$target\": $layer may include only: ${allowed[$layer]}" >&2
      bad=1
    fi
  done < <(grep -HnE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "${files[@]}" || true)
done
# Flat files left in a library's folder would belong to no room; so would an unknown folder.
stray=$(find mechanics thermal coupling -maxdepth 1 -type f \( -name '*.h' -o -name '*.cpp' \))
[ -n "$stray" ] && { echo "check_layers: files outside a room: $stray" >&2; bad=1; }
while IFS= read -r -d '' dir; do
  [ -n "${allowed[$dir]+x}" ] || { echo "check_layers: $dir is no known room (add it to allowed)" >&2; bad=1; }
done < <(find mechanics thermal coupling -mindepth 1 -maxdepth 1 -type d -print0)
unknown_deeper=$(find mechanics thermal coupling -mindepth 2 -type f \( -name '*.h' -o -name '*.cpp' \) | awk -F/ 'NF > 3')
[ -n "$unknown_deeper" ] && { echo "check_layers: files nested below a room: $unknown_deeper" >&2; bad=1; }
# One header extension across the project.
hpp=$(find mechanics thermal coupling tests bench -name '*.hpp')
[ -n "$hpp" ] && { echo "check_layers: use .h headers: $hpp" >&2; bad=1; }
[ $bad -eq 0 ] && echo "check_layers: every include points down the layers"
exit $bad
