# The clang that scripts/install-deps.sh installs and scripts/test-hardening.sh
# builds with, named once. Debian 12's clang-14 package has versioned commands
# only (clang-14, clang++-14); the unversioned ones come from another package.
# Sourced, not run.
KEYTURN_CLANG_VERSION=14
KEYTURN_CC=clang-$KEYTURN_CLANG_VERSION
KEYTURN_CXX=clang++-$KEYTURN_CLANG_VERSION
# The sanitizers' symbolizer (package llvm-14): suppressions by function name need it.
KEYTURN_SYMBOLIZER=${KEYTURN_SYMBOLIZER:-/usr/lib/llvm-$KEYTURN_CLANG_VERSION/bin/llvm-symbolizer}
