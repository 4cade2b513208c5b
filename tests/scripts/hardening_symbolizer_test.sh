#!/usr/bin/env bash
# The hardening run needs llvm-symbolizer (lsan.supp matches function names): the package that
# ships it is among install-deps.sh's, and test-hardening.sh refuses to start without it, in one
# line, before its long build (issue 52: a bare Debian 12 root had no symbolizer and four sound
# tests failed on suppressed system leaks).
# Usage: hardening_symbolizer_test.sh SOURCE_DIR WORK_DIR
set -uo pipefail
src=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
source "$src/scripts/toolchain.sh"
status=0
# 1. install-deps.sh installs the package that owns the symbolizer it expects.
owner=$(dpkg -S "$(readlink -f "$KEYTURN_SYMBOLIZER")" 2>/dev/null | cut -d: -f1 | head -1)
if [[ -z $owner ]]; then
  echo "FAIL: no Debian package owns $KEYTURN_SYMBOLIZER on this machine"; status=1
elif ! bash -c "source '$src/scripts/toolchain.sh'; eval \"\$(sed -n '/^packages=(/,/^)/p' '$src/scripts/install-deps.sh')\"; printf '%s\n' \"\${packages[@]}\"" |
     grep -x "$owner" > /dev/null; then
  echo "FAIL: scripts/install-deps.sh does not install $owner, which ships $KEYTURN_SYMBOLIZER"; status=1
fi
# 2. Without the symbolizer, test-hardening.sh stops at once with one line and builds nothing.
out=$(KEYTURN_SYMBOLIZER=$work/no-such-symbolizer HARDENING_BUILD_DIR=$work/build bash "$src/scripts/test-hardening.sh" 2>&1)
rc=$?
if [[ $rc -ne 1 ]]; then echo "FAIL: test-hardening.sh exited $rc without a symbolizer, expected 1"; status=1; fi
if [[ $(wc -l <<<"$out") -ne 1 || $out != *"no $work/no-such-symbolizer"*"llvm-$KEYTURN_CLANG_VERSION"* ]]; then
  echo "FAIL: expected one line naming the symbolizer and its package, got:"; echo "$out"; status=1
fi
if [[ -e $work/build ]]; then echo "FAIL: test-hardening.sh configured a build before checking"; status=1; fi
[[ $status -eq 0 ]] && echo "PASS: the symbolizer is installed by install-deps.sh ($owner) and checked first"
exit $status
