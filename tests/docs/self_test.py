#!/usr/bin/env python3
"""The docs test on documents made for it: an unmarked example that needs hardware fails with its
file and line; marked, it is listed as skipped with its reason; reduced, it runs the reduced form."""
import os
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent


def run(build, readme, docs=None, setup=None, ci=False):
    with tempfile.TemporaryDirectory() as tmp:
        src = Path(tmp) / "src"
        (src / "docs").mkdir(parents=True)
        (src / "data").mkdir()
        (src / "README.md").write_text(readme)
        for name, text in (docs or {}).items():
            (src / "docs" / name).write_text(text)
        if setup is not None:  # the repository's scripts/install-deps.sh
            (src / "scripts").mkdir()
            (src / "scripts" / "install-deps.sh").write_text(setup)
        env = {k: v for k, v in os.environ.items() if k != "CI"}
        if ci:
            env["CI"] = "true"
        p = subprocess.run([sys.executable, str(HERE / "run_examples.py"), "--source", str(src), "--build", build,
                            "--work", str(Path(tmp) / "work"), "--no-checks"], capture_output=True, text=True, env=env)
        return p.returncode, p.stdout + p.stderr


def main():
    build = sys.argv[1]
    failures = []

    def expect(cond, what, out):
        if not cond:
            failures.append(f"{what}:\n{out}")

    hardware = "# Title\n\nText.\n\n```sh\nbuild/app/keyturn grab --camera sim --out a.pcd\n" \
               "build/app/keyturn grab --camera usb --out b.pcd\n```\n"
    rc, out = run(build, hardware)
    expect(rc == 1 and "README.md:7: example exited 1" in out and "libMesaSR" in out,
           "an unmarked hardware example fails with its file and line", out)

    marked = hardware.replace("```sh", '<!-- docs-test: skip "--camera usb" needs an SR4000 -->\n```sh')
    rc, out = run(build, marked)
    expect(rc == 0 and "skipped (needs an SR4000): build/app/keyturn grab --camera usb" in out,
           "a marked one is skipped with its reason", out)

    reduced = "<!-- docs-test: reduced \"--frames 50\" \"--frames 2\" 2 frames -->\n```sh\n" \
              "build/app/keyturn grab --frames 50 --out a.pcd\ntest -s a_confidence.png\n```\n"
    rc, out = run(build, reduced, {"new.md": "```bash\nbuild/app/keyturn devices --json > d.json\n```\n"})
    expect(rc == 0 and "reduced (2 frames): build/app/keyturn grab --frames 2" in out and "docs/new.md:1: ok" in out,
           "a reduced one runs reduced; a new document is picked up", out)

    rc, out = run(build, '<!-- docs-test: reduced "--nothing" "x" no such text -->\n```sh\nls\n```\n')
    expect(rc != 0 and "matches no command" in out, "a directive that matches nothing is an error", out)

    rc, out = run(build, "```\nbuild/app/keyturn devices\n```\n")
    expect(rc == 1 and "without a language" in out, "an unlabelled block of commands is an error", out)

    needs = ("<!-- docs-test: needs no_such_module_kt optional -->\n```sh\nexit 3\n```\n"
             "<!-- docs-test: needs json standard library -->\n```sh\ntouch ran\ntest -e ran\n```\n")
    rc, out = run(build, needs)
    expect(rc == 0 and "skipped (no Python module no_such_module_kt: optional)" in out and "README.md:6: ok" in out,
           "a block that needs an absent Python module is skipped, one whose module is there runs", out)

    setup = "packages=(\n  python3-no_such_module_kt\n)\n"
    rc, out = run(build, needs, setup=setup, ci=True)
    expect(rc == 1 and "README.md:2: needs Python module no_such_module_kt, which scripts/install-deps.sh installs" in out,
           "under CI=true, a block that needs a module the set-up installs fails when it cannot be imported", out)
    rc, out = run(build, needs, setup=setup)
    expect(rc == 0 and "skipped (no Python module no_such_module_kt: optional)" in out,
           "outside CI the same block is skipped with its reason", out)
    rc, out = run(build, needs, setup="packages=(\n  python3-no_such_module_kt_other\n)\n", ci=True)
    expect(rc == 0 and "skipped (no Python module no_such_module_kt: optional)" in out,
           "under CI=true a module the set-up does not install is still skipped", out)

    output = ("<!-- docs-test: setup echo set-up -->\n```sh\nprintf 'a\\nb\\nc\\nd\\n'\necho to-stderr >&2\n```\n\n"
              "<!-- docs-test: output -->\n```text\na\n…\nd\n```\n")
    rc, out = run(build, output)
    expect(rc == 0 and "README.md:8: output as quoted" in out,
           "an output block is the block's standard output (its set-up's and standard error aside; … any lines)", out)
    rc, out = run(build, output.replace("a\n…\nd\n```", "a\nB\nc\nd\n```"))
    expect(rc == 1 and "README.md:8: the output quoted is not what the block above printed: line 2" in out,
           "an output block that is not what the block printed fails, naming the line", out)

    for f in failures:
        print("FAILED:", f)
    print(f"{11 - len(failures)} passed, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
