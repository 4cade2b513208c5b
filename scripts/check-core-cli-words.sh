#!/usr/bin/env bash
# Below app/ nothing speaks the CLI's language: fails, listing each one, when a string literal in the
# C/C++ sources under ROOT/core, ROOT/drivers, ROOT/rig or ROOT/simulators (default: this checkout)
# names a command-line flag — "--" followed by a letter ("--shard", "see --explain"). Flags, their
# syntax and every wording that names them belong to app/ (the studio and Python reach the same code
# without them); the libraries' errors name the value and what is wrong, typed where app/ words them
# in its flags (docs/architecture.md). Comments may name flags: only string literals are read (raw
# strings and character literals understood). A literal that is another program's command line
# (udevadm's, for the USB permissions) is not keyturn's flag.
# Usage: scripts/check-core-cli-words.sh [ROOT]
set -euo pipefail
root=${1:-"$(cd "$(dirname "$0")/.." && pwd)"}
[ -d "$root/core" ] || { echo "check-core-cli-words: $root/core: no such folder" >&2; exit 2; }
exec python3 - "$root" <<'PY'
import pathlib, re, sys

root = pathlib.Path(sys.argv[1])
FLAG = re.compile(r"--[A-Za-z]")
SOURCES = {".c", ".cc", ".cpp", ".cxx", ".h", ".hh", ".hpp", ".hxx", ".inl"}


def literals(text):
    """Yields (line, literal) for every string literal of C/C++ source text, skipping comments."""
    i, n, line = 0, len(text), 1
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif text.startswith("//", i):
            i = text.find("\n", i)
            i = n if i < 0 else i
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            line += text.count("\n", i, end)
            i = end
        elif c == "'" and not (i > 0 and (text[i - 1].isalnum() or text[i - 1] == "_")):  # not 1'000 digit separators
            j = i + 1
            while j < n and text[j] not in "'\n":
                j += 2 if text[j] == "\\" else 1
            i = j + 1
        elif c == '"':
            raw = re.search(r"(?:u8|[uUL])?R$", text[max(0, i - 3):i])
            if raw:
                m = re.match(r'"([^()\\\s]{0,16})\(', text[i:])
                close = ")" + (m.group(1) if m else "") + '"'
                start = i + (m.end() if m else 1)
                end = text.find(close, start)
                end = n if end < 0 else end
                yield line, text[start:end]
                line += text.count("\n", i, end)
                i = end + len(close)
            else:
                j = i + 1
                while j < n and text[j] not in '"\n':
                    j += 2 if text[j] == "\\" else 1
                yield line, text[i + 1:j]
                i = j + 1
        else:
            i += 1


hits = []
OTHER_PROGRAM = re.compile(r"\budevadm\b")
FOLDERS = [f for f in ("core", "drivers", "rig", "simulators") if (root / f).is_dir()]
paths = sorted(p for f in FOLDERS for p in (root / f).rglob("*"))
for path in paths:
    if path.suffix in SOURCES and path.is_file():
        text = path.read_text(encoding="utf-8", errors="replace")
        for line, s in literals(text):
            if FLAG.search(s) and not OTHER_PROGRAM.search(s):
                shown = s.replace("\n", "\\n")  # one line per literal, raw strings too
                hits.append(f"{path.relative_to(root)}:{line}: \"{shown}\"")
if hits:
    print(f"check-core-cli-words: {len(hits)} string literal(s) under {', '.join(f + '/' for f in FOLDERS)} name a command-line flag "
          "(the CLI's wording belongs to app/):", file=sys.stderr)
    print("\n".join(hits), file=sys.stderr)
    sys.exit(1)
print(f"check-core-cli-words: no string literal under {', '.join(f + '/' for f in FOLDERS)} names a command-line flag")
PY
