"""Figures the docs quote, checked against the program (part of the docs test, run_examples.py).

Each check finds its figure in the docs by a pattern; a figure that is no longer where the check looks
fails too (with the pattern), so a reworded sentence is looked at again rather than silently unchecked.
Examples' outputs are read from the documents' work folders (the examples ran just before).
"""
import json
import re
import subprocess
from pathlib import Path


class Context:
    def __init__(self, source, build, folders):
        self.source, self.build, self.folders = source, build, folders
        self.results, self._help = [], {}

    def doc(self, rel):
        return (self.source / rel).read_text(encoding="utf-8")

    def find(self, rel, pattern, flags=re.S):
        """The first match of pattern in the document, or None (and a failure naming the pattern)."""
        m = re.search(pattern, self.doc(rel), flags)
        if not m:
            self.fail(f"{rel}: the docs test looks for /{pattern}/ and does not find it (update tests/docs/checks.py "
                      f"with the docs)")
        return m

    def ok(self, text):
        self.results.append((True, text))

    def fail(self, text):
        self.results.append((False, text))

    def expect(self, cond, text):
        self.results.append((bool(cond), text))

    def run(self, *args, cwd=None, timeout=300):
        p = subprocess.run([str(a) for a in args], cwd=cwd, capture_output=True, text=True, timeout=timeout)
        if p.returncode != 0:
            raise RuntimeError(f"{' '.join(map(str, args))} exited {p.returncode}: {p.stderr.strip()[-400:]}")
        return p.stdout

    def keyturn(self, *args, **kw):
        return self.run(self.build / "app" / "keyturn", *args, **kw)

    def default(self, command, option):
        """The default --help prints for an option (CLI11: `--bins INT:INT in [2 - 4096]=32`)."""
        if command not in self._help:
            exe = self.build / "app" / ("keyturn-studio" if command == "studio" else "keyturn")
            argv = [exe, "--help"] if command == "studio" else [exe] + command.split() + ["--help"]
            self._help[command] = self.run(*argv)
        for line in self._help[command].splitlines():
            m = re.match(r"^\s+(?:-\w,)?" + re.escape(option) + r"(?:,\S+)?\s+\S.*?=(.+?)(?:\s{2,}|$)", line)
            if m:
                return m.group(1)
        return None

    def expect_default(self, rel, quoted, command, option):
        actual = self.default(command, option)
        self.expect(actual == quoted, f"{rel}: {command} {option} default: docs say {quoted}, --help says {actual}")


def header_of_pcd(path):
    head = {}
    with open(path, "rb") as f:
        for raw in f:
            line = raw.decode("ascii", "replace").strip()
            key, _, value = line.partition(" ")
            head[key] = value
            if key == "DATA":
                break
    return head


