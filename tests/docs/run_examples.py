#!/usr/bin/env python3
"""The docs test: every shell example in README.md and docs/*.md, run as a user would.

Each document gets a work folder of its own (with `build`, `data` and `tests` linking to the build and
the repository's data and tests, and the build's app/ and then this test's python3 on PATH); its ```sh blocks run there in order, each as one
bash script under `set -e`. A block that cannot run here says so in an HTML comment on the lines
just above it, and the test lists it with its reason:

  <!-- docs-test: skip REASON -->                  the whole block is not run
  <!-- docs-test: skip "TEXT" REASON -->           the block's commands containing TEXT are not run
  <!-- docs-test: reduced "FROM" "TO" REASON -->   run with FROM replaced by TO (e.g. fewer views)
  <!-- docs-test: setup COMMAND -->                run COMMAND first (the state the example assumes)
  <!-- docs-test: display -->                      run under Xvfb (1600 × 1000)
  <!-- docs-test: env NAME=VALUE -->               set for the block
  <!-- docs-test: file NAME -->                    (before any block) write the block's text to NAME
  <!-- docs-test: needs MODULE REASON -->          run only when python3 imports MODULE (an optional package;
                                                   under CI=true a module scripts/install-deps.sh installs as
                                                   python3-MODULE must be there: its absence fails)
  <!-- docs-test: output -->                       (above a ```text block) what the shell block above it prints
                                                   on standard output, compared line by line; a line "…" stands
                                                   for any lines (output left out)

An unmarked example that fails (one that needs hardware, say) fails the test with its file and line.
Then the figures the docs quote that a program can confirm (defaults, column names, JSON keys,
counts, sizes) are checked against the program: see checks.py.
"""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import checks  # noqa: E402

SHELL_LANGS = {"sh", "bash", "shell", "console"}
DIRECTIVE = re.compile(r"^\s*<!--\s*docs-test:\s*(.*?)\s*-->\s*$")
COMMAND_LIKE = re.compile(r"^\s*(\$ |build/app/\S|keyturn(-studio)? (-|[a-z][a-z-]* )|bash scripts/|xvfb-run )")


class Block:
    def __init__(self, doc, line, lang, text, directives):
        self.doc, self.line, self.lang, self.text, self.directives = doc, line, lang, text, directives

    @property
    def where(self):
        return f"{self.doc}:{self.line}"


def parse_quoted(rest):
    """'"A" "B" reason' -> (["A", "B"], "reason"); quotes may not nest."""
    parts = []
    rest = rest.strip()
    while rest.startswith('"'):
        end = rest.find('"', 1)
        if end < 0:
            raise ValueError("unclosed quote")
        parts.append(rest[1:end])
        rest = rest[end + 1:].strip()
    return parts, rest


def read_blocks(root, rel):
    """Fenced blocks of one Markdown file, with the docs-test directives just above each."""
    lines = (root / rel).read_text(encoding="utf-8").splitlines()
    blocks, pending, i = [], [], 0
    while i < len(lines):
        m = DIRECTIVE.match(lines[i])
        if m:
            pending.append((i + 1, m.group(1)))
            i += 1
            continue
        fence = re.match(r"^(\s*)(```+|~~~+)\s*([\w+-]*)", lines[i])
        if not fence:
            if lines[i].strip():
                pending = []  # a directive belongs to the block right below it
            i += 1
            continue
        marker, lang, start = fence.group(2), fence.group(3).lower(), i + 1
        body = []
        i += 1
        while i < len(lines) and not lines[i].lstrip().startswith(marker):
            body.append((i + 1, lines[i]))
            i += 1
        i += 1
        blocks.append(Block(rel, start, lang, body, pending))
        pending = []
    return blocks


def commands_of(block):
    """Logical command lines (continuations joined) as (line number, text)."""
    out, cur, cur_line = [], "", None
    for n, text in block.text:
        if cur_line is None:
            if not text.strip() or text.lstrip().startswith("#"):
                continue
            cur_line = n
        if text.rstrip().endswith("\\"):
            cur += text.rstrip()[:-1] + " "
            continue
        out.append((cur_line, cur + text))
        cur, cur_line = "", None
    if cur_line is not None:
        out.append((cur_line, cur))
    return out


