#!/usr/bin/env bash
# Rewrites the command-line block of docs/REFERENCE.md (§1.2) with what the program prints
# (`luxtrace reference cli`), after an option or subcommand changed. Review with git diff.
#   scripts/update_reference.sh [LUXTRACE_BINARY]      (default: build/src/luxtrace)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
lux=${1:-$root/build/src/luxtrace}
doc=$root/docs/REFERENCE.md
begin='<!-- BEGIN luxtrace reference cli -->'
end='<!-- END luxtrace reference cli -->'
grep -qxF "$begin" "$doc" && grep -qxF "$end" "$doc" || { echo "$doc: no reference cli block" >&2; exit 1; }
block=$(mktemp)
trap 'rm -f "$block" "$doc.new"' EXIT
"$lux" reference cli > "$block"
awk -v begin="$begin" -v end="$end" -v block="$block" '
    $0 == begin { print; while ((getline line < block) > 0) print line; skip = 1; next }
    $0 == end   { skip = 0 }
    !skip       { print }' "$doc" > "$doc.new"
mv "$doc.new" "$doc"
echo "updated $doc"
