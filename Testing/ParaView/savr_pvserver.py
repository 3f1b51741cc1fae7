"""Client-server test of the SAVR ParaView plugin: a pvpython client connected to a pvserver.

    LD_LIBRARY_PATH=/usr/lib/x86_64-linux-gnu \\
      PYTHONPATH=build-paraview/python3-paraview/usr/lib/python3/dist-packages \\
      xvfb-run -a -s "-screen 0 1024x768x24 -noreset" build-paraview/python3-paraview/usr/bin/pvpython \\
      Testing/ParaView/savr_pvserver.py [--plugin SAVRPlugin.so] [--baselines DIR] [--output DIR]
        [--pvserver pvserver] [--timeout SECONDS] [--ranks N]

Starts `pvserver --server-port=0` (with --ranks N, under `mpirun -np N`: the wavelet is then
split over the server's ranks and composited there; the server picks a free port and prints it; the script reads
it from the server's output), connects to it with Connect("localhost", port) and loads the
plugin on both sides (remote=False for the client's copies of the plugin's objects, remote=True
for the server, which renders). Remote rendering is forced (RemoteRenderThreshold 0), so the
server renders every still render and delivers the image to the client, compressed as ParaView
does by default (LZ4, lossy). The wavelet is shown as "SAVR Volume" with the single-process
test's transfer functions and camera (LD_LIBRARY_PATH: see run-paraview-tests.sh). Checks:

- "SAVR Volume" is offered and shown (the proxy definitions are the server's: without the
  plugin on the server it is not offered, and the test stops there);
- the client's view rendered remotely (its UseDistributedRenderingForRender), so the images
  below are the server's, and the state the client reads (the SAVR settings live on the server
  only) is the server's mapper's: all frames, complete;
- one refinement frame per still render, read from the images the client receives: after the
  camera change, each of the first 4 renders (the default frame limit) changes the image, and
  a 5th render after completion does not change it at all;
- the first frame and the final image differ (refinement happened on the server);
- the final image is drawn (not blank) and matches the single-process baseline
  ParaViewWavelet.png within the tolerances of the 2-rank test (savr_pvbatch_mpi.py: max 16
  levels, mean 0.2; here the delivery's lossy compression is the difference);
- the server is still running after all that.

The server is started with a parent-death signal (SIGKILL): it ends when the client does,
however the client ends (an exception stops it at once). After --timeout seconds the client
prints its stack and exits with status 1 (faulthandler's watchdog thread, which works while the
client waits inside ParaView for a server that does not answer).
"""
import argparse
import ctypes
import faulthandler
import os
import re
import signal
import subprocess
import sys
import threading

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import savr_paraview_testing as T  # noqa: E402
from paraview import simple as pvs  # noqa: E402

# Composited or delivered images vs the single-process baseline (as savr_pvbatch_mpi.py).
MAX_LEVEL = 16
MAX_MEAN = 0.2
FRAME_LIMIT = 4  # the mapper's automatic frame limit for the wavelet at the default step


def die_with_parent():
    """In the child before exec: SIGKILL when the client (its parent) dies."""
    PR_SET_PDEATHSIG = 1
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)


def start_server(pvserver, log_path, ranks):
    """Starts pvserver on a free port, on `ranks` MPI ranks when more than one; returns the
    process and the port (the watchdog ends a server that never says)."""
    log = open(log_path, "w")
    command = [pvserver, "--dr", "--server-port=0"]
    environment = dict(os.environ)
    if ranks > 1:
        command = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + command
        # pvpython initializes MPI as a singleton, which leaves Open MPI's variables in its
        # environment; an mpirun started with them refuses to run (it exits at once, silent).
        environment = {k: v for k, v in environment.items()
                       if not k.startswith(("OMPI_", "PMIX_", "OPAL_"))}
    server = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              text=True, preexec_fn=die_with_parent, env=environment)
    port = None
    for line in server.stdout:
        log.write(line)
        log.flush()
        match = re.search(r"Accepting connection\(s\): \S+:(\d+)", line)
        if match:
            port = int(match.group(1))
            break
    if port is None:
        stop_server(server)
        log.close()
        show_server_log(log_path)
        raise SystemExit("pvserver did not report a port (its output is above)")
    # The rest of the server's output goes to the log, read by a thread of its own (the pipe
    # must not fill up).
    def drain():
        for rest in server.stdout:
            log.write(rest)
            log.flush()
        log.close()
    threading.Thread(target=drain, daemon=True).start()
    return server, port


def show_server_log(log_path):
    """Prints the server's output (on failure: run-paraview-tests.sh looks there too for the X
    server's refusals)."""
    print("---- pvserver output (%s):" % log_path)
    with open(log_path) as f:
        sys.stdout.write(f.read())
    print("---- end of pvserver output")
    sys.stdout.flush()


