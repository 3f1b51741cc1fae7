#!/usr/bin/env bash
# Runs the ParaView plugin's tests under Xvfb (started here unless SAVR_PARAVIEW_XVFB is set,
# for a display of your own): the GUI tests (paraview --script: the image refines by itself, the
# plugin rendering the view through its proxy on the Qt interactor's timer, with no message in
# the Output Messages; the scenes of savr_gui_scenes.py; the Properties panel shows the
# settings, the state and the volume properties that apply to "SAVR Volume", and the particle
# settings for a point cloud), the single-process pvbatch test (wavelet, the wavelet as
# tetrahedra, the MRI head, the AMR pulse, a particle cloud; baselines, refinement, settings,
# threads), the client-server test (a pvpython client connected to a pvserver it starts: the server
# refines, the client receives the images) and the
# distributed tests (the wavelet split across 2 MPI ranks, composited by IceT; a particle cloud
# spread over 2 ranks, gathered on the first; a three-level AMR
# hierarchy in 1 process and spread over 2 and 4 ranks, each drawing a region). Exits non-zero
# when any test fails or logs an error ("ERR|" lines, OpenGL errors among them). Run
# Utilities/setup-paraview.sh first (it builds build-paraview/).
#
#   bash Testing/ParaView/run-paraview-tests.sh            # all the tests
#   bash Testing/ParaView/run-paraview-tests.sh --no-mpi   # without the distributed test
#
# Images (and .diff.png for failed comparisons) go to build-paraview/Testing/Temporary.
set -uo pipefail
script=$(readlink -f "$0")
cd "$(dirname "$script")/../.."
root=$(pwd)
build=${SAVR_PARAVIEW_BUILD:-$root/build-paraview}
# The plugin's folder is named after the installed ParaView's version (paraview-5.11, -5.13).
paraview_version=$(dpkg-query -W -f='${Version}' paraview | sed -e 's/^[0-9]*://' -e 's/^\([0-9]*\.[0-9]*\).*/\1/')
plugin="$build/lib/paraview-$paraview_version/plugins/SAVRPlugin/SAVRPlugin.so"
arch=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || gcc -print-multiarch)
output="$build/Testing/Temporary"
mpi=1
[ "${1:-}" = "--no-mpi" ] && mpi=0

# One X server for all the tests, on a display number picked at random: back-to-back xvfb-run -a
# calls can reuse the number of a server that is still shutting down ("bad X server connection").
# -noreset: by default the server resets whenever its last client disconnects, and a connection
# opened during the reset is closed by it. A process that probes OpenGL with a window of its own,
# closes it and opens its real window at once loses that second connection when it was the only
# client ("bad X server connection", then abort). Measured: 10 of 48 pvbatch processes started
# 4 at a time lost it with the reset, none of 48 with -noreset.
if [ -z "${SAVR_PARAVIEW_XVFB:-}" ] && command -v xvfb-run >/dev/null; then
  export SAVR_PARAVIEW_XVFB=1
  exec xvfb-run -a -n $((200 + RANDOM % 600)) -s "-screen 0 1024x768x24 -noreset" \
    bash "$script" "$@"
fi

if [ ! -f "$plugin" ]; then
  echo "run-paraview-tests: $plugin is missing; run Utilities/setup-paraview.sh first" >&2
  exit 1
fi
# ParaView's Python, unpacked privately by the setup (python3-paraview conflicts with
# python3-vtk9, which the standalone build needs).
export PYTHONPATH="$build/python3-paraview/usr/lib/python3/dist-packages"
mkdir -p "$output"

status=0
# What failed, repeated at the end (group, then its lines that say FAIL or error), so that the
# last lines of a long log still say which group failed and why.
failures=$(mktemp)
run() {
  local name=$1
  shift
  local attempt log
  for attempt in 1 2 3; do
    echo "== $name: $*"
    local start=$SECONDS
    log=$(mktemp)
    # A normal run takes seconds; the limit catches a rank that waits forever for another.
    # An error that VTK or ParaView logged (an "ERR|" line: OpenGL errors among them) fails the
    # run even where every check passed.
    if timeout 300 "$@" 2>&1 | tee "$log"; [ "${PIPESTATUS[0]}" = 0 ] && ! grep -q "ERR|" "$log"; then
      echo "== $name passed ($((SECONDS - start)) s)"
      rm -f "$log"
      return
    fi
    # A lost X connection ("bad X server connection", before any check runs) is tried again,
    # twice, and nothing else is. (It came from the server's reset, which -noreset above turns
    # off; a display of one's own, SAVR_PARAVIEW_XVFB set, may still reset.) A rank that cannot
    # reach the X server while the ranks probe it makes every rank report that remote rendering
    # is not available, and the first render then waits for it until the timeout: the same
    # failure, tried again too.
    if [ $attempt -lt 3 ] && grep -q -e "bad X server connection" \
      -e "require remote rendering which, however, is not available" "$log"; then
      echo "== $name: the X server refused a connection; trying once more"
      rm -f "$log"
      sleep 2
      continue
    fi
    echo "== $name FAILED ($((SECONDS - start)) s)"
    {
      echo "== $name FAILED"
      grep -i -e "fail" -e "error" -e "ERR|" -e "abort" -e "timed out" "$log" | head -n 20 | cut -c 1-300
    } >>"$failures"
    rm -f "$log"
    status=1
    return
  done
}

