#!/usr/bin/env bash
# The known log of the viewer's and the log tools' tests, in the current folder: a small mine
# (log_tool generate: 1 x 2 pillars, 6 stations, seed 1) as world.json and stations.csv, its
# survey (720-point scans, 0.4 s apart) as survey.lcm, and known.lcm (viewer_test_log: the
# survey plus POSE, CONTOUR_MAP, PATH, DRIVE_PATH, MISSION_STATUS and HEARTBEAT).
#   viewer/testing/make_known_log.sh BIN_DIR
set -euo pipefail
bin="$1"
"$bin/log_tool" generate --kind mine --seed 1 --rows 1 --cols 2 --stations 6 --world-out world.json \
  --stations-out stations.csv >/dev/null
"$bin/log_tool" survey --world world.json --stations stations.csv --out survey.lcm --points 720 \
  --station-interval 0.4 --quiet
"$bin/viewer_test_log" survey.lcm known.lcm >/dev/null
