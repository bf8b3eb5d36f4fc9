#!/usr/bin/env bash
# SUMO-level tests of sumo-criticality (ctest label sumo), one case per ctest entry:
#   scenario_cases.sh DRIVER BENCH SCENARIOS_DIR WORK_DIR CASE
# Cases: collision:NAME, free:NAME, brake, brake_hold, conversion_replay, connect, all_vehicles,
# consistent_reads, disk_full, sumo_dies, bad_input, lifecycle_arrive, lifecycle_teleport,
# collision_actions, reader, signals, small_options, counter_traffic, riding_person,
# city_one_ego, city_sublane_all, mixed_fleet:NETWORK (level_crossing, tram_street, trucks,
# bus_stop, parking, bike_lanes).
# Every check asserts on the results database (sqlite3), on exit codes and messages, or on
# SUMO's own outputs.
set -u
driver=$1 bench=$2 scenarios=$3 work=$4 case=$5
here=$(cd "$(dirname "$0")" && pwd)
data=$here/data
mkdir -p "$work"
fail=0
check() {  # check DESCRIPTION COMMAND...
  local what=$1; shift
  if "$@"; then echo "ok: $what"; else echo "FAILED: $what"; fail=1; fi
}
q() { sqlite3 "$1" "$2"; }
summary_field() {  # summary_field JSON_LINE KEY
  python3 -c "import json,sys; v=json.loads(sys.argv[1])[sys.argv[2]]; print('null' if v is None else v)" "$1" "$2"
}
cfg_value() {  # cfg_value SCENARIO KEY: a value of its scenario.cfg
  sed -n "s/^$2 *= *//p" "$scenarios/$1/scenario.cfg" | head -n 1
}
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
    quiet=$(cfg_value "$name" quiet-until); partner=$(cfg_value "$name" expect-partner)
    check "$name: scenario.cfg states its quiet phase and partner" test -n "$quiet" -a -n "$partner"
    check "$name: run completed" test "$(q "$db" "select status from runs")" = completed
    check "$name: the scenario's metadata recorded" \
      test "$(q "$db" "select expect || ' ' || expect_partner || ' ' || quiet_until_s || ' ' || category from runs")" = \
           "collision $partner $quiet $(cfg_value "$name" category)"
    check "$name: SUMO recorded the collision of the ego with $partner" \
      test "$(q "$db" "select count(*) from collisions where involves_ego = 1 and 'ego' in (collider, victim) and '$partner' in (collider, victim)")" -ge 1
    first=$(q "$db" "select min(time_s) from collisions where 'ego' in (collider, victim) and '$partner' in (collider, victim)")
    check "$name: a warning episode started after the quiet phase ($quiet s) and before the collision ($first s)" \
      test "$(q "$db" "select count(*) from warnings where ego='ego' and start_s >= $quiet and start_s < $first")" -ge 1
    check "$name: the collision's anticipation time is positive" \
      test "$(q "$db" "select count(*) from collisions where '$partner' in (collider, victim) and anticipation_s > 0")" -ge 1
    check "$name: steps recorded every 0.1 s until the end" \
      test "$(q "$db" "select count(*) from steps")" -ge 50
    check "$name: summary says the expectation is met" grep -q '"expectation_met":true' <<<"$summary"
    check "$name: summary counts the ego's collision" test "$(summary_field "$summary" ego_collisions)" -ge 1
    # The same scenario with another partner expected: the expectation is not met.
    summary=$(run "$name" "$work/$name.other.sqlite" --expect-partner nobody-else)
    check "$name: a collision with someone else does not meet an expectation naming another partner" \
      grep -q '"expectation_met":false' <<<"$summary"
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
    # Handed back: a release after the last brake; or the run ended while braking (its last
    # action a brake).
    check "brake: control is handed back (release recorded) or the run ends braking" \
      test "$(q "$brake_db" "select (select count(*) from actions where kind='release' and time_s >= (select max(time_s) from actions where kind='brake')) + (select count(*) from (select kind from actions order by time_s desc, rowid desc limit 1) where kind='brake')")" -ge 1
    ;;
  brake_hold)
    # rear_approach: the follower runs into the ego's back (11.1 s) and on through it (SUMO's
    # collision.action warn), after which SUMO's own driver would drive the stopped ego on into
    # the jam ahead. The closed loop brakes once and keeps the ego stopped: handing back is
    # judged with SUMO's own choice of speed (its type's acceleration, as SUMO reports only the
    # speed driven while ours is in force), so there is no brake/release cycling for it.
    db=$work/brake_hold.sqlite
    run rear_approach "$db" --act brake >/dev/null
    sqlite3 "$db" "select time_s, kind, round(p_collision, 3) from actions"
    check "brake_hold: the closed loop brakes for the jam after the collision" \
      test "$(q "$db" "select count(*) from actions where kind='brake' and time_s > 11.1")" -ge 1
    check "brake_hold: one engagement, no brake after a release" \
      test "$(q "$db" "select count(*) from actions a where kind='brake' and exists (select 1 from actions r where r.kind='release' and r.time_s < a.time_s)")" -eq 0
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
    # SUMO's default position update is Euler: the scenes say with which step; with
    # --step-method.ballistic they say nothing (continuous motion).
    check "the scenes carry SUMO's Euler update step (0.1 s)" grep -q '^euler-update-step 0.1' "$scenes/$last"
    rm -rf "$scenes"
    run rear_end "$db" --record-scenes "$scenes" --end 2 -- --step-method.ballistic >/dev/null
    check "scenes were recorded under --step-method.ballistic" test -n "$(ls "$scenes")"
    check "under --step-method.ballistic no scene has an Euler update step" \
      test -z "$(grep -l '^euler-update-step' "$scenes"/*)"
    # SUMO switches to its ballistic update by itself where a default action step length is
    # given, or a vehicle type's actionStepLength differs from the step length.
    rm -rf "$scenes"
    run rear_end "$db" --record-scenes "$scenes" --end 2 -- --default.action-step-length 0.5 >/dev/null
    check "under --default.action-step-length no scene has an Euler update step" \
      test -n "$(ls "$scenes")" -a -z "$(grep -l '^euler-update-step' "$scenes"/*)"
    rm -rf "$scenes"
    printf '<additional>\n  <vType id="slow_reaction" actionStepLength="1.0"/>\n</additional>\n' \
      > "$work/slow_reaction.add.xml"
    run rear_end "$db" --record-scenes "$scenes" --end 2 -- \
      --additional-files "$work/slow_reaction.add.xml" >/dev/null 2>&1
    check "with a vehicle type's actionStepLength 1.0 at 0.1 s steps no scene has an Euler update step" \
      test -n "$(ls "$scenes")" -a -z "$(grep -l '^euler-update-step' "$scenes"/*)"
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
    db=$work/full.sqlite; rm -f "$db"*
    # A file-size limit makes every write past 1 MB fail, as a full disk does.
    err=$( (ulimit -f 1024; trap '' XFSZ; exec "$driver" --config "$scenarios/rear_end/scenario.cfg" \
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
    # Killed once the run has recorded some steps (a fixed delay raced the whole 2 s run on an
    # idle machine: the run completed before SUMO was killed).
    (for _ in $(seq 1 400); do
       sleep 0.05
       n=0
       [ -f "$db" ] && n=$(sqlite3 -readonly -cmd ".timeout 1000" "$db" \
                             "select count(*) from steps" 2>/dev/null)
       [ "${n:-0}" -ge 5 ] && break
     done
     kill -9 $sumo_pid 2>/dev/null) &
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
      local err rc out
      out=$("$driver" --no-progress "$@" 2>"$work/err.txt"); rc=$?
      err=$(cat "$work/err.txt")
      check "'$*' exits $code" test "$rc" -eq "$code"
      check "'$*' error is one line" test "$(printf '%s\n' "$err" | wc -l)" -eq 1
      check "'$*' error names '$pattern'" grep -q -- "$pattern" <<<"$err"
      check "'$*' summary line says failed with exit code $code" \
        test "$(summary_field "$(tail -n 1 <<<"$out")" status)/$(summary_field "$(tail -n 1 <<<"$out")" exit_code)" = "failed/$code"
      echo "   -> $err"
    }
    cfg=$scenarios/rear_end/scenario.cfg
    rm -f "$work"/b*.sqlite*
    expect_error 2 "no such file" -c "$work/missing.sumocfg" --ego ego --output "$work/b1.sqlite"
    printf '<configuration><input><net-file value="nowhere.net.xml"/></input>\n' > "$work/broken.sumocfg"
    expect_error 3 "SUMO error" -c "$work/broken.sumocfg" --ego ego --output "$work/b2.sqlite"
    check "a run that fails before its first step leaves no output file" test ! -e "$work/b2.sqlite"
    # SUMO prints an error for an invalid option value and runs on with its default: an error.
    expect_error 3 "collision.action 'bogus'" --config "$cfg" --output "$work/b2c.sqlite" -- \
      --collision.action bogus
    check "a run SUMO reported errors for leaves no output file" test ! -e "$work/b2c.sqlite"
    expect_error 5 "never load" --config "$cfg" --ego nobody --output "$work/b3.sqlite"
    check "an ego no route file defines fails before the first step, leaving no file" test ! -e "$work/b3.sqlite"
    expect_error 5 "is a person" --config "$scenarios/pedestrian_steps_out/scenario.cfg" --ego walker --output "$work/b3p.sqlite"
    touch "$work/b3.sqlite"
    expect_error 4 "already exists" --config "$cfg" --output "$work/b3.sqlite"
    expect_error 2 "act" --config "$cfg" --act explode --output "$work/b4.sqlite"
    expect_error 2 "--profiles" --config "$cfg" --profiles 1 --output "$work/b5.sqlite"
    expect_error 2 "--horizon" --config "$cfg" --horizon 0 --output "$work/b5h.sqlite"
    expect_error 2 "unknown action" --config "$cfg" --event "1 ego fly 3" --output "$work/b6.sqlite"
    expect_error 2 "HOST:PORT" --connect nonsense --ego ego --output "$work/b7.sqlite"
    expect_error 2 "no ego" -c "$scenarios/rear_end/rear_end.sumocfg" --output "$work/b8.sqlite"
    ;;
  lifecycle_arrive)
    # The ego's route ends long before the simulation does: a normal event, never an abort.
    db=$work/arrive.sqlite; rm -f "$db"
    summary=$("$driver" --no-progress -c "$data/lifecycle/arrive.sumocfg" --ego ego --output "$db"); rc=$?
    echo "$summary"
    check "an arriving ego: exit 0" test $rc -eq 0
    check "an arriving ego: the run ends when every named ego has arrived" \
      test "$(summary_field "$summary" end_reason)" = egos-arrived
    check "an arriving ego: depart and arrive recorded" \
      test "$(q "$db" "select group_concat(event) from (select event from ego_events where ego='ego' order by time_s)")" = "depart,arrive"
    check "an arriving ego: its steps are kept" test "$(q "$db" "select count(*) from steps")" -ge 50
    check "an arriving ego: run completed" test "$(q "$db" "select status || ' ' || end_reason from runs")" = "completed egos-arrived"
    # --all-vehicles goes on until SUMO ends; the other car drives on after the ego arrived.
    db=$work/arrive_all.sqlite; rm -f "$db"
    summary=$("$driver" --no-progress -c "$data/lifecycle/arrive.sumocfg" --all-vehicles --output "$db" \
                --own-lane-samples 1 --neighbour-lane-samples 1); rc=$?
    check "--all-vehicles with an arrival: exit 0, until SUMO ends" \
      test "$rc/$(summary_field "$summary" end_reason)" = "0/sumo-end"
    check "--all-vehicles: the arrival is an event of that ego" \
      test "$(q "$db" "select count(*) from ego_events where ego='ego' and event='arrive'")" -eq 1
    check "--all-vehicles: the other car is still estimated after the ego arrived" \
      test "$(q "$db" "select count(*) from steps where ego='other' and time_s > (select time_s from ego_events where ego='ego' and event='arrive')")" -ge 10
    ;;
  lifecycle_teleport)
    # A jam: SUMO teleports the ego (time-to-teleport); the next edge is full for a while, so
    # the teleport lasts; estimation pauses meanwhile and resumes after it.
    db=$work/jam.sqlite; rm -f "$db"
    summary=$("$driver" --no-progress -c "$data/lifecycle/jam.sumocfg" --ego ego --output "$db"); rc=$?
    echo "$summary"
    check "a teleported ego: exit 0" test $rc -eq 0
    check "a teleported ego: depart, teleport-start, teleport-end, arrive recorded in order" \
      test "$(q "$db" "select group_concat(event) from (select event from ego_events where ego='ego' order by time_s, rowid)")" = "depart,teleport-start,teleport-end,arrive"
    start=$(q "$db" "select time_s from ego_events where event='teleport-start'")
    end=$(q "$db" "select time_s from ego_events where event='teleport-end'")
    check "a teleported ego: the teleport lasted several steps ($start -> $end s)" \
      python3 -c "import sys; sys.exit(0 if $end - $start >= 1.0 else 1)"
    check "a teleported ego: no estimate while teleported" \
      test "$(q "$db" "select count(*) from steps where time_s >= $start and time_s < $end")" -eq 0
    check "a teleported ego: estimated again after the teleport" \
      test "$(q "$db" "select count(*) from steps where time_s >= $end")" -ge 50
    ;;
  collision_actions)
    # The rear-end collision under each collision.action: recorded, with SUMO's own stamp, the
    # collider's lane and where it happened; the ego's fate is an event, never an abort.
    for action in warn teleport remove; do
      db=$work/col_$action.sqlite; rm -f "$db"
      summary=$(run rear_end "$db" -- --collision.action $action --collision-output "$work/col_$action.xml"); rc=$?
      check "collision.action $action: exit 0" test $rc -eq 0
      sumo_time=$(sed -n 's/.*<collision time="\([0-9.]*\)".*collider="ego".*/\1/p' "$work/col_$action.xml" | head -n 1)
      check "collision.action $action: stamped as in SUMO's collision output ($sumo_time s)" \
        test "$(q "$db" "select printf('%.2f', time_s) from collisions where collider='ego'")" = "$sumo_time"
      # With collision.mingap-factor 0 (every scenario) the bumpers touch at x = 397 m.
      check "collision.action $action: lane and place of the collider" \
        test "$(q "$db" "select lane || ' ' || printf('%.1f %.2f', x_m, y_m) || ' ' || involves_ego from collisions")" = "WE_1 397.0 -5.25 1"
      check "collision.action $action: summary counts it as the ego's" \
        test "$(summary_field "$summary" collisions)/$(summary_field "$summary" ego_collisions)" = "1/1"
      check "collision.action $action: anticipated by the warning active at the impact" \
        test "$(q "$db" "select anticipation_s > 0 from collisions")" = 1
    done
    check "collision.action teleport: the ego's teleport and arrival are events" \
      test "$(q "$work/col_teleport.sqlite" "select group_concat(event) from (select event from ego_events order by time_s, rowid)")" = "depart,teleport-start,arrive"
    check "collision.action remove: the ego vanished" \
      test "$(q "$work/col_remove.sqlite" "select group_concat(event) from (select event from ego_events order by time_s, rowid)")" = "depart,vanish"
    # A collision between two others counts in "collisions" only: the same rear-end with a
    # bystander on another lane as the ego.
    sed -e 's#</routes>#  <vehicle id="bystander" type="car" depart="0" departLane="0" departPos="10" departSpeed="20"><route edges="WE"/></vehicle>\n</routes>#' \
      "$scenarios/rear_end/rear_end.rou.xml" > "$work/bystander.rou.xml"
    sed -e "s#rear_end.rou.xml#$work/bystander.rou.xml#" -e "s#../../sumo_nets#$scenarios/../sumo_nets#" \
      "$scenarios/rear_end/rear_end.sumocfg" > "$work/bystander.sumocfg"
    db=$work/col_other.sqlite; rm -f "$db"
    summary=$("$driver" --no-progress -c "$work/bystander.sumocfg" --ego bystander --output "$db" \
                --event "0 ego speed-mode 0" --event "0 ego speed 30" --event "0 ego lane-change-mode 0")
    echo "$summary"
    check "a collision of two others: collisions 1, ego_collisions 0" \
      test "$(summary_field "$summary" collisions)/$(summary_field "$summary" ego_collisions)" = "1/0"
    check "a collision of two others: involves_ego 0" \
      test "$(q "$db" "select group_concat(collider || '>' || victim || ':' || involves_ego) from collisions")" = "ego>obstacle:0"
    ;;
  reader)
    # A reader polling the database every 0.1 s while the run goes on never breaks it. The reader
    # gives SQLite a busy timeout, as plugin/README.md tells readers to: without one, a read at the
    # moment the run closes the file (the WAL folded into it) is told "database is locked".
    db=$work/read.sqlite; rm -f "$db"*
    "$driver" --config "$scenarios/motorway_dense_free/scenario.cfg" --output "$db" --no-progress \
      > "$work/read.out" 2>&1 &
    pid=$!
    reads=0 failures=0
    while kill -0 $pid 2>/dev/null; do
      if [ -e "$db" ]; then
        if out=$(sqlite3 -cmd ".timeout 1000" "$db" "select count(*) from steps" 2>&1) &&
           [[ $out =~ ^[0-9]+$ ]]; then
          reads=$((reads + 1))
        elif [ $reads -gt 0 ]; then
          failures=$((failures + 1)); echo "   reader: $out"
        fi
      fi
      sleep 0.1
    done
    wait $pid; rc=$?
    tail -n 1 "$work/read.out"
    check "with a reader polling every 0.1 s: exit 0" test $rc -eq 0
    check "the reader read $reads times during the run" test $reads -ge 10
    check "no read failed" test $failures -eq 0
    check "the run completed" test "$(q "$db" "select status from runs")" = completed
    ;;
  signals)
    long_run() {  # long_run DB: a run of several seconds in the background; sets pid
      rm -f "$1"*
      "$driver" --config "$scenarios/motorway_dense_free/scenario.cfg" --all-vehicles \
        --output "$1" --no-progress > "$1.out" 2> "$1.err" &
      pid=$!
      for _ in $(seq 100); do  # until its first steps are in (sqlite3 would create a missing file)
        [ -e "$1" ] && [ "$(sqlite3 "$1" "select count(*) from steps" 2>/dev/null)" -gt 20 ] 2>/dev/null && break
        sleep 0.1
      done
    }
    for sig in INT TERM; do
      db=$work/sig_$sig.sqlite
      long_run "$db"; kill -$sig $pid; wait $pid; rc=$?
      want=$([ $sig = INT ] && echo 130 || echo 143)
      last=$(tail -n 1 "$db.out")
      echo "$last"
      check "SIG$sig: exit $want" test $rc -eq $want
      check "SIG$sig: summary line says interrupted" \
        test "$(summary_field "$last" status)/$(summary_field "$last" exit_code)" = "interrupted/$want"
      check "SIG$sig: the run is marked interrupted" \
        test "$(q "$db" "select status || ' ' || end_reason from runs")" = "interrupted interrupted"
      check "SIG$sig: the steps so far are kept" test "$(q "$db" "select count(*) from steps")" -ge 20
    done
    db=$work/sig_KILL.sqlite
    long_run "$db"; kill -KILL $pid; killed=$(date +%s.%N); wait $pid 2>/dev/null
    check "SIGKILL: the file is readable and whole" test "$(q "$db" "pragma integrity_check")" = ok
    check "SIGKILL: status stays running" test "$(q "$db" "select status from runs")" = running
    check "SIGKILL: its heartbeat stopped within 2 s of the kill" \
      python3 -c "import sys; hb=float('$(q "$db" "select heartbeat_unix from runs")'); sys.exit(0 if $killed - 2.0 <= hb <= $killed + 0.1 else 1)"
    check "SIGKILL: the committed steps are readable" test "$(q "$db" "select count(*) from steps")" -ge 20
    ;;
  small_options)
    rm -rf "$work"/*.sqlite* "$work/full_dir"
    out=$("$driver" --version); rc=$?
    check "--version exits 0 and names the version" test $rc -eq 0 -a -n "$(grep -o 'sumo-criticality [0-9.]*' <<<"$out")"
    for bad in -5 nan inf; do
      err=$("$driver" --config "$scenarios/rear_end/scenario.cfg" --output "$work/e.sqlite" --end $bad 2>&1 >/dev/null); rc=$?
      check "--end $bad is rejected (exit 2, names --end)" test $rc -eq 2 -a -n "$(grep -o -- '--end' <<<"$err")"
    done
    printf 'sumo-config = %s\nego = ego\n\nprofiles = lots\n' "$scenarios/rear_end/rear_end.sumocfg" > "$work/bad.cfg"
    err=$("$driver" --config "$work/bad.cfg" --output "$work/c.sqlite" 2>&1 >/dev/null); rc=$?
    echo "   -> $err"
    check "a bad value in a config file: exit 2, file and line named" \
      test $rc -eq 2 -a -n "$(grep -o "bad.cfg:4:" <<<"$err")"
    printf 'sumo-config = %s\nego = ego\ncollision.action = teleport\n' "$scenarios/rear_end/rear_end.sumocfg" > "$work/bad2.cfg"
    err=$("$driver" --config "$work/bad2.cfg" --output "$work/c.sqlite" 2>&1 >/dev/null); rc=$?
    echo "   -> $err"
    check "a SUMO option in a config file: file, line and a hint" \
      test $rc -eq 2 -a -n "$(grep -o "bad2.cfg:3: unknown option 'collision.action' (a SUMO option" <<<"$err")"
    err=$("$driver" --config "$scenarios/rear_end/scenario.cfg" --output "$work/c.sqlite" --collision.action teleport 2>&1 >/dev/null); rc=$?
    echo "   -> $err"
    check "a SUMO option before '--': exit 2 and the hint '-- --collision.action'" \
      test $rc -eq 2 -a -n "$(grep -o -- "-- --collision.action" <<<"$err")"
    err=$("$driver" --connect 127.0.0.1:9 --ego ego --output "$work/c.sqlite" -- --seed 3 2>&1 >/dev/null); rc=$?
    echo "   -> $err"
    check "options after '--' under --connect are rejected" test $rc -eq 2 -a -n "$(grep -o "already running" <<<"$err")"
    port=$(python3 -c "import socket; s=socket.socket(); s.bind(('127.0.0.1',0)); print(s.getsockname()[1])")
    t0=$(date +%s.%N)
    err=$("$driver" --connect 127.0.0.1:$port --ego ego --output "$work/c.sqlite" 2>&1 >/dev/null); rc=$?
    t1=$(date +%s.%N)
    echo "   -> $err"
    check "--connect to a closed port: exit 3 in one line" test $rc -eq 3 -a "$(printf '%s\n' "$err" | wc -l)" -eq 1
    check "--connect to a closed port fails within 6 s" python3 -c "import sys; sys.exit(0 if $t1 - $t0 < 6 else 1)"
    check "--connect failure leaves no output file" test ! -e "$work/c.sqlite"
    # A scripted event naming a vehicle SUMO does not know: an error at the event's time.
    err=$("$driver" --config "$scenarios/rear_end/scenario.cfg" --output "$work/ev.sqlite" --event "3 egoo speed 10" 2>&1 >/dev/null); rc=$?
    echo "   -> $err"
    check "an event for an unknown vehicle: exit 2 at its time" \
      test $rc -eq 2 -a -n "$(grep -o "egoo speed 10' at t = 3" <<<"$err")"
    check "the steps before that event are kept" test "$(q "$work/ev.sqlite" "select max(time_s) from steps")" = 2.9
    # --record-scenes: a non-empty folder is refused; IDs with '/' are written safely.
    mkdir -p "$work/full_dir" && touch "$work/full_dir/x"
    err=$("$driver" --config "$scenarios/rear_end/scenario.cfg" --output "$work/rs.sqlite" --record-scenes "$work/full_dir" 2>&1 >/dev/null); rc=$?
    check "--record-scenes refuses a non-empty folder" test $rc -eq 2 -a -n "$(grep -o "not empty" <<<"$err")"
    sed -e 's/"ego"/"ego\/1"/' "$scenarios/rear_end/rear_end.rou.xml" > "$work/slash.rou.xml"
    sed -e "s#rear_end.rou.xml#$work/slash.rou.xml#" -e "s#../../sumo_nets#$scenarios/../sumo_nets#" \
      "$scenarios/rear_end/rear_end.sumocfg" > "$work/slash.sumocfg"
    rm -rf "$work/slash_scenes"
    "$driver" --no-progress -c "$work/slash.sumocfg" --ego "ego/1" --output "$work/slash.sqlite" \
      --record-scenes "$work/slash_scenes" --end 1 >/dev/null; rc=$?
    check "an ego ID with '/': exit 0" test $rc -eq 0
    check "its scene files are in the folder, '/' written as %2F" \
      test "$(ls "$work/slash_scenes" | grep -c '_ego%2F1.scene$')" -eq 10
    ;;
  counter_traffic)
    # Counter-traffic lanes flagged from each vehicle's own view on sumo_nets/counter_mix: every
    # vehicle is an ego, its scene recorded; SUMO's FCD output says which lane it was on.
    db=$work/counter.sqlite scenes=$work/counter_scenes; rm -rf "$db" "$scenes"
    summary=$("$driver" --no-progress -c "$data/counter_traffic/counter.sumocfg" --all-vehicles \
                --output "$db" --record-scenes "$scenes" -- --fcd-output "$work/counter_fcd.xml"); rc=$?
    check "counter traffic: exit 0" test $rc -eq 0
    check "every vehicle's own lanes flag counter-traffic as seen from it" python3 - "$scenes" "$work/counter_fcd.xml" <<'PY'
import collections, os, re, sys
scenes, fcd = sys.argv[1], sys.argv[2]
lane_at, order = {}, collections.defaultdict(list)
t = None
for line in open(fcd):
    m = re.search(r'<timestep time="([0-9.]+)"', line)
    if m: t = float(m.group(1)); continue
    m = re.search(r'<vehicle id="([^"]+)".* lane="([^"]+)"', line)
    if m: lane_at[(round(t, 1), m.group(1))] = m.group(2); order[m.group(1)].append((t, m.group(2)))
def next_normal(v, t):  # the first normal lane after time t (for vehicles in the junction)
    for tt, lane in order[v]:
        if tt >= t and not lane.startswith(':'): return lane
# (left present, left counter, right present) expected on each normal lane.
def expect(lane):
    edge, index = lane.rsplit('_', 1)
    if edge in ('WJ', 'JW'): return (True, True, False)        # sidewalk at index 0 is no lane
    if edge in ('JE', 'EJ'): return (True, index == '1', index == '1')  # two lanes each way
    return (True, True, False)                                 # single lane each way
# Strict: every flag present is right, and no lane is given where there is none (the sidewalk
# is never a right lane). Lanes may be missing where a lane cannot be a curve y(x) in the
# vehicle's frame (a sharp turn ahead): then the estimator uses a virtual lane; that must stay
# the exception.
checked = wrong = complete = normal_scenes = 0
for f in sorted(os.listdir(scenes)):
    t = round(float(f[1:11]), 1); ego = f[12:-6]
    lanes = {}
    for line in open(os.path.join(scenes, f)):
        w = line.split()
        if w[0] in ('vehicle', 'pedestrian'): break
        if w[0] == 'lane': lanes[w[1]] = w[2] == '1'
    lane = lane_at[(t, ego)]
    normal = next_normal(ego, t) if lane.startswith(':') else lane
    if normal is None: continue
    left, counter, right = expect(normal)
    ok = lanes.get('own', False) is False and lanes.get('left', counter) == counter and \
         (right or 'right' not in lanes) and lanes.get('right', False) is False
    checked += 1
    if not lane.startswith(':'):
        normal_scenes += 1
        complete += 'own' in lanes and ('left' in lanes) == left and ('right' in lanes) == right
    if not ok:
        wrong += 1
        if wrong <= 5: print('wrong:', f, lane, normal, lanes)
print(f'{checked} ego scenes checked, {wrong} wrong; {complete} of {normal_scenes} on normal lanes have every lane')
sys.exit(0 if checked > 1000 and wrong == 0 and complete >= 0.8 * normal_scenes else 1)
PY
    check "two cars passing head-on on the two-way street: no warning" \
      test "$(q "$db" "select count(*) from warnings where ego like 'pass_%' and start_s < 15")" -eq 0
    ;;
  riding_person)
    # A person riding in a vehicle is not a pedestrian (SUMO reports them at the vehicle's
    # place): in scenes only while waiting to be picked up. FCD output says when they ride.
    db=$work/ride.sqlite scenes=$work/ride_scenes; rm -rf "$db" "$scenes"
    "$driver" --no-progress -c "$data/riding/ride.sumocfg" --ego ego --output "$db" \
      --record-scenes "$scenes" -- --fcd-output "$work/ride_fcd.xml" >/dev/null; rc=$?
    check "riding person: exit 0" test $rc -eq 0
    boarded=$(python3 -c "
import re
t = None
for line in open('$work/ride_fcd.xml'):
    m = re.search(r'<timestep time=\"([0-9.]+)\"', line)
    if m: t = float(m.group(1))
    if 'person id=\"rider\"' in line and float(re.search(r' speed=\"([0-9.]+)\"', line).group(1)) > 1.0:
        print(t); break")
    last=$(grep -l "^pedestrian rider " "$scenes"/* | tail -n 1 | sed -e 's/.*_\?t\([0-9.]*\)_ego.scene/\1/' -e 's/^0*//')
    echo "   rider moves with the taxi from $boarded s; last scene with the rider as a pedestrian: $last s"
    check "riding person: a pedestrian while waiting" test -n "$last"
    check "riding person: never a pedestrian once riding" python3 -c "import sys; sys.exit(0 if float('$last') < float('$boarded') else 1)"
    ;;
  city_one_ego|city_sublane_all)
    # The city-like network (bench/city: 1,500 randomTrips cars, 600 pedestrians, traffic
    # lights, sidewalks): one ego with the full hypothesis set until it arrives; or, with the
    # sublane model and 0.25 s steps, every vehicle an ego over the first 120 s (cheaper
    # hypothesis settings). SUMO's own collision output is the reference.
    city=$here/../../bench/city
    db=$work/$case.sqlite; rm -f "$db"
    if [ $case = city_one_ego ]; then
      summary=$("$driver" --no-progress -c "$city/city.sumocfg" --ego car22 --output "$db" \
                  -- --collision-output "$work/$case.collisions.xml"); rc=$?
      check "city, one ego: ends when it arrives" test "$(summary_field "$summary" end_reason)" = egos-arrived
      check "city, one ego: depart and arrive recorded" \
        test "$(q "$db" "select group_concat(event) from (select event from ego_events order by time_s)")" = "depart,arrive"
    else
      summary=$("$driver" --no-progress -c "$city/city.sumocfg" --all-vehicles --output "$db" \
                  --profiles 3 --own-lane-samples 1 --neighbour-lane-samples 1 \
                  -- --step-length 0.25 --lateral-resolution 0.3 --end 120 \
                  --collision-output "$work/$case.collisions.xml"); rc=$?
      check "city, sublane, 0.25 s: every step stamped on the 0.25 s grid" \
        test "$(q "$db" "select count(*) from step_times where abs(time_s * 4 - round(time_s * 4)) > 1e-6")" -eq 0
      check "city, sublane, 0.25 s: hundreds of egos" test "$(summary_field "$summary" egos)" -ge 200
      check "city, sublane: the shortcut answered some estimates" \
        test "$(summary_field "$summary" shortcut_estimates)" -ge 1
    fi
    echo "$summary"
    check "city ($case): exit 0" test $rc -eq 0
    check "city ($case): one time breakdown per step" \
      test "$(q "$db" "select count(*) from step_times")" -eq "$(summary_field "$summary" steps)"
    check "city ($case): the same collisions as SUMO's collision output, with its time stamps" python3 - "$db" "$work/$case.collisions.xml" <<'PY'
