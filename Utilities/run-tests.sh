#!/usr/bin/env bash
# Sets up vtkSAVR and runs every test (engine unit tests and rendering tests) under Xvfb.
set -euo pipefail
cd "$(dirname "$0")/.."
bash Utilities/setup.sh
cd build
xvfb-run -a -s "-screen 0 1024x768x24" ctest --output-on-failure "$@"
