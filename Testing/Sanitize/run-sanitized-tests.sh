#!/usr/bin/env bash
# Builds the engine and its unit and stability tests with AddressSanitizer and UBSan into
# build-sanitize/ (Testing/Sanitize) and runs them with ctest. A memory error, a leak or any
# undefined behaviour aborts the test that meets it, so the run fails. Arguments go to ctest.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build=${SAVR_SANITIZE_BUILD:-$root/build-sanitize}
cmake -S "$root/Testing/Sanitize" -B "$build"
cmake --build "$build" -j2
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
cd "$build" && ctest --output-on-failure "$@"
