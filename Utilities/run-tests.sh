#!/usr/bin/env bash
# Sets up vtkSAVR and runs every test under Xvfb: the standalone build's tests (engine unit tests,
# rendering tests, the stability label, Python, the installed package used by another project),
# the engine's unit and stability tests again under AddressSanitizer and UBSan (build-sanitize),
# then the ParaView plugin's tests (it is built against ParaView 5.11's own VTK into
# build-paraview; pvbatch in one process and on 2 MPI ranks). Arguments go to ctest.
# SAVR_SKIP_SANITIZE=1 skips the sanitized part, SAVR_SKIP_PARAVIEW=1 the ParaView part.
set -euo pipefail
cd "$(dirname "$0")/.."
bash Utilities/setup.sh
(cd build && xvfb-run -a -s "-screen 0 1024x768x24 -noreset" ctest --output-on-failure "$@")
if [ "${SAVR_SKIP_SANITIZE:-0}" != 1 ]; then
  bash Testing/Sanitize/run-sanitized-tests.sh
fi
if [ "${SAVR_SKIP_PARAVIEW:-0}" != 1 ]; then
  bash Utilities/setup-paraview.sh
  bash Testing/ParaView/run-paraview-tests.sh
fi
