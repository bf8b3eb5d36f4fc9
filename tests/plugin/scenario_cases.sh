#!/usr/bin/env bash
# SUMO-level tests of sumo-criticality (ctest label sumo), one case per ctest entry:
#   scenario_cases.sh DRIVER BENCH SCENARIOS_DIR WORK_DIR CASE
# Cases: collision:NAME, free:NAME, brake, conversion_replay, connect, bad_input.
# Every check asserts on the results database (sqlite3) or on exit codes and messages.
set -u
driver=$1 bench=$2 scenarios=$3 work=$4 case=$5
mkdir -p "$work"
fail=0
check() {  # check DESCRIPTION COMMAND...
  local what=$1; shift
  if "$@"; then echo "ok: $what"; else echo "FAILED: $what"; fail=1; fi
}
q() { sqlite3 "$1" "$2"; }
start_sumo() {  # start_sumo SCENARIO SUMOCFG: a sumo server on a free port; sets port, sumo_pid
  port=$(python3 -c "import socket; s=socket.socket(); s.bind(('127.0.0.1',0)); print(s.getsockname()[1])")
  (cd "$scenarios/$1" && SUMO_HOME=${SUMO_HOME:-/usr/share/sumo} exec sumo -c "$2" \
     --remote-port "$port" --no-step-log --xml-validation never >/dev/null 2>&1) &
  sumo_pid=$!
}
run() {  # run NAME DB [extra args]: runs a scenario, echoes its summary line
  local name=$1 db=$2; shift 2
  rm -f "$db"
  "$driver" --config "$scenarios/$name/scenario.cfg" --output "$db" --no-progress "$@"
}