def check_option_defaults(c):
    for rel, pattern, command, option in [
        ("docs/cli.md", r"`--extent`\s*\(([\d.]+) m\)", "describe", "--extent"),
        ("docs/cli.md", r"`--range (\w+)` \(default\)", "describe", "--range"),
        ("docs/cli.md", r"`low_keypoints`\s*\(1 when K < (\d+)", "describe", "--low-keypoints"),
        ("docs/descriptors.md", r"(\d+) bins by default", "describe", "--bins"),
        ("docs/descriptors.md", r"\(`--seed`, default (\d+)\)", "describe", "--seed"),
        ("docs/studio.md", r"`--threads N` \(recognition threads, default (\d+)\)", "studio", "--threads"),
        ("docs/results.md", r"--classifier ([\w,]+),\s*\n", "evaluate", "--classifier"),
        ("docs/results.md", r"#\s+--protocol ([\w,-]+), (\d+) bins", "evaluate", "--protocol"),
        ("docs/benchmarks.md", r"`keyturn bench --repetitions \d+`, default (\d+) runs", "bench", "--repetitions"),
        ("docs/camera.md", r"\| modulation \| (\d+) MHz", "grab", "--modulation"),
        ("docs/protocols.md", r"\(`--unit`, default (\d+)\)", "sim turntable", "--unit"),
        ("docs/slurm.md", r"`--cpus C` per task \(`--cpus-per-task`, and keyturn's `--jobs`; default (\d+)\)", "slurm",
         "--cpus"),
        ("docs/slurm.md", r"`--mem`\s*\(default (\w+),", "slurm", "--mem"),
    ]:
        m = c.find(rel, pattern)
        if m:
            c.expect_default(rel, m.group(1), command, option)
    # The descriptor's table of defaults, row by row (the tests hold the library to it; switches have none).
    rows = re.findall(r"^\| `\w+` \| `(--[\w-]+)` \| (\S+) \|$", c.doc("docs/descriptors.md"), re.M)
    c.expect(len(rows) >= 20, f"docs/descriptors.md: the table of defaults has {len(rows)} rows")
    for option, quoted in rows:
        if not option.startswith("--no-"):
            c.expect_default("docs/descriptors.md", quoted, "describe", option)
    m = c.find("docs/results.md", r"#\s+--protocol [\w,-]+, (\d+) bins")
    if m:
        c.expect_default("docs/results.md", m.group(1), "evaluate", "--bins")
    m = c.find("docs/results.md", r"defaults: the (\d+) feature sets")
    if m:
        sets = (c.default("evaluate", "--features") or "").strip('"').split()
        c.expect(int(m.group(1)) == len(sets),
                 f"docs/results.md: evaluate's default feature sets: docs say {m.group(1)}, --help lists {len(sets)}")


def check_describe_columns(c, work):
    m = c.find("docs/cli.md", r"- Columns: (.*?)`<feature>_<bin>`")
    csv = work / "features.csv"
    if not m:
        return
    if not csv.exists():
        return c.fail(f"docs/cli.md: {csv.name} was not written by the describe example")
    quoted = re.findall(r"`([^`]+)`", m.group(1))
    names = [n.strip() for q in quoted for n in q.split(",") if re.fullmatch(r"\s*[a-z_]+\s*", n)]
    header = csv.read_text().splitlines()[0].split(",")
    c.expect(header[:len(names)] == names,
             f"docs/cli.md: describe's leading columns: docs say {names}, features.csv has {header[:len(names)]}")
    ex = c.find("docs/cli.md", r"keyturn describe out/demo/dataset --features ([\w,]+)\s*\\\s*\n\s*--bins (\d+)")
    if ex:
        feats, bins = ex.group(1).split(","), int(ex.group(2))
        want = [f"{f}_{b}" for f in feats for b in range(bins)]
        c.expect(header[len(names):] == want,
                 f"docs/cli.md: describe's feature columns are <feature>_<bin> for {feats} × {bins} bins "
                 f"({len(header) - len(names)} columns, {len(want)} expected)")


def check_bench_keys(c):
    """Every key docs/cli.md names for bench --json is there, in the top level and in each view."""
    m = c.find("docs/cli.md", r"JSON keys(.*?)per-stage `stages\.\{…\}\.\{([\w,]+)\}`(.*?)Measured figures")
    if not m:
        return
    listed = [k for k in re.findall(r"`([a-z_]+)`", m.group(1))]
    tail = re.findall(r"`([a-z_]+)`", m.group(3))
    j = json.loads(c.keyturn("bench", "--json", "--repetitions", "1", "--pcl-repetitions", "1"))
    missing = [k for k in listed + ["stages"] + tail[:1] if k not in j]
    c.expect(listed and not missing, f"docs/cli.md: bench --json has the keys the page lists (missing: {missing})")
    stats = m.group(2).split(",")
    stages = j.get("stages", {})
    bad = [s for s, v in stages.items() if sorted(v) != sorted(stats)]
    c.expect(stages and not bad, f"docs/cli.md: every bench stage has {stats} (not: {bad})")
    views = j.get("views", [])
    short = [v.get("name") for v in views if any(k not in v for k in listed)]
    c.expect(views and not short, f"docs/cli.md: each of bench's views has those keys (not: {short})")


