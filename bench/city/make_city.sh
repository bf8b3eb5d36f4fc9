#!/usr/bin/env bash
# Regenerates the city benchmark's traffic on sumo_nets/city_grid with SUMO's randomTrips
# (seeded: the same routes every time): 1,500 cars over 900 s (one every 0.6 s, trips of at
# least 300 m, more from the border) and about 600 pedestrians (one every 1.5 s, walks up to
# 600 m). Usage: bench/city/make_city.sh (run after sumo_nets/make_nets.sh changed the net).
set -euo pipefail
cd "$(dirname "$0")"
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
net=../../sumo_nets/city_grid/city_grid.net.xml
python3 "$SUMO_HOME/tools/randomTrips.py" -n "$net" -o /tmp/city_cars.trips.xml -r cars.rou.xml \
  --seed 1 -b 0 -e 900 -p 0.6 --fringe-factor 3 --min-distance 300 --prefix car --validate \
  --trip-attributes 'departLane="best" departSpeed="max"' >/dev/null
python3 "$SUMO_HOME/tools/randomTrips.py" -n "$net" -o /tmp/city_peds.trips.xml -r peds.rou.xml \
  --seed 2 -b 0 -e 900 -p 1.5 --pedestrians --prefix ped --max-distance 600 >/dev/null
rm -f cars.rou.alt.xml peds.rou.alt.xml
echo "made bench/city/cars.rou.xml ($(grep -c '<vehicle' cars.rou.xml) cars), peds.rou.xml ($(grep -c '<person' peds.rou.xml) pedestrians)"
