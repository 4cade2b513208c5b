#!/usr/bin/env python3
"""The Python user's path of docs/python.md, end to end: a fresh venv (Debian's python3, system
site-packages), `pip install --no-build-isolation` of the repository (offline: --no-index), then
`import keyturn` from another folder, the walkthrough section's blocks run as written (its sh blocks
with the venv's python3 and the build's CLI on PATH) and mypy --strict on the typed walkthrough.

Run by ctest (tests/CMakeLists.txt): KEYTURN_SOURCE the repository, KEYTURN_BUILD the build folder
pip builds the package in (reused: its extension is already built, so the install only packages
it), KEYTURN_WORK a scratch folder. Exits 77 (skipped) when mypy, Open3D or matplotlib is missing,
and fails then under CI=true."""
import os
import re
import subprocess
import sys
import time
from pathlib import Path

SOURCE = Path(os.environ["KEYTURN_SOURCE"]).resolve()
BUILD = Path(os.environ["KEYTURN_BUILD"]).resolve()
WORK = Path(os.environ["KEYTURN_WORK"]).resolve()
SECTION = "## Walkthrough"


def run(cmd, **kw):
    print("+", " ".join(map(str, cmd)), flush=True)
    return subprocess.run([str(c) for c in cmd], check=True, **kw)


def walkthrough_blocks():
    """The section's fenced blocks in order: (file name or None, language, text)."""
    text = (SOURCE / "docs/python.md").read_text()
    start = text.index(SECTION)
    end = text.find("\n## ", start + len(SECTION))
    section = text[start:end if end >= 0 else len(text)]
    blocks = []
    for m in re.finditer(r"((?:<!--[^\n]*-->\n)*)```(\w*)\n(.*?)```", section, re.S):
        marks, lang, body = m.groups()
        file = re.search(r"docs-test: file (\S+)", marks)
        blocks.append((file.group(1) if file else None, lang, body))
    return blocks


def main():
    missing = [m for m in ("mypy", "open3d", "matplotlib")
               if subprocess.run([sys.executable, "-c", f"import {m}"], capture_output=True).returncode]
    if missing:
        print(f"walkthrough: Python modules missing: {', '.join(missing)} (scripts/install-deps.sh installs them)")
        return 1 if os.environ.get("CI") == "true" else 77

    subprocess.run(["rm", "-rf", str(WORK)], check=True)
    run_dir = WORK / "run"
    run_dir.mkdir(parents=True)
    venv = WORK / "venv"
    run([sys.executable, "-m", "venv", "--system-site-packages", venv])
    t0 = time.monotonic()
    run([venv / "bin/python", "-m", "pip", "install", "--no-build-isolation", "--no-index", "-q",
         "--config-settings", f"build-dir={BUILD}", SOURCE])
    print(f"walkthrough: pip install took {time.monotonic() - t0:.1f} s", flush=True)

    # Installed with pip's metadata, found from any folder (not the repository's, not PYTHONPATH).
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PATH"] = f"{venv / 'bin'}:{BUILD / 'app'}:{env.get('PATH', '')}"
    env["MPLBACKEND"] = "Agg"
    show = run([venv / "bin/python", "-m", "pip", "show", "-f", "keyturn"], capture_output=True, text=True, env=env,
               cwd=run_dir).stdout
    for needed in ("Name: keyturn", "keyturn/__init__.pyi", "keyturn/py.typed", "keyturn/_keyturn"):
        if needed not in show:
            print(f"walkthrough: pip show -f keyturn lacks {needed}:\n{show}")
            return 1
    where = run([venv / "bin/python", "-c", "import keyturn; print(keyturn.__file__)"], capture_output=True,
                text=True, env=env, cwd="/").stdout.strip()
    if not where.startswith(str(venv)):
        print(f"walkthrough: import keyturn found {where}, not the venv's package")
        return 1

    # The walkthrough as the docs give it, in a folder with the repository's data and tests.
    for name in ("data", "tests"):
        (run_dir / name).symlink_to(SOURCE / name)
    typed = []
    for file, lang, body in walkthrough_blocks():
        if file:
            (run_dir / file).write_text(body)
            if file.endswith(".py"):
                typed.append(file)
        elif lang == "sh":
            run(["bash", "-euo", "pipefail", "-c", body], env=env, cwd=run_dir)
    if not typed:
        print(f"walkthrough: docs/python.md has no typed example under {SECTION}")
        return 1
    for out in ("walk-simulated.png", "walk-real.png", "walk-keypoints.ply", "walk-model/model.json"):
        if not (run_dir / out).exists() or (run_dir / out).stat().st_size == 0:
            print(f"walkthrough: {out} was not written")
            return 1
    # mypy --strict (pyproject.toml's settings) on the typed example, against the installed stubs.
    run([venv / "bin/python", "-m", "mypy", "--config-file", SOURCE / "pyproject.toml", "--cache-dir",
         WORK / "mypy-cache", *typed], env=env, cwd=run_dir)
    # The stubs do check: wrong uses of the API are refused.
    (run_dir / "misuse.py").write_text(
        "import keyturn\n"
        "d = keyturn.describe('v.pcd', kind='organized')\n"
        "k: str = keyturn.describe('v.pcd').K\n"
        "keyturn.Dataset('ds').features(cache='yes')\n")
    bad = subprocess.run([str(venv / "bin/python"), "-m", "mypy", "--config-file", str(SOURCE / "pyproject.toml"),
                          "--cache-dir", str(WORK / "mypy-cache"), "misuse.py"], env=env, cwd=run_dir,
                         capture_output=True, text=True)
    if bad.returncode == 0 or bad.stdout.count("error:") < 3:
        print(f"walkthrough: mypy let misuse.py through:\n{bad.stdout}")
        return 1
    print("walkthrough: ok")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except subprocess.CalledProcessError as e:
        print(f"walkthrough: {e}")
        sys.exit(1)