def check_render_and_grab(c, work):
    m = c.find("docs/cli.md", r"a simulated SR4000 view \((\d+) × (\d+) organized PCD: ([\w ]+)\)")
    pcd = work / "views" / "mug_000.pcd"
    if m:
        if not pcd.exists():
            c.fail("docs/cli.md: the render example did not write views/mug_000.pcd")
        else:
            h = header_of_pcd(pcd)
            got = (h.get("WIDTH"), h.get("HEIGHT"), h.get("FIELDS"))
            c.expect(got == (m.group(1), m.group(2), m.group(3)),
                     f"docs/cli.md: render writes {m.group(1)} × {m.group(2)} with fields '{m.group(3)}' (got {got})")
    m = c.find("docs/cli.md", r"`\{angle\}` becomes .*?: (`views/mug_\d+\.pcd`(?:,\s*`views/mug_\d+\.pcd`)*)")
    if m:
        names = re.findall(r"`([^`]+)`", m.group(1))
        missing = [n for n in names if not (work / n).exists()]
        c.expect(not missing, f"docs/cli.md: render's {{angle}} file names {names} (missing: {missing})")


def check_dataset_format(c, cli_work):
    rel = "docs/dataset-format.md"
    ds = cli_work / "datasets" / "sim"
    m = c.find(rel, r"## manifest\.csv\s*```\s*\n([^\n]+)\n")
    if m and (ds / "manifest.csv").exists():
        got = (ds / "manifest.csv").read_text().splitlines()[0]
        c.expect(got == m.group(1), f"{rel}: manifest header: docs '{m.group(1)}', capture wrote '{got}'")
    m = c.find(rel, r"dataset\.json\s+\{([^}]*)\}")
    if m and (ds / "dataset.json").exists():
        keys = re.findall(r'"(\w+)"', m.group(1))
        got = sorted(json.loads((ds / "dataset.json").read_text()))
        c.expect(sorted(keys) == got, f"{rel}: dataset.json keys: docs {sorted(keys)}, capture wrote {got}")
    m = c.find(rel, r"## The sidecar.*?\n\| key \| meaning \|\n(.*?)\n\n")
    sidecars = sorted(ds.glob("*/*/*/*.json"))
    if m and sidecars:
        keys = sorted({k for row in m.group(1).splitlines() for k in re.findall(r"`(\w+)`", row.split("|")[1])})
        got = sorted(json.loads(sidecars[0].read_text()))
        c.expect(keys == got, f"{rel}: sidecar keys: docs {keys}, capture wrote {got}")
    m = c.find(rel, r"## Axis calibration file.*?```json\s*\n(.*?)```")
    axis = cli_work / "axis.json"
    if m and axis.exists():
        keys = sorted(re.findall(r'"(\w+)":', m.group(1)))
        got = sorted(json.loads(axis.read_text()))
        c.expect(keys == got, f"{rel}: calibration keys: docs {keys}, calibrate-axis wrote {got}")
    m = c.find(rel, r"## Feature cache.*?```\s*\n.*?\n(id,[\w,]+?),kpd2_0")
    calibrated = cli_work / "datasets" / "calibrated"
    if m and calibrated.exists():
        c.keyturn("describe", calibrated, "--cache", "-q")
        caches = sorted((calibrated / ".keyturn").glob("features-*.csv"))
        lines = [l for l in caches[0].read_text().splitlines() if not l.startswith("#")] if caches else [""]
        c.expect(lines[0].startswith(m.group(1) + ",kpd2_0"),
                 f"{rel}: feature cache columns start '{m.group(1)},kpd2_0' (got '{lines[0][:60]}')")


