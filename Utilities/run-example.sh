#!/usr/bin/env bash
# Sets up vtkSAVR and renders the MRI head headless until refinement completes, printing each
# frame's time and writing savr_head.png. Extra arguments go to the example.
set -euo pipefail
cd "$(dirname "$0")/.."
bash Utilities/setup.sh
xvfb-run -a -s "-screen 0 1024x768x24 -noreset" build/bin/savr_head --headless --output savr_head.png "$@"
