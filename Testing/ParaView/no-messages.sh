#!/usr/bin/env bash
# Runs a command (a ParaView GUI test) and fails when it fails or when its output holds an error
# or a warning of VTK or ParaView ("ERR|" or "WARN|", as VTK's logger prints them: the messages
# the GUI also shows in its Output Messages window, which pops up over the view).
#
#   bash Testing/ParaView/no-messages.sh paraview --script=...
set -uo pipefail
log=$(mktemp)
"$@" > "$log" 2>&1
status=$?
cat "$log"
messages=$(grep -cE "(WARN|ERR)\|" "$log")
if [ "$messages" != 0 ]; then
  echo "no-messages: $messages error or warning lines in the output (the GUI's Output Messages)"
  status=1
fi
rm -f "$log"
exit $status