def check_dataset_size(c, work):
    """The full simulated dataset's size, from a quarter-turn sample of every object and elevation."""
    m = c.find("docs/cli.md", r"--out datasets/sr4kd-sim` \(([\d,]+)\s+views, about ([\d.]+) GB")
    r = c.find("docs/results.md", r"#\s+(\d+) objects × elevations ([\d,]+) × (\d+) views \((\d+)°\) = ([\d,]+) views")
    objects = [l for l in (c.source / "data/objects/objects.csv").read_text().splitlines()[1:] if l.strip()]
    elevations = (c.default("simulate", "--elevations") or "").strip('"').split(",")
    step = float(c.default("simulate", "--step") or "nan")
    total = len(objects) * len(elevations) * round(360 / step)
    if r:
        c.expect((int(r.group(1)), r.group(2), int(r.group(3)), float(r.group(4)), int(r.group(5).replace(",", "")))
                 == (len(objects), ",".join(elevations), round(360 / step), step, total),
                 f"docs/results.md: {r.group(0).strip('# ')} (program: {len(objects)} objects, elevations "
                 f"{','.join(elevations)}, step {step:g}°: {total} views)")
    if not m:
        return
    c.expect(int(m.group(1).replace(",", "")) == total, f"docs/cli.md: the simulated dataset has {total} views "
                                                        f"(docs: {m.group(1)})")
    sample = work / "size-sample"
    c.keyturn("simulate", "--objects", c.source / "data/objects/objects.csv", "--step", "90", "-q",
              "--out", sample, timeout=600)
    rows = len((sample / "manifest.csv").read_text().splitlines()) - 1
    size = sum(p.stat().st_size for p in sample.rglob("*") if p.is_file() and ".sim" not in p.parts)
    estimate = size / rows * total / 1e9
    quoted = float(m.group(2))
    c.expect(abs(estimate - quoted) <= 0.15 * quoted,
             f"docs/cli.md: about {quoted} GB for {total} views; measured {size / rows / 1e3:.0f} kB/view over "
             f"{rows} views → {estimate:.2f} GB")


def check_repeatability_report(c, work):
    m = c.find("docs/cli.md", r"The report folder holds (.*?) and (\w+) PNG charts")
    report = work / "reports" / "rep-lab"
    if not m:
        return
    if not report.exists():
        return c.fail("docs/cli.md: the repeatability example wrote no reports/rep-lab")
    files = re.findall(r"`([\w.]+)`", m.group(1))
    missing = [f for f in files if not (report / f).exists()]
    words = {"one": 1, "two": 2, "three": 3, "four": 4, "five": 5}
    pngs = len(list(report.glob("*.png")))
    c.expect(not missing and pngs == words.get(m.group(2), -1),
             f"docs/cli.md: the repeatability report holds {files} and {m.group(2)} PNGs (missing {missing}, "
             f"{pngs} PNGs)")


def check_studio_model_labels(c):
    model = json.loads((c.source / "data/models/sim-objects/model.json").read_text())
    builtin = "+".join(b.upper() for b in model["blocks"])
    labels = set(re.findall(r"^\| built-in: ([\w+]+) \|", c.doc("docs/benchmarks.md"), re.M))
    c.expect(labels == {builtin}, f"docs/benchmarks.md: rows labelled built-in name the built-in model {builtin} "
                                  f"(labels: {sorted(labels)})")
    m = c.find("docs/benchmarks.md", r"The built-in model is ([\w +]+?) \(")
    if m:
        c.expect(m.group(1).replace(" ", "") == builtin, f"docs/benchmarks.md: 'The built-in model is {m.group(1)}' "
                                                         f"(data/models/sim-objects: {builtin})")