def stop_server(server):
    if server.poll() is None:
        server.terminate()
        try:
            server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plugin", default=T.DEFAULT_PLUGIN)
    parser.add_argument("--baselines", default=T.DEFAULT_BASELINES)
    parser.add_argument("--output", default=T.DEFAULT_OUTPUT)
    parser.add_argument("--pvserver", default="pvserver")
    parser.add_argument("--timeout", type=float, default=240.0)
    parser.add_argument("--ranks", type=int, default=1, help="pvserver's MPI ranks")
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)
    if not os.path.exists(args.plugin):
        raise SystemExit("plugin not found: %s (run Utilities/setup-paraview.sh)" % args.plugin)
    # File descriptor 2: pvpython replaces sys.stderr with an object without a descriptor.
    faulthandler.dump_traceback_later(args.timeout, exit=True, file=2)

    log_path = os.path.join(args.output, "savr_pvserver.server.log")
    server, port = start_server(args.pvserver, log_path, args.ranks)
    print("pvserver (pid %d) listens on port %d; its output goes to %s" % (
        server.pid, port, log_path))
    sys.stdout.flush()
    try:
        failures = run(args, port)
    except BaseException:
        stop_server(server)
        show_server_log(log_path)
        raise
    # The server must have lived through the checks. It is left running until this client
    # exits: then the parent-death signal ends it, after the client has closed its session
    # (pvs.Disconnect() leaves the server waiting, and stopping the server first makes the
    # client's exit report a broken connection).
    failures.check(server.poll() is None, "pvserver is still running after the checks (exit "
        "status %s)" % server.returncode)
    if failures.messages:
        stop_server(server)
        show_server_log(log_path)
        print("%d check(s) failed:" % len(failures.messages))
        for m in failures.messages:
            print("  " + m)
        sys.stdout.flush()
        sys.exit(1)
    print("all checks passed")
    sys.stdout.flush()


def run(args, port):
    failures = T.Failures()
    pvs.Connect("localhost", port)
    connection = pvs.servermanager.ActiveConnection
    failures.check(connection is not None and connection.IsRemote(),
        "connected to the pvserver on port %d" % port)
    partitions = connection.GetNumberOfDataPartitions()
    failures.check(partitions == args.ranks,
        "the server runs on %d rank(s) (expected %d)" % (partitions, args.ranks))
    # The client makes its own copies of the representations (which never render); the
    # server renders.
    T.load_plugin(args.plugin, remote=False)
    T.load_plugin(args.plugin, remote=True)
    pvs.GetSettingsProxy("RenderViewSettings").RemoteRenderThreshold = 0.0

    view = T.make_view()
    source, rep, camera = T.wavelet_scene(view)
    available = rep.GetProperty("Representation").Available
    if not failures.check("SAVR Volume" in available and rep.Representation == "SAVR Volume" and
            rep.GetProperty("NumberOfFramesAccumulated") is not None,
            "the wavelet is shown as \"SAVR Volume\" (offered: %s)" % ", ".join(available)):
        return failures
    T.start_view(view, rep, camera)
    images = []
    for _ in range(FRAME_LIMIT + 1):
        pvs.Render(view)
        images.append(T.capture(view))

    failures.check(view.GetClientSideObject().GetUseDistributedRenderingForRender(),
        "the client's view renders remotely (the server renders, the client receives the image)")
    state = T.state(rep)
    failures.check(state["NumberOfFramesAccumulated"] == FRAME_LIMIT == state["FrameLimit"] and
        state["RefinementComplete"] == 1,
        "the state the client reads is the server's mapper's (%d of %d frames, complete %d)" % (
            state["NumberOfFramesAccumulated"], state["FrameLimit"], state["RefinementComplete"]))
    for i in range(1, FRAME_LIMIT):
        worst, mean = T.difference(images[i - 1], images[i])
        failures.check(worst > 0,
            "render %d adds a frame: the image changes (max %d, mean %.4f)" % (i + 1, worst, mean))
    worst, mean = T.difference(images[FRAME_LIMIT - 1], images[FRAME_LIMIT])
    failures.check(worst == 0,
        "render %d, after completion, leaves the image as it was (max %d, mean %.4f)" % (
            FRAME_LIMIT + 1, worst, mean))
    first, final = images[0], images[FRAME_LIMIT - 1]
    worst, mean = T.difference(first, final)
    failures.check(worst >= 5 and mean > 0.05,
        "refinement changed the delivered image (first frame vs final: max %d, mean %.3f)" % (
            worst, mean))
    T.is_drawn(final, failures, "the wavelet delivered to the client")
    T.compare_baseline(final, "ParaViewWaveletPVServer", args.baselines, args.output, failures,
        max_level=MAX_LEVEL, max_mean=MAX_MEAN, baseline_name="ParaViewWavelet")
    T.write_png(first, os.path.join(args.output, "ParaViewWaveletPVServerFirstFrame.png"))
    expected = os.path.join(args.baselines, "ParaViewWaveletFirstFrame.png")
    if os.path.exists(expected):
        print("first frame vs the single-process first frame: max %d, mean %.3f" %
              T.difference(first, T.read_png(expected)))

    T.close_session()
    return failures


if __name__ == "__main__":
    main()
