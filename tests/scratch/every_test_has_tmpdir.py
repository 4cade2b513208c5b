#!/usr/bin/env python3
"""Every ctest test of this build runs with TMPDIR=BUILD/test-tmp and in the fixture keyturn_tmpdir, so
scratch.tmpdir_left_empty sees what it leaves (a test added without them would leak into /tmp unseen).
Reads the tests as ctest lists them (--show-only=json-v1). Usage: every_test_has_tmpdir.py CTEST BUILD TMPDIR"""
import json
import subprocess
import sys

ctest, build, tmpdir = sys.argv[1:4]
listing = subprocess.run([ctest, "--test-dir", build, "--show-only=json-v1"], capture_output=True, text=True, check=True)
tests = json.loads(listing.stdout)["tests"]
own = {"scratch.tmpdir_reset", "scratch.tmpdir_left_empty"}
missing = []
for t in tests:
    if t["name"] in own:
        continue
    props = {p["name"]: p["value"] for p in t.get("properties", [])}
    fixtures = props.get("FIXTURES_REQUIRED", [])
    env = props.get("ENVIRONMENT_MODIFICATION", [])
    lacks = []
    if "keyturn_tmpdir" not in fixtures:
        lacks.append("FIXTURES_REQUIRED keyturn_tmpdir")
    if f"TMPDIR=set:{tmpdir}" not in env:
        lacks.append(f"ENVIRONMENT_MODIFICATION TMPDIR=set:{tmpdir}")
    if lacks:
        missing.append(f"  {t['name']}: no {' and no '.join(lacks)}")
checked = len(tests) - len(own & {t["name"] for t in tests})
if len(tests) < 50:
    sys.exit(f"every_test_has_tmpdir: ctest lists only {len(tests)} tests in {build}: not this suite")
if missing:
    print(f"every_test_has_tmpdir: {len(missing)} of {checked} tests run outside the tests' TMPDIR "
          "(give them ${KEYTURN_TEST_TMPDIR_PROPERTIES}, tests/CMakeLists.txt):")
    print("\n".join(missing))
    sys.exit(1)
print(f"every_test_has_tmpdir: all {checked} tests run with TMPDIR={tmpdir} in the fixture keyturn_tmpdir")