def check_demo_folder(c):
    """docs/cli.md's describe example reads the folder `keyturn demo` and scripts/demo.sh write."""
    script = re.search(r"OUT=\$\{OUT:-([\w/.-]+)\}", (c.source / "scripts/demo.sh").read_text())
    default = c.default("demo", "--out")
    m = c.find("docs/cli.md", r"keyturn describe ([\w/.-]+)/dataset --features")
    if m and script:
        c.expect(default == script.group(1) == m.group(1),
                 f"docs/cli.md: the demo folder: keyturn demo --out default {default}, scripts/demo.sh {script.group(1)}, "
                 f"its describe example {m.group(1)}")


def check_studio_objects(c):
    """docs/studio.md names the object list --object is checked against, and its first object (the default)."""
    rel = "docs/studio.md"
    m = c.find(rel, r"\(`--object`, an instance from\s+`(data/objects/[\w-]+\.csv)`.*?default the first, the \w+ `(\w+)`\)")
    if not m:
        return
    exe = c.build / "app" / "keyturn-studio"
    if not exe.exists():
        return c.ok(f"{rel}: keyturn-studio not built: its object list not checked")
    p = subprocess.run([str(exe), "--simulated", "--object", "no-such-object-kt"], capture_output=True, text=True,
                       timeout=60, env={"PATH": "/usr/bin:/bin", "LC_ALL": "C.UTF-8"})
    named = re.search(r"not in (\S+) \(([\w, ]+)\)", p.stderr)
    c.expect(p.returncode == 1 and named and named.group(1).endswith("/" + m.group(1)),
             f"{rel}: --object is checked against {m.group(1)} (keyturn-studio says: {p.stderr.strip()[:120]})")
    first = (c.source / m.group(1)).read_text().splitlines()[1].split(",")[1]
    c.expect(first == m.group(2) and named and named.group(2).split(", ")[0] == first,
             f"{rel}: --object's default, the list's first, is {m.group(2)} (the list's first: {first})")


def check_stability_one_view(c):
    """docs/descriptors.md quotes how `keyturn stability` refuses a single view; the program does so."""
    rel = "docs/descriptors.md"
    m = c.find(rel, r"one view alone is refused in one line,\s+`([^`]+)` \(exit (\d+)\)")
    if not m:
        return
    p = subprocess.run([str(c.build / "app" / "keyturn"), "stability", str(c.source / "data/frames/mosd_learn0.pcd"),
                        "-q"], capture_output=True, text=True, timeout=120)
    c.expect(p.returncode == int(m.group(2)) and p.stderr.strip() == m.group(1),
             f"{rel}: stability on one file: docs say '{m.group(1)}' (exit {m.group(2)}), it said "
             f"'{p.stderr.strip()}' (exit {p.returncode})")


def check_programs_named(c):
    """The runnable examples of the README, the command-line guide and the Python page name the programs a user
    has after the README's set-up: build/app/keyturn (not on PATH) and Debian's /usr/bin/python3 (a python3
    first on PATH may be another Python, without numpy). The docs test puts both on PATH, so only this sees it."""
    import run_examples  # the same block and command reading as the examples
    bare = {"keyturn", "keyturn-studio", "python3", "python"}
    for rel in ["README.md", "docs/cli.md", "docs/python.md"]:
        if not (c.source / rel).exists():
            continue
        found = []
        for block in run_examples.read_blocks(c.source, rel):
            if block.lang not in run_examples.SHELL_LANGS or run_examples.Plan(block).skip_reason:
                continue
            for n, cmd in run_examples.commands_of(block):
                for part in re.split(r"&&|\|\||[;|()]|\$\(|\b(?:do|then)\b", cmd):
                    words = [w for w in part.split() if not re.match(r"^\w+=", w)]
                    if words and words[0] in bare:
                        found.append(f"{rel}:{n}: {words[0]}")
        c.expect(not found, f"{rel}: runnable examples name build/app/keyturn and /usr/bin/python3 "
                            f"(bare: {', '.join(found) or 'none'})")