class Plan:
    """What the directives make of a block: the script to run and what was left out or reduced."""

    def __init__(self, block):
        self.block, self.skip_reason, self.notes = block, None, []
        self.setup, self.env, self.display, self.file = [], {}, False, None
        self.skips, self.subs, self.needs = [], [], []
        self.output = False
        for line, d in block.directives:
            word, _, rest = d.partition(" ")
            try:
                if word == "skip":
                    quoted, reason = parse_quoted(rest)
                    if not reason:
                        raise ValueError("a skip needs its reason")
                    if quoted:
                        self.skips.append((quoted[0], reason))
                    else:
                        self.skip_reason = reason
                elif word == "reduced":
                    quoted, reason = parse_quoted(rest)
                    if len(quoted) != 2 or not reason:
                        raise ValueError('expected reduced "FROM" "TO" REASON')
                    self.subs.append((quoted[0], quoted[1], reason))
                elif word == "setup":
                    self.setup.append(rest)
                elif word == "env":
                    name, _, value = rest.partition("=")
                    self.env[name.strip()] = value.strip()
                elif word == "needs":
                    module, _, reason = rest.partition(" ")
                    if not module or not reason.strip():
                        raise ValueError("expected needs MODULE REASON")
                    self.needs.append((module, reason.strip()))
                elif word == "display":
                    self.display = True
                elif word == "file":
                    self.file = rest.strip()
                elif word == "output":
                    self.output = True
                else:
                    raise ValueError(f"unknown directive '{word}'")
            except ValueError as e:
                raise SystemExit(f"{block.doc}:{line}: docs-test directive: {e}")

    def script(self):
        """bash script of the block's commands, each announcing its line for the failure report."""
        used_subs, used_skips, body = set(), set(), []
        for n, cmd in commands_of(self.block):
            skipped = [s for s in self.skips if s[0] in cmd]
            if skipped:
                used_skips.add(skipped[0][0])
                self.notes.append(f"{self.block.doc}:{n}: skipped ({skipped[0][1]}): {cmd.strip()}")
                continue
            for old, new, reason in self.subs:
                if old in cmd:
                    used_subs.add(old)
                    cmd = cmd.replace(old, new)
                    self.notes.append(f"{self.block.doc}:{n}: reduced ({reason}): {cmd.strip()}")
            body.append(f"__docs_line={n}\n{cmd}")
        for old, _, _ in self.subs:
            if old not in used_subs:
                raise SystemExit(f"{self.block.where}: docs-test: reduced \"{old}\" matches no command of the block")
        for text, _ in self.skips:
            if text not in used_skips:
                raise SystemExit(f"{self.block.where}: docs-test: skip \"{text}\" matches no command of the block")
        head = ["set -eo pipefail", "trap 'echo \"$__docs_line\" > .docs-test-line' ERR", "__docs_line=0"]
        head += [f"__docs_line={self.block.line}\n{{ {c}\n}} >&2" for c in self.setup]  # its output is not the block's
        self.notes += [f"{self.block.where}: set up first: {c}" for c in self.setup]
        return "\n".join(head + body) + "\n"


def run_script(script, cwd, env, display, timeout):
    """(exit code, standard output, standard error, failing line or None); a script over its time is killed
    with its children."""
    (cwd / ".docs-test-line").unlink(missing_ok=True)
    argv = ["bash", "-c", script]
    if display:
        argv = ["xvfb-run", "-a", "-s", "-screen 0 1600x1000x24"] + argv
    p = subprocess.Popen(argv, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         start_new_session=True)
    try:
        out, err = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, err = p.communicate()
        return None, out.decode(errors="replace"), err.decode(errors="replace"), None
    marker = cwd / ".docs-test-line"
    line = marker.read_text().strip() if marker.exists() else None
    return p.returncode, out.decode(errors="replace"), err.decode(errors="replace"), line


def output_differs(quoted, printed):
    """None when the printed text is the quoted one (trailing blanks aside; a quoted line "…" stands for any
    lines), else the first line that differs, in words."""
    want = [l.rstrip() for l in quoted]
    got = printed.rstrip("\n").split("\n") if printed.strip() else []
    got = [l.rstrip() for l in got]
    pattern = "".join("(?:.*\n)*?" if l.strip() == "…" else re.escape(l) + "\n" for l in want)
    if re.fullmatch(pattern, "".join(l + "\n" for l in got)):
        return None
    for i, (w, g) in enumerate(zip(want, got)):
        if w.strip() == "…":
            break
        if w != g:
            return f"line {i + 1}: the docs say\n      {w}\n    it printed\n      {g}"
    return f"the docs quote {len(want)} lines, it printed {len(got)}:\n" + "\n".join("      " + l for l in got[-12:])


def python_has(module):
    return subprocess.run([sys.executable, "-c", f"import {module}"], capture_output=True).returncode == 0


def installed_by_setup(source, module):
    """Whether scripts/install-deps.sh installs MODULE's Debian package (python3-MODULE): CI has it then,
    and a block that needs it may not be skipped there."""
    setup = source / "scripts" / "install-deps.sh"
    text = setup.read_text(encoding="utf-8") if setup.exists() else ""
    return re.search(rf"(?<![\w-])python3-{re.escape(module)}(?![\w-])", text) is not None


