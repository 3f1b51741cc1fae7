#!/usr/bin/env bash
# Runs the README's test command (Utilities/run-tests.sh) on Debian 13 ("trixie": VTK 9.3,
# ParaView 5.13 with Qt 6), as root. On a Debian 13 machine it runs there; elsewhere it runs in a
# clean Debian 13 root beside the machine's own system (Utilities/in-debian-root.sh: made once
# with debootstrap, kept in /var/cache/vtksavr/trixie), which installs and builds what the tests
# need inside it. Arguments go to ctest, as with run-tests.sh.
# SAVR_SANITIZE_DEBIAN13=1 also runs the sanitized engine tests there (the compiler is another
# one, the engine's code is the same: left out by default to keep CI within its time).
set -euo pipefail
cd "$(dirname "$0")/.."
codename=$(. /etc/os-release && echo "${VERSION_CODENAME:-}")
skip_sanitize=1
[ "${SAVR_SANITIZE_DEBIAN13:-0}" = 1 ] && skip_sanitize=0
if [ "$codename" = trixie ]; then
  SAVR_SKIP_SANITIZE=$skip_sanitize exec bash Utilities/run-tests.sh "$@"
fi
start=$SECONDS
status=0
SAVR_SKIP_SANITIZE=$skip_sanitize bash Utilities/in-debian-root.sh trixie \
  bash Utilities/run-tests.sh "$@" || status=$?
echo "run-tests-debian13: $([ $status = 0 ] && echo passed || echo FAILED) in $((SECONDS - start)) s"
exit $status
