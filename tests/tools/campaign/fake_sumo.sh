#!/usr/bin/env bash
# A stand-in for `sumo` in the campaign tool's tests (what `plan` asks SUMO): with
# --save-configuration FILE it writes a configuration as SUMO does (an <output> section, the time
# and the collision action given), or SUMO's error for an option it does not know; given such a
# configuration (-c FILE --end T) it is the dry start: SUMO's error for a collision action it does
# not know (on exit code 0, as SUMO 1.15 does) and an error when the configuration still names
# an output (which a dry start must not write). Appends each call to $FAKE_SUMO_LOG when set.
[ -n "${FAKE_SUMO_LOG:-}" ] && echo "$*" >>"$FAKE_SUMO_LOG"
save="" cfg="" action="warn" end=""
while [ $# -gt 0 ]; do
  case "$1" in
    --save-configuration) save=$2; shift ;;
    -c) cfg=$2; shift ;;
    --collision.action) action=$2; shift ;;
    --end) end=$2; shift ;;
    --step-lenght)
      echo "Error: On processing option '--step-lenght':" >&2
      echo " No option with the name 'step-lenght' exists." >&2
      echo "Error: Could not parse commandline options." >&2
      echo "Quitting (on error)." >&2
      exit 1 ;;
  esac
  shift
done
if [ -n "$save" ]; then
  cat >"$save" <<XML
<?xml version="1.0" encoding="UTF-8"?>
<configuration>
    <input>
        <net-file value="$cfg.net.xml"/>
    </input>
    <output>
        <fcd-output value="fcd.xml"/>
    </output>
    <time>
        <begin value="5"/>
        <end value="100"/>
    </time>
    <processing>
        <collision.action value="$action"/>
    </processing>
    <report>
        <log value="sumo.log"/>
    </report>
</configuration>
XML
  exit 0
fi
if [ "$end" != 5 ]; then
  echo "Error: a dry start ends where the configuration begins (5), not at '$end'" >&2
  exit 1
fi
if grep -q "output\|<log \|<end " "$cfg"; then
  echo "Error: the dry start was given an output to write" >&2
  exit 1
fi
if grep -q 'collision.action value="explode"' "$cfg"; then
  echo "Error: Invalid collision.action 'explode'." >&2
fi
exit 0