case $case in
  collision:*)
    name=${case#collision:}; db=$work/$name.sqlite
    summary=$(run "$name" "$db"); echo "$summary"
    check "$name: run completed" test "$(q "$db" "select status from runs")" = completed
    check "$name: SUMO recorded a collision of the ego" \
      test "$(q "$db" "select count(*) from collisions where collider='ego' or victim='ego'")" -ge 1
    first=$(q "$db" "select min(time_s) from collisions where collider='ego' or victim='ego'")
    check "$name: a warning episode started before the collision" \
      test "$(q "$db" "select count(*) from warnings where ego='ego' and start_s < $first")" -ge 1
    check "$name: the collision's anticipation time is positive" \
      test "$(q "$db" "select count(*) from collisions where anticipation_s > 0")" -ge 1
    check "$name: steps recorded every 0.1 s until the end" \
      test "$(q "$db" "select count(*) from steps")" -ge 50
    check "$name: summary says the expectation is met" grep -q '"expectation_met":true' <<<"$summary"
    ;;
  free:*)
    name=${case#free:}; db=$work/$name.sqlite
    summary=$(run "$name" "$db"); echo "$summary"
    check "$name: no collision" test "$(q "$db" "select count(*) from collisions")" -eq 0
    check "$name: no warning" test "$(q "$db" "select count(*) from warnings")" -eq 0
    check "$name: close traffic was considered (objects > 0)" \
      test "$(q "$db" "select max(objects) from steps")" -ge 1
    check "$name: but some risk was seen (p > 0 at some step)" \
      test "$(q "$db" "select count(*) from steps where p_collision > 0")" -ge 1
    ;;
  brake)
    warn_db=$work/brake_warn.sqlite brake_db=$work/brake_brake.sqlite
    run rear_end "$warn_db" --act warn >/dev/null
    run rear_end "$brake_db" --act brake >/dev/null
    v_warn=$(q "$warn_db" "select collider_speed_mps from collisions where collider='ego' order by time_s limit 1")
    v_brake=$(q "$brake_db" "select coalesce((select collider_speed_mps from collisions where collider='ego' order by time_s limit 1), 0)")
    echo "collision speed: warn $v_warn m/s, brake ${v_brake} m/s (0 = avoided)"
    check "brake: an action was recorded" test "$(q "$brake_db" "select count(*) from actions where kind='brake'")" -ge 1
    check "brake: the collision is avoided or slower" python3 -c "import sys; sys.exit(0 if float('$v_brake') < float('$v_warn') - 1.0 else 1)"
    check "brake: control is handed back (release recorded) or the run ends braking" \
      test "$(q "$brake_db" "select count(*) from actions")" -ge 1
    ;;
  conversion_replay)
    db=$work/conversion.sqlite scenes=$work/scenes
    rm -rf "$scenes"
    run rear_end "$db" --record-scenes "$scenes" --end 11.5 >/dev/null
    file=$(cd "$scenes" && grep -l '^vehicle obstacle ' * | head -n 1)
    check "scene files were recorded" test -n "$file"
    # The obstacle stands with its front bumper at x = 400 m on lane 1 (centre y = -5.25) of
    # the eastbound road: SUMO's navigation angle 90 deg. Its centre is 2.25 m behind the front.
    line=$(grep '^vehicle obstacle ' "$scenes/$file")
    check "front bumper -> centre and navigation angle -> yaw on a known vehicle" \
      python3 -c "x,y,yaw=map(float,'$line'.split()[2:5]); import sys; sys.exit(0 if abs(x-397.75)<1e-6 and abs(y+5.25)<1e-6 and abs(yaw)<1e-9 else 1)"
    last=$(ls "$scenes" | tail -n 1)
    t=$(sed -e 's/^t0*\([0-9.]*\)_.*/\1/' <<<"$last")
    p_db=$(q "$db" "select printf('%.12f', p_collision) from steps where abs(time_s - $t) < 1e-6")
    p_bench=$("$bench" --scene-file "$scenes/$last" --repeat 1 --warmup 0 --json | tail -n 1 |
              python3 -c "import json,sys; print('%.12f' % json.loads(sys.stdin.read())['p_collision'])")
    check "criticality-bench --scene-file replays the recorded estimate exactly ($p_db = $p_bench)" test "$p_db" = "$p_bench"
    ;;
  connect)
    db=$work/connect.sqlite; rm -f "$db"
    start_sumo rear_end rear_end.sumocfg
    summary=$("$driver" --connect "127.0.0.1:$port" --ego ego --output "$db" --no-progress \
                --event "0 ego speed-mode 0" --event "0 ego speed 30" --event "0 ego lane-change-mode 0")
    rc=$?
    wait $sumo_pid 2>/dev/null
    echo "$summary"
    check "--connect run exits 0" test $rc -eq 0
    check "--connect: steps recorded" test "$(q "$db" "select count(*) from steps")" -ge 50
    check "--connect: the rear-end collision recorded" \
      test "$(q "$db" "select count(*) from collisions where 'ego' in (collider, victim)")" -ge 1
    ;;
  all_vehicles)
    db=$work/all.sqlite
    summary=$(run motorway_dense_free "$db" --all-vehicles --end 2 --own-lane-samples 1 --neighbour-lane-samples 1)
    echo "$summary"
    check "--all-vehicles: every one of the 7 vehicles is an ego" \
      test "$(q "$db" "select count(distinct ego) from steps")" -eq 7
    check "--all-vehicles: summary counts 7 egos" grep -q '"egos":7,' <<<"$summary"
    ;;
  consistent_reads)
    # With several egos, every scene of one step must see the same state of a vehicle (each
    # vehicle is read once per step; a second read in one step once gave yaw rate 0). Turning
    # traffic gives non-zero yaw rates, and curved junction lanes must never fail a run.
    db=$work/consistent.sqlite scenes=$work/consistent_scenes
    rm -rf "$scenes"
    summary=$(run junction_turning_free "$db" --all-vehicles --record-scenes "$scenes")
    check "turning traffic: run completed" grep -q '"status":"completed"' <<<"$summary"
    check "turning traffic: no collision" test "$(q "$db" "select count(*) from collisions")" -eq 0
    check "scenes recorded for every ego" test "$(ls "$scenes" | wc -l)" -ge 600
    check "one state per vehicle and step in every ego's scene, yaw rates non-zero" python3 - "$scenes" <<'PY'
import collections, os, sys
d = sys.argv[1]
states = collections.defaultdict(set)  # (time, vehicle) -> states seen
turning = 0
for f in os.listdir(d):
    t = f.split('_')[0]
    for line in open(os.path.join(d, f)):
        w = line.split()
        if w and w[0] in ('ego', 'vehicle'):
            states[(t, w[1])].add(tuple(w[2:9]))
            turning += abs(float(w[7])) > 1e-6
