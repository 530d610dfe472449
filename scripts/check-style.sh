#!/usr/bin/env bash
# Style checks of mo2d (issue 11, item 6). Three stages; every one runs, the exit status is 1 if
# any found something:
#   1. format: clang-format --dry-run -Werror on every tracked *.cpp / *.hpp (.clang-format);
#   2. sizes:  no file in src/ over 500 lines (counted here), no function in src/ over 150 lines
#              (clang-tidy's readability-function-size, LineThreshold 150 in .clang-tidy: it counts
#              the lines of the body from the AST, so braces in strings, macros and lambdas cannot
#              fool it; a lambda counts as part of its enclosing function);
#   3. tidy:   clang-tidy (.clang-tidy: bugprone-*, performance-*, cognitive complexity <= 50) over
#              the translation units of src/ and the src/ and include/ headers they include, with
#              the compile commands of a configured build, in parallel: on its unity batches where
#              it has them (then every batched file is also compiled alone, syntax only, so that a
#              file that does not include what it uses is found). Warnings found in a header are
#              counted once, not once per translation unit.
# A summary of the findings per check and per file ends the output.
#
#   scripts/check-style.sh [build-dir]     (default build/: cmake --preset release writes
#                                           compile_commands.json there)
# Environment: MO2D_STYLE_JOBS (parallel clang-tidy processes, default nproc),
#              MO2D_STYLE_DIRS (folders of translation units for clang-tidy, default "src").
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
root=$PWD
build=${1:-build}
jobs=${MO2D_STYLE_JOBS:-$(nproc 2>/dev/null || echo 2)}
read -r -a dirs <<<"${MO2D_STYLE_DIRS:-src}"
max_file_lines=500
start=$SECONDS
failed=()

for tool in clang-format clang-tidy; do
  command -v "$tool" >/dev/null || { echo "check-style: $tool not found (scripts/install-deps.sh)" >&2; exit 2; }
done