echo "run-paraview-tests: DISPLAY=${DISPLAY:-unset}"
run "pvbatch, 1 process" pvbatch Testing/ParaView/savr_pvbatch.py \
  --plugin "$plugin" --output "$output"
run "paraview GUI, refinement after interaction" env SAVR_PLUGIN="$plugin" \
  bash Testing/ParaView/no-messages.sh paraview --script=Testing/ParaView/savr_gui.py
# The GUI as a user meets it, one scene per process (savr_gui_scenes.py): a translucent sphere
# with depth peeling, the colour legend and axes on every frame, no renders for a volume that
# draws nothing, the array chosen when switching to SAVR Volume, the AMR pulse on first use
# (coloured by a vector array), a mouse drag, a 200,000-point cloud whose renders never hold the
# event loop past 0.5 s, a cloud's density in Solid Color. No run may leave a message in the
# GUI's Output Messages (no-messages.sh).
for scene in peeling annotations idle autoarray amrfirst drag responsive density; do
  run "paraview GUI, $scene" env SAVR_PLUGIN="$plugin" SAVR_GUI_SCENE=$scene \
    bash Testing/ParaView/no-messages.sh \
    paraview --dr --script=Testing/ParaView/savr_gui_scenes.py
done
# The GUI connected to a pvserver: the server renders every refinement frame the client's
# scheduler asks for.
run "paraview GUI connected to a pvserver" env SAVR_PLUGIN="$plugin" SAVR_GUI_SCENE=server \
  bash Testing/ParaView/with-pvserver.sh \
  paraview --dr --script=Testing/ParaView/savr_gui_scenes.py
# The Properties panel: QtTesting plays savr_gui_panel.xml's checks of which widgets it shows
# (--dr: without the user's settings; DASHBOARD_TEST_FROM_CTEST: no "Are you sure?" prompt;
# a missing widget lists 5 of the widgets found instead of thousands).
run "paraview GUI, Properties panel" env SAVR_PLUGIN="$plugin" DASHBOARD_TEST_FROM_CTEST=1 \
  PQOBJECTNAMING_MATCH_LIMIT=5 \
  paraview --dr --script=Testing/ParaView/savr_gui_panel.py \
  --test-script=Testing/ParaView/savr_gui_panel.xml --exit
# The same for a point cloud: the particle settings and the volume properties.
run "paraview GUI, Properties panel of a point cloud" env SAVR_PLUGIN="$plugin" \
  DASHBOARD_TEST_FROM_CTEST=1 PQOBJECTNAMING_MATCH_LIMIT=5 \
  paraview --dr --script=Testing/ParaView/savr_gui_particles.py \
  --test-script=Testing/ParaView/savr_gui_particles.xml --exit
# pvpython comes with ParaView's Python, unpacked into the build. Loaded from there it finds
# ParaView's libraries through the loader's cache (/lib/...), derives "//lib/python3/dist-packages"
# from them and puts that before PYTHONPATH: Debian's VTK (python3-vtk9) instead of ParaView's,
# which crashes. With the libraries' /usr path it adds nothing.
run "pvpython client, pvserver" \
  env LD_LIBRARY_PATH="/usr/lib/$arch${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
  "$build/python3-paraview/usr/bin/pvpython" Testing/ParaView/savr_pvserver.py \
  --plugin "$plugin" --output "$output"
if [ $mpi = 1 ]; then
  run "pvbatch, 2 MPI ranks" mpirun --allow-run-as-root --oversubscribe -np 2 \
    -x PYTHONPATH \
    pvbatch --mpi Testing/ParaView/savr_pvbatch_mpi.py --ranks 2 \
    --plugin "$plugin" --output "$output"
  # The particle cloud spread over 2 ranks: the first gathers every point and draws alone.
  run "pvbatch particles, 2 MPI ranks" mpirun --allow-run-as-root --oversubscribe -np 2 \
    -x PYTHONPATH \
    pvbatch --mpi Testing/ParaView/savr_pvbatch_mpi.py --scenes particles --ranks 2 \
    --plugin "$plugin" --output "$output"
  # AMR spread over 1, 2 and 4 ranks (4 oversubscribe the 2 cores: slow, but it shows the
  # regions and the blocks they exchange).
  run "pvbatch AMR, 1 process" pvbatch Testing/ParaView/savr_pvbatch_mpi.py --scenes amr \
    --ranks 1 --plugin "$plugin" --output "$output"
  run "pvpython client, pvserver on 2 MPI ranks" \
    env LD_LIBRARY_PATH="/usr/lib/$arch${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
    "$build/python3-paraview/usr/bin/pvpython" Testing/ParaView/savr_pvserver.py --ranks 2 \
    --plugin "$plugin" --output "$output"
  for n in 2 4; do
    run "pvbatch AMR, $n MPI ranks" mpirun --allow-run-as-root --oversubscribe -np $n \
      -x PYTHONPATH \
      pvbatch --mpi Testing/ParaView/savr_pvbatch_mpi.py --scenes amr --ranks $n \
      --plugin "$plugin" --output "$output"
  done
fi
if [ $status = 0 ]; then
  echo "run-paraview-tests: all passed"
else
  echo "run-paraview-tests: what failed:"
  cat "$failures"
  echo "run-paraview-tests: FAILED"
fi
rm -f "$failures"
exit $status
