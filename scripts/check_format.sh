#!/usr/bin/env bash
# Checks the C++ sources against .clang-format (clang-format-14): exit 1 listing the files
# that clang-format would change, with the number of lines each; 0 when all conform.
#   scripts/check_format.sh          check (the tests' format_check)
#   scripts/check_format.sh --fix    reformat those files in place
#   CLANG_FORMAT=clang-format-15 scripts/check_format.sh   another clang-format
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cf=${CLANG_FORMAT:-clang-format-14}
command -v "$cf" >/dev/null || { echo "check_format: $cf not found (scripts/install_deps.sh installs it)" >&2; exit 2; }
cd "$root"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    mapfile -t files < <(git ls-files --cached --others --exclude-standard -- '*.cpp' '*.hpp' '*.h' | sort -u)
else
    mapfile -t files < <(find . -path ./build\* -prune -o \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' \) -print |
                         sed 's|^\./||' | sort)
fi
if [ "${1:-}" = --fix ]; then
    "$cf" -i --style=file "${files[@]}"
    exit 0
fi
bad=0
for f in "${files[@]}"; do
    [ -f "$f" ] || continue
    n=$("$cf" --style=file "$f" | diff "$f" - | grep -c '^<' || true)
    if [ "$n" -gt 0 ]; then
        echo "$f: $n line(s) differ from .clang-format"
        bad=$((bad + 1))
    fi
done
if [ "$bad" -gt 0 ]; then
    echo "check_format: $bad of ${#files[@]} files differ; scripts/check_format.sh --fix reformats them"
    exit 1
fi
echo "check_format: ${#files[@]} files conform to .clang-format"