def prose_lines(text):
    """The lines of a Markdown text outside fenced blocks."""
    out, fence = [], None
    for line in text.splitlines():
        m = re.match(r"^\s*(```+|~~~+)", line)
        if m and fence is None:
            fence = m.group(1)
        elif m and line.strip().startswith(fence):
            fence = None
        elif fence is None:
            out.append(line)
    return out


def anchors_of(text):
    """GitHub's anchors of a Markdown text's headings (lower case, punctuation dropped, spaces to hyphens,
    -1, -2 … for repeats)."""
    seen, out = {}, set()
    for line in prose_lines(text):
        m = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if not m:
            continue
        title = re.sub(r"\[([^]]*)\]\([^)]*\)", r"\1", m.group(1))
        slug = re.sub(r"[^\w\- ]", "", title.lower()).replace(" ", "-")
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        out.add(slug if n == 0 else f"{slug}-{n}")
    return out


def check_links(c):
    """Every link between the docs resolves: [text](FILE#ANCHOR) and images to files that exist, anchors to
    headings of the file; and the `docs/FILE.md#ANCHOR` the prose cites in code spans."""
    docs = ["README.md"] + sorted(str(p.relative_to(c.source)) for p in (c.source / "docs").glob("*.md"))
    bad, count = [], 0
    for rel in docs:
        here = (c.source / rel).parent
        for n, line in enumerate(prose_lines(c.doc(rel)), 1):
            targets = [(t, here) for t in re.findall(r"\]\(([^)\s]+)\)", line)]
            targets += [(t, c.source) for t in re.findall(r"`((?:docs/)?[\w./-]+\.md#[\w-]+)`", line)]
            targets += [(t, c.source) for t in re.findall(r"(?<![\w/(`-])(docs/[\w./-]+\.md#[\w-]+)(?!`)", line)]
            for target, base in targets:
                if re.match(r"^[a-z]+:", target):
                    continue
                count += 1
                path, _, frag = target.partition("#")
                f = (base / path).resolve() if path else c.source / rel
                if base == c.source and path and not f.exists():
                    f = (here / path).resolve()
                if not f.exists():
                    bad.append(f"{rel}: {target} (no such file)")
                elif frag and f.suffix == ".md" and frag not in anchors_of(f.read_text(encoding="utf-8")):
                    bad.append(f"{rel}: {target} (no such heading)")
    c.expect(count > 20 and not bad, f"links between the docs resolve ({count} links; broken: {bad})")


def run_all(source, build, folders):
    c = Context(source, build, folders)
    cli = folders.get("docs/cli.md")
    camera = folders.get("docs/camera.md")
    for check in [lambda: check_option_defaults(c),
                  lambda: check_describe_columns(c, cli),
                  lambda: check_bench_keys(c),
                  lambda: check_render_and_grab(c, cli),
                  lambda: check_camera_grab(c, camera),
                  lambda: check_dataset_format(c, cli),
                  lambda: check_repeatability_report(c, cli),
                  lambda: check_studio_model_labels(c),
                  lambda: check_demo_folder(c),
                  lambda: check_studio_objects(c),
                  lambda: check_stability_one_view(c),
                  lambda: check_programs_named(c),
                  lambda: check_links(c),
                  lambda: check_dataset_size(c, cli)]:
        try:
            check()
        except Exception as e:  # a check that cannot run is a failure, never a pass
            c.fail(f"a docs check could not run: {e}")
    return c.results


def check_camera_grab(c, work):
    """docs/camera.md's grab example writes the four files it names (in its own work folder)."""
    m = c.find("docs/camera.md", r"Writes (`view\.pcd`).*?and (`view_\w+\.png`, `view_\w+\.png`, `view_\w+\.png`)")
    if m:
        names = re.findall(r"`([^`]+)`", m.group(1) + m.group(2))
        missing = [n for n in names if not (work / n).exists()]
        c.expect(len(names) == 4 and not missing, f"docs/camera.md: grab writes {names} (missing: {missing})")
