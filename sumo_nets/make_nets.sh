#!/usr/bin/env bash
# Regenerates every .net.xml from its plain-XML sources with SUMO's netconvert (Debian sumo).
# Usage: sumo_nets/make_nets.sh   (run after editing a .nod/.edg/.con.xml)
set -euo pipefail
cd "$(dirname "$0")"
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
for dir in */; do
  name=${dir%/}
  args=(--node-files "$name/$name.nod.xml" --edge-files "$name/$name.edg.xml"
        --output-file "$name/$name.net.xml" --no-turnarounds true --xml-validation never)
  [ -f "$name/$name.con.xml" ] && args+=(--connection-files "$name/$name.con.xml")
  # Opposite-direction lanes know each other (overtaking through counter traffic).
  args+=(--opposites.guess true)
  netconvert "${args[@]}" >/dev/null
  echo "made $name/$name.net.xml"
done