import re, sqlite3, sys
db, xml = sys.argv[1], sys.argv[2]
ours = sorted(sqlite3.connect(db).execute("select printf('%.2f', time_s), collider, victim from collisions"))
theirs, seen = [], set()
for line in open(xml):
    m = re.search(r'<collision time="([0-9.]+)".* collider="([^"]+)" victim="([^"]+)"', line)
    if m:
        key = (m.group(2), m.group(3))
        t = float(m.group(1))
        if key in seen and any(abs(t - tt) < 0.3 for tt in seen_t.get(key, [])):
            seen_t[key].append(t); continue  # the same contact, reported again
        seen.add(key); seen_t = globals().setdefault('seen_t', {}); seen_t.setdefault(key, []).append(t)
        theirs.append(('%.2f' % t, m.group(2), m.group(3)))
theirs.sort()
print(len(ours), 'collisions recorded,', len(theirs), 'in SUMO\'s output')
if ours != theirs: print('ours  ', ours[:10]); print('theirs', theirs[:10])
sys.exit(0 if ours == theirs else 1)
PY
    # Memory flat in simulated time: the resident memory of the second half of the run stays
    # within 15 MB of the first half's, plus 0.3 MB per ego estimated at once beyond the first
    # half's most (the fleet run's traffic builds up over its 120 s, from about 100 to 200 egos
    # per step, and SUMO and the estimators hold more for more vehicles: measured 99 -> 129 MB,
    # at the same size at the end whether the step up fell into the first half or not).
    check "city ($case): memory flat" python3 - "$db" <<'PY'
