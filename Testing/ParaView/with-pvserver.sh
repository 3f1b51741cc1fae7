#!/usr/bin/env bash
# Starts a pvserver on a free local port, runs a command with --server-url=cs://localhost:<port>
# appended (a paraview GUI test that connects to it), stops the server, and exits with the
# command's status.
#
#   bash Testing/ParaView/with-pvserver.sh paraview --script=...
set -uo pipefail
port=$((20000 + RANDOM % 20000))
log=$(mktemp)
pvserver --server-port=$port < /dev/null > "$log" 2>&1 &
server=$!
# Wait until it listens (at most 30 s).
for _ in $(seq 300); do
  grep -q "Accepting connection" "$log" && break
  kill -0 $server 2>/dev/null || break
  sleep 0.1
done
if ! grep -q "Accepting connection" "$log"; then
  echo "with-pvserver: the server did not start:"
  cat "$log"
  kill $server 2>/dev/null
  rm -f "$log"
  exit 1
fi
"$@" --server-url=cs://localhost:$port
status=$?
# The server may outlive its client for a while (or ignore the request to stop while it still
# waits on the closed connection): ask, then insist, never wait forever.
kill $server 2>/dev/null
for _ in $(seq 50); do
  kill -0 $server 2>/dev/null || break
  sleep 0.1
done
kill -9 $server 2>/dev/null
rm -f "$log"
exit $status