bad = [k for k, v in states.items() if len(v) > 1]
print(f"{len(states)} (step, vehicle) states, {len(bad)} inconsistent, {turning} with yaw rate")
sys.exit(0 if not bad and turning > 0 else 1)
PY
    ;;
  disk_full)
    # A file-size limit makes every write past 32 KB fail, as a full disk does.
    db=$work/full.sqlite; rm -f "$db"*
    err=$( (ulimit -f 32; trap '' XFSZ; exec "$driver" --config "$scenarios/rear_end/scenario.cfg" \
             --output "$db" --no-progress) 2>&1 >/dev/null); rc=$?
    echo "   -> $err"
    check "full disk: exit 4" test $rc -eq 4
    check "full disk: one-line error naming the output" test "$(printf '%s\n' "$err" | wc -l)" -eq 1
    check "full disk: error names the file" grep -q "full.sqlite" <<<"$err"
    check "full disk: the steps completed before are readable" test "$(q "$db" "select count(*) from steps")" -ge 10
    ;;
  sumo_dies)
    # SUMO goes away mid-run (a closed sumo-gui): SUMO error, completed steps kept.
    db=$work/dies.sqlite; rm -f "$db"
    start_sumo motorway_dense_free motorway.sumocfg
    (sleep 4; kill -9 $sumo_pid 2>/dev/null) &
    err=$("$driver" --connect "127.0.0.1:$port" --ego ego --output "$db" --no-progress 2>&1 >/dev/null); rc=$?
    echo "   -> $err"
    check "SUMO died: exit 3" test $rc -eq 3
    check "SUMO died: one-line error" test "$(printf '%s\n' "$err" | wc -l)" -eq 1
    check "SUMO died: steps before are kept" test "$(q "$db" "select count(*) from steps")" -ge 1
    check "SUMO died: the run is marked failed" grep -q "^failed" <<<"$(q "$db" "select status from runs")"
    ;;
  bad_input)
    expect_error() {  # expect_error CODE PATTERN ARGS...
      local code=$1 pattern=$2; shift 2
      local err rc
      err=$("$driver" --no-progress "$@" 2>&1 >/dev/null); rc=$?
      check "'$*' exits $code" test "$rc" -eq "$code"
      check "'$*' error is one line" test "$(printf '%s\n' "$err" | wc -l)" -eq 1
      check "'$*' error names '$pattern'" grep -q -- "$pattern" <<<"$err"
      echo "   -> $err"
    }
    cfg=$scenarios/rear_end/scenario.cfg
    rm -f "$work"/b*.sqlite
    expect_error 2 "no such file" -c "$work/missing.sumocfg" --ego ego --output "$work/b1.sqlite"
    printf '<configuration><input><net-file value="nowhere.net.xml"/></input>\n' > "$work/broken.sumocfg"
    rm -f "$work/b2.sqlite"
    expect_error 3 "SUMO error" -c "$work/broken.sumocfg" --ego ego --output "$work/b2.sqlite"
    check "a failed SUMO start is recorded in the database" grep -q failed <<<"$(q "$work/b2.sqlite" "select status from runs")"
    rm -f "$work/b3.sqlite"
    expect_error 5 "never departed" --config "$cfg" --ego nobody --output "$work/b3.sqlite"
    check "steps before the failure are kept" test "$(q "$work/b3.sqlite" "select count(*) from steps where ego='ego'")" -ge 100
    expect_error 4 "already exists" --config "$cfg" --output "$work/b3.sqlite"
    expect_error 2 "act" --config "$cfg" --act explode --output "$work/b4.sqlite"
    expect_error 2 "params.profiles" --config "$cfg" --profiles 1 --output "$work/b5.sqlite"
    expect_error 2 "unknown action" --config "$cfg" --event "1 ego fly 3" --output "$work/b6.sqlite"
    expect_error 2 "HOST:PORT" --connect nonsense --ego ego --output "$work/b7.sqlite"
    expect_error 2 "no ego" -c "$scenarios/rear_end/rear_end.sumocfg" --output "$work/b8.sqlite"
    # An ego whose route ends (arrivalPos) while another vehicle drives on.
    cat > "$work/arrive.rou.xml" <<'XML'
<routes>
  <vType id="car" length="4.5" width="1.8" sigma="0"/>
  <vehicle id="other" type="car" depart="0" departLane="0" departPos="5" departSpeed="20"><route edges="WE"/></vehicle>
  <vehicle id="ego" type="car" depart="0" departLane="1" departPos="10" departSpeed="30" arrivalPos="300"><route edges="WE"/></vehicle>
</routes>
XML
    printf '<configuration><input><net-file value="%s"/><route-files value="arrive.rou.xml"/></input><time><end value="60"/><step-length value="0.1"/></time></configuration>\n' \
      "$scenarios/../sumo_nets/straight_3lane/straight_3lane.net.xml" > "$work/arrive.sumocfg"
    rm -f "$work/b9.sqlite"
    expect_error 5 "arrived" -c "$work/arrive.sumocfg" --ego ego --output "$work/b9.sqlite"
    check "an arriving ego keeps its completed steps" test "$(q "$work/b9.sqlite" "select count(*) from steps")" -ge 50
    rm -f "$work/b10.sqlite"
    check "the same run stopped before the ego arrives (--end) is fine" \
      "$driver" --no-progress -c "$work/arrive.sumocfg" --ego ego --end 8.5 --output "$work/b10.sqlite"
    ;;
  *) echo "unknown case $case"; exit 2 ;;
esac
exit $fail