import sqlite3, sys
rows = sqlite3.connect(sys.argv[1]).execute(
    "select time_s, rss_mb, estimates from step_times order by time_s").fetchall()
half = len(rows) // 2
first = max(r[1] for r in rows[len(rows) // 10:half]); second = max(r[1] for r in rows[half:])
more_egos = max(0, max(r[2] for r in rows[half:]) - max(r[2] for r in rows[:half]))
allowed = first + 15.0 + 0.3 * more_egos
print(f'resident memory: first half up to {first:.1f} MB, second half up to {second:.1f} MB '
      f'(allowed {allowed:.1f}: {more_egos} more egos per step)')
sys.exit(0 if second <= allowed else 1)
PY
    ;;
  mixed_fleet:*)
    # Issue 21: every run completes on networks with every road user and state SUMO has
    # (data/mixed_fleet/NAME.sumocfg on the sumo_nets built for each): --all-vehicles, and a
    # named ego beside the special vehicles. Both: exit 0, run completed, no error on stderr.
    # Named ego: steps recorded for it at every step where a special one is within 30 m of it
    # (footprints from SUMO's FCD), the in-lane ones objects of its scene there. All vehicles:
    # no vehicle an ego while it is parked (SUMO's stop output), the road vehicles among the
    # special ones egos, rail vehicles not (the default --ego-classes).
    name=${case#mixed_fleet:}; cfg=$data/mixed_fleet/$name.sumocfg
    egos= no_egos=
    case $name in
      level_crossing) specials=train in_scene=train no_egos=train ;;  # a 150 m train
      tram_street) specials=tram_east,tram_west in_scene=$specials no_egos=$specials ;;  # 45 m, 32 m
      trucks) specials=semitrailer,truck_trailer,road_train in_scene=$specials egos=$specials ;;
      bus_stop) specials=bus in_scene=bus egos=bus ;;  # stands at its stop while passengers board
      parking) specials=parked1,parked2,parked3,parked4,parked5,van1,van2,van3 in_scene= egos=parked2,parked4,van2 ;;
      bike_lanes) specials=cyclist1,cyclist2,walker1 in_scene=cyclist1,cyclist2 egos=truck,cyclist1,cyclist2 ;;
      *) echo "unknown mixed_fleet network $name"; exit 2 ;;
    esac
    for mode in named all; do
      db=$work/$name.$mode.sqlite scenes=$work/$name.scenes; rm -f "$db"
      if [ $mode = named ]; then
        rm -rf "$scenes"
        args=(--ego ego --record-scenes "$scenes")
      else
        args=(--all-vehicles --own-lane-samples 1 --neighbour-lane-samples 1)
      fi
      summary=$("$driver" --no-progress -c "$cfg" "${args[@]}" --output "$db" -- \
                  --fcd-output "$work/$name.$mode.fcd.xml" --stop-output "$work/$name.$mode.stops.xml" \
                  --stop-output.write-unfinished true 2>"$work/$name.$mode.err"); rc=$?
      tail -n 1 <<<"$summary"
      [ -s "$work/$name.$mode.err" ] && sed -e 's/^/   stderr: /' "$work/$name.$mode.err" | head -n 5
      check "$name ($mode): exit 0" test $rc -eq 0
      check "$name ($mode): summary says completed" \
        test "$(summary_field "$(tail -n 1 <<<"$summary")" status)" = completed
      check "$name ($mode): the run is completed in the database" \
        test "$(q "$db" "select status from runs" 2>/dev/null)" = completed
      check "$name ($mode): no error on stderr" test -z "$(grep -i error "$work/$name.$mode.err")"
      # The summary counts the egos estimated: not the rail vehicles --all-vehicles leaves out.
      [ $mode = all ] && check "$name (all): the summary's egos are the egos table's rows" \
        test "$(summary_field "$(tail -n 1 <<<"$summary")" egos)" = "$(q "$db" "select count(*) from egos")"
      if [ $mode = all ] && [ -n "$no_egos" ]; then
        quoted="'${no_egos//,/\',\'}'"
        check "$name (all): no ego events of the vehicles that are no egos ($no_egos)" \
          test "$(q "$db" "select count(*) from ego_events where ego in ($quoted)")" = 0
      fi
    done
    check "$name (named ego): steps recorded while each special vehicle is within 30 m, the in-lane ones in its scene" \
      python3 "$here/mixed_fleet_check.py" named "$cfg" "$work/$name.named.fcd.xml" \
        "$work/$name.named.sqlite" "$work/$name.scenes" ego 30 "$specials" --in-scene "$in_scene"
    check "$name (--all-vehicles): no ego while parked, road vehicles egos, rail vehicles not" \
      python3 "$here/mixed_fleet_check.py" all "$work/$name.all.stops.xml" "$work/$name.all.sqlite" \
        --egos "$egos" --no-egos "$no_egos"
    ;;
  *) echo "unknown case $case"; exit 2 ;;
esac
exit $fail
