#!/usr/bin/env bash
# Fails when a source file includes a layer it may not see. The layers, lowest first:
#   mechanics, thermal        never include each other (nor anything of coupling/)
#   coupling/common           small helpers every room may use (number formatting)
#   coupling/output           result files, summary, checkpoints, progress: stands alone
#   coupling/scene            scene input: may use mechanics, thermal for the heat-transfer
#                             modes' declarations (ModeRegistry: sections, keys, ranges), and
#                             output to read particles from a result file ([[import]])
#   coupling/bridge           contacts -> thermal network: scene, mechanics, thermal
#   coupling/run              the time loop: bridge, scene, output
#   coupling/studies          studies: run and below
#   coupling/app              the program and its commands: everything
# Usage: scripts/check_layers.sh [SOURCE_ROOT]
set -uo pipefail
root="${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}"
cd "$root" || exit 2

declare -A allowed=(
  [mechanics]="mechanics"
  [thermal]="thermal"
  [coupling/common]="coupling/common"
  [coupling/scene]="mechanics thermal coupling/common coupling/output coupling/scene"
  [coupling/output]="coupling/common coupling/output"
  [coupling/bridge]="mechanics thermal coupling/common coupling/scene coupling/bridge"
  [coupling/run]="mechanics thermal coupling/common coupling/scene coupling/output coupling/bridge coupling/run"
  [coupling/studies]="mechanics thermal coupling/common coupling/scene coupling/output coupling/bridge coupling/run coupling/studies"
  [coupling/app]="mechanics thermal coupling/common coupling/scene coupling/output coupling/bridge coupling/run coupling/studies coupling/app"
)

bad=0
for layer in "${!allowed[@]}"; do
  [ -d "$layer" ] || { echo "check_layers: missing folder $layer" >&2; bad=1; continue; }
  # Only the files directly in the layer's folder (coupling/ rooms are folders of their own).
  while IFS= read -r -d '' file; do
    while IFS= read -r line; do
      target=$(sed -E 's/^[0-9]+:[[:space:]]*#[[:space:]]*include[[:space:]]*"([^"]+)".*/\1/' <<<"$line")
      case "$target" in
        mechanics/*) room=mechanics ;;
        thermal/*) room=thermal ;;
        coupling/*/*) room=$(cut -d/ -f1-2 <<<"$target") ;;
        *) continue ;;
      esac
      ok=0
      for a in ${allowed[$layer]}; do [ "$a" = "$room" ] && ok=1; done
      if [ $ok -eq 0 ]; then
        echo "check_layers: $file:${line%%:*} includes \"$target\": $layer may include only: ${allowed[$layer]}" >&2
        bad=1
      fi
    done < <(grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$file" || true)
  done < <(find "$layer" -maxdepth 1 -type f \( -name '*.h' -o -name '*.cpp' \) -print0)
done
# Flat files left in coupling/ would belong to no room.
stray=$(find coupling -maxdepth 1 -type f \( -name '*.h' -o -name '*.cpp' \))
[ -n "$stray" ] && { echo "check_layers: files outside a coupling room: $stray" >&2; bad=1; }
# One header extension across the project.
hpp=$(find mechanics thermal coupling tests bench -name '*.hpp')
[ -n "$hpp" ] && { echo "check_layers: use .h headers: $hpp" >&2; bad=1; }
[ $bad -eq 0 ] && echo "check_layers: every include points down the layers"
exit $bad