# ---- 1. format ------------------------------------------------------------------------------------
echo "== style 1/3: clang-format ($(clang-format --version | grep -o 'version [0-9.]*'))"
mapfile -t sources < <(git ls-files '*.cpp' '*.hpp')
format_log=$(mktemp)
tidy_dir=$(mktemp -d)
trap 'rm -rf "$format_log" "$tidy_dir"' EXIT
clang-format --dry-run -Werror "${sources[@]}" >"$format_log" 2>&1
mapfile -t unformatted < <(grep -o '^[^:]*:[0-9]*:[0-9]*: error' "$format_log" | cut -d: -f1 | sort -u)
if ((${#unformatted[@]})); then
  for f in "${unformatted[@]}"; do
    echo "  $f: $(grep -c "^$f:[0-9]*:[0-9]*: error" "$format_log") places to reformat (clang-format -i $f)"
  done
  failed+=("format: ${#unformatted[@]} of ${#sources[@]} files")
else
  echo "  ${#sources[@]} files formatted"
fi

# ---- 2. sizes (files; functions are counted by clang-tidy in stage 3) ------------------------------
echo "== style 2/3: sizes (files in src/ <= ${max_file_lines} lines; functions <= 150 lines, stage 3)"
large=0
while read -r lines file; do
  [[ "$file" == total ]] && continue
  if ((lines > max_file_lines)); then
    echo "  $file: $lines lines (limit $max_file_lines)"
    large=$((large + 1))
  fi
done < <(git ls-files 'src/*.cpp' 'src/*.hpp' | xargs wc -l)
((large)) && failed+=("sizes: $large files in src/ over $max_file_lines lines")

# ---- 3. clang-tidy --------------------------------------------------------------------------------
echo "== style 3/3: clang-tidy ($(clang-tidy --version | grep -o 'version [0-9.]*'), ${dirs[*]}, $jobs jobs)"
if [[ ! -f "$build/compile_commands.json" ]]; then
  echo "check-style: $build/compile_commands.json not found: configure first (cmake --preset release)" >&2
  exit 2
fi
mapfile -t units < <(git ls-files "${dirs[@]/%//*.cpp}")
# A unity build (the release preset) compiles its sources in batches (Unity/unity_N_cxx.cxx, each
# including up to 16 of them): clang-tidy on a batch parses the shared headers once for all its
# files (6-10 s of CPU per file otherwise). A batch is checked whole when every file it includes is
# one of the units; the other units (a file-by-file build, SKIP_UNITY_BUILD_INCLUSION) one by one.
alone="$tidy_dir/alone.commands"
mapfile -t inputs < <(python3 - "$build/compile_commands.json" "$root" "$alone" "${units[@]}" <<'PY'
import json, re, sys
commands, root, alone, units = sys.argv[1], sys.argv[2], sys.argv[3], set(sys.argv[4:])
covered, batches = set(), []
for entry in json.load(open(commands)):
    if not re.search(r"/Unity/unity_[0-9]+_cxx\.cxx$", entry["file"]):
        continue
    text = open(entry["file"]).read()
    files = [f[len(root) + 1:] if f.startswith(root + "/") else f
             for f in re.findall(r'^#include "([^"]+)"', text, re.M)]
    if files and all(f in units for f in files):
        batches.append(entry["file"])
        covered.update(files)
        # each file of the batch compiled alone, with the batch's flags (syntax only)
        command = entry["command"].replace(entry["file"], "{}")
        command = re.sub(r" -o \S+", "", command).replace(" -c ", " -fsyntax-only -w ")
        with open(alone, "a") as out:
            for f in files:
                out.write("cd %s && %s\n" % (entry["directory"], command.replace("{}", root + "/" + f)))
print("\n".join(batches + sorted(units - covered)))
PY
)
tidy_start=$SECONDS
# one log per input; --quiet drops the "N warnings generated" lines
printf '%s\n' "${inputs[@]}" | xargs -P "$jobs" -I{} sh -c \
  'clang-tidy --quiet -p "$1" --header-filter="^$2/(src|include|render|view|crosscheck|apps)/" "$3" >"$4/$(echo "$3" | tr / _).log" 2>&1' \
  _ "$build" "$root" {} "$tidy_dir"
# a batch's #include of its .cpp files is what bugprone-suspicious-include reports: not a finding
sed -i -E '/\/Unity\/unity_[0-9]+_cxx\.cxx:[0-9]+:[0-9]+: warning: .*\[bugprone-suspicious-include\]$/d' "$tidy_dir"/*.log
# findings: "file:line:col: warning: text [check]", relative to the root and counted once (a
# header's are repeated by every unit that includes it); a long function gets its line count
# from the note that follows its warning
findings=$(cat "$tidy_dir"/*.log | awk -v root="$root/" '
  function rel(s) { return index(s, root) == 1 ? substr(s, length(root) + 1) : s }
  /^\/.*:[0-9]+:[0-9]+: (warning|error): .*\[[a-z][a-z0-9.,-]*\]$/ {
    if (pending != "") print pending
    pending = ""
    if ($0 ~ /\[readability-function-size\]$/) pending = rel($0); else print rel($0)
    next
  }
  pending != "" && /: note: [0-9]+ lines including/ {
    n = $0; sub(/.*: note: /, "", n); print pending " " n; pending = ""
  }
  END { if (pending != "") print pending }' | sort -u)
if grep -q -E '^(Error|error):' "$tidy_dir"/*.log; then
  grep -h -E '^(Error|error):' "$tidy_dir"/*.log | sort -u | sed 's/^/  /'
  failed+=("tidy: clang-tidy could not process some files")
fi
echo "  ${#units[@]} translation units (${#inputs[@]} clang-tidy runs) in $((SECONDS - tidy_start)) s"
# In a batch a file sees what the files before it included: what a file-by-file build (a plain
# `cmake -B dir`, no preset) would find missing is found by compiling each batched file alone
# (clang++ -fsyntax-only -w, the batch's flags: a quarter of clang-tidy's time per file).
if [[ -s "$alone" ]]; then
  alone_start=$SECONDS
  sed -i 's|^\(cd [^&]*&& \)[^ ]*|\1clang++|' "$alone"
  tr '\n' '\0' <"$alone" | xargs -0 -P "$jobs" -n 1 sh -c \
    'eval "$1" >>"$0/alone.log" 2>&1 || echo "$1" >>"$0/alone.failed"' "$tidy_dir"
  if [[ -s "$tidy_dir/alone.failed" ]]; then
    grep -E ': (fatal )?error:' "$tidy_dir/alone.log" | sort -u | head -20 | sed 's/^/  /'
    failed+=("includes: $(wc -l <"$tidy_dir/alone.failed") files do not compile alone")
  fi
  echo "  $(wc -l <"$alone") batched files compiled alone (includes) in $((SECONDS - alone_start)) s"
fi
if [[ -n "$findings" ]]; then
  echo "$findings" | sed 's/^/  /'
  count=$(echo "$findings" | wc -l)
  failed+=("tidy: $count findings")
  echo "  -- per check"
  echo "$findings" | sed -E 's/.*\[([a-z][a-z0-9.,-]*)\]( .*)?$/\1/' | sort | uniq -c | sort -rn | sed 's/^/  /'
  echo "  -- per file"
  echo "$findings" | cut -d: -f1 | sort | uniq -c | sort -rn | sed 's/^/  /'
else
  echo "  no findings"
fi

echo "== style: $((SECONDS - start)) s"
if ((${#failed[@]})); then
  printf 'check-style: %s\n' "${failed[@]}"
  exit 1
fi
echo "check-style: clean"