def prepare_work(work, source, build, rel):
    folder = work / re.sub(r"[^\w.-]", "_", rel)
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    (folder / "build").symlink_to(build)
    (folder / "data").symlink_to(source / "data")
    (folder / "tests").symlink_to(source / "tests")  # the real-data fixtures docs/results.md evaluates
    (folder / "scripts").symlink_to(source / "scripts")  # the scripts the docs run (e.g. real-surface-repeatability.py)
    (folder / "home").mkdir()
    return folder


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--source", required=True, type=Path, help="repository root")
    ap.add_argument("--build", required=True, type=Path, help="build folder (with app/keyturn)")
    ap.add_argument("--work", required=True, type=Path, help="scratch folder (emptied)")
    ap.add_argument("--only", action="append", help="run only these documents (e.g. README.md)")
    ap.add_argument("--timeout", type=float, default=600, help="seconds per block")
    ap.add_argument("--no-checks", action="store_true", help="examples only")
    args = ap.parse_args()
    source, build, work = args.source.resolve(), args.build.resolve(), args.work.resolve()
    if not (build / "app" / "keyturn").exists():
        sys.exit(f"{build}: no app/keyturn (build first)")
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)

    docs = ["README.md"] + sorted(str(p.relative_to(source)) for p in (source / "docs").glob("*.md"))
    if args.only:
        docs = [d for d in docs if d in args.only]
    failures, notes, ran, folders = [], [], 0, {}
    started = time.monotonic()
    for rel in docs:
        folder = prepare_work(work, source, build, rel)
        folders[rel] = folder
        # python3 in the examples is the one this test runs with (CMake's: the one the module is built for).
        path = f"{build / 'app'}:{Path(sys.executable).parent}:{os.environ.get('PATH', '')}"
        env = dict(os.environ, PATH=path, HOME=str(folder / "home"),
                   LC_ALL="C.UTF-8")
        env.pop("DISPLAY", None)  # a block that needs a display says so (display), and gets Xvfb
        printed = None  # the standard output of this document's last shell block, when it ran as written
        for block in read_blocks(source, rel):
            plan = Plan(block)
            if plan.file:
                (folder / plan.file).write_text("\n".join(t for _, t in block.text) + "\n")
                notes.append(f"{block.where}: written to {plan.file}")
                continue
            if plan.output:
                if block.lang in SHELL_LANGS:
                    failures.append(f"{block.where}: an output block is marked ```{block.lang}: mark it ```text")
                elif printed is None:
                    notes.append(f"{block.where}: output not compared (the shell block above did not run as written)")
                else:
                    differs = output_differs([t for _, t in block.text], printed)
                    print(f"{block.where}: output {'as quoted' if differs is None else 'DIFFERS'}", flush=True)
                    if differs:
                        failures.append(f"{block.where}: the output quoted is not what the block above printed: "
                                        f"{differs}")
                printed = None
                continue
            if block.lang not in SHELL_LANGS:
                if not block.lang and any(COMMAND_LIKE.match(t) for _, t in block.text):
                    failures.append(f"{block.where}: a block of commands without a language: mark it ```sh")
                continue
            printed = None
            if plan.skip_reason:
                notes.append(f"{block.where}: skipped ({plan.skip_reason})")
                continue
            absent = [(m, r) for m, r in plan.needs if not python_has(m)]
            if absent:
                set_up = [m for m, _ in absent if installed_by_setup(source, m)]
                if os.environ.get("CI") == "true" and set_up:
                    failures.append(f"{block.where}: needs Python module {set_up[0]}, which scripts/install-deps.sh "
                                    f"installs (python3-{set_up[0]}), and {sys.executable} cannot import it")
                    continue
                notes.append(f"{block.where}: skipped (no Python module {absent[0][0]}: {absent[0][1]})")
                continue
            script = plan.script()
            notes.extend(plan.notes)
            t0 = time.monotonic()
            rc, out, err, line = run_script(script, folder, dict(env, **plan.env), plan.display, args.timeout)
            if rc == 0 and not plan.skips and not plan.subs:
                printed = out
            ran += 1
            took = time.monotonic() - t0
            print(f"{block.where}: {'ok' if rc == 0 else 'FAILED'} in {took:.1f} s", flush=True)
            if rc != 0:
                what = f"timed out after {args.timeout:.0f} s" if rc is None else f"exited {rc}"
                at = f"{rel}:{line}" if line and line != "0" else block.where
                tail = "\n".join("    " + l for l in (out.strip() + "\n" + err.strip()).strip().splitlines()[-12:])
                failures.append(f"{at}: example {what} (mark it in the docs if it needs hardware or takes "
                                f"minutes):\n{tail}")
    print(f"\n{ran} example blocks run in {time.monotonic() - started:.0f} s; left out or reduced:")
    for n in notes:
        print("  " + n)
    if not args.no_checks and not args.only:
        results = checks.run_all(source, build, folders)
        for ok, text in results:
            print(("  ok    " if ok else "  FAIL  ") + text)
        failures += [t for ok, t in results if not ok]
    if failures:
        print(f"\n{len(failures)} failure(s):")
        for f in failures:
            print(f)
        return 1
    print("\ndocs and program agree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
