#!/usr/bin/env bash
# Drives `glint view` with real X input (xdotool, XTEST) on the display it is given
# (tests/scenes/cli_test.cpp runs it under xvfb-run) and saves F12 screenshots for the
# test to compare. Every step waits for the screenshot it asked for, never for a fixed
# time: on a loaded machine the viewer just takes longer.
#
#   viewer_input.sh GLINT OUT_DIR
#
# OUT_DIR/3d: env/cube/front (static: its spin option is 0)
#   1  the first frame            2  the defined camera (the panel is up by now)
#   3  after a drag on the panel's title bar (the panel's, not the camera's)
#   4  after a left drag over the scene (orbit)
#   5  after C (the defined camera again)
#   6  after three wheel notches towards the scene (zoom)
#   7  after a right drag (pan)
#   8  after Home (the defined camera again)
# OUT_DIR/2d: basics/triangle/color (NDC geometry, no camera)
#   1  the first frame  2  the picture  3  after left and right drags and the wheel over it
set -Eeuo pipefail
glint="$1"
out="$2"
wid=""
viewer=""
# On failure: what the viewer said, and no viewer left behind (xvfb-run then stops the server).
trap 'cat "$out"/*/viewer.log >&2 2>/dev/null || true; [[ -n "$viewer" ]] && kill "$viewer" 2>/dev/null || true' ERR

# shot DIR N: presses F12 and waits until the viewer has written DIR/glint-view-N.png
# (written atomically: once it exists it is whole).
shot() {
  xdotool key F12
  for _ in $(seq 1 600); do
    [[ -e "$1/glint-view-$2.png" ]] && return 0
    sleep 0.05
  done
  echo "viewer_input: no screenshot $1/glint-view-$2.png after 30 s" >&2
  return 1
}

# drag BUTTON X0 Y0 X1 Y1: press at (X0, Y0), move there in four steps, release; window coordinates.
drag() {
  local b=$1 x0=$2 y0=$3 x1=$4 y1=$5 i
  xdotool mousemove --window "$wid" "$x0" "$y0" sleep 0.05 mousedown "$b"
  for i in 1 2 3 4; do
    xdotool sleep 0.05 mousemove --window "$wid" $((x0 + (x1 - x0) * i / 4)) $((y0 + (y1 - y0) * i / 4))
  done
  xdotool sleep 0.05 mouseup "$b"
}

# start SCENE DIR: starts the viewer and waits for its window.
start() {
  mkdir -p "$2"
  "$glint" view "$1" --size 800x600 --shot-dir "$2" >"$2/viewer.log" 2>&1 &
  viewer=$!
  wid=$(timeout 60 xdotool search --sync --name "^glint — $1\$" | head -1)
  [[ -n "$wid" ]] || { echo "viewer_input: no window for $1" >&2; return 1; }
  xdotool mousemove --window "$wid" 600 300  # keyboard focus follows the pointer without a window manager
}

# finish: Esc, and the viewer's exit status.
finish() {
  xdotool key Escape
  local status=0
  timeout 30 tail --pid="$viewer" -f /dev/null || { kill "$viewer"; echo "viewer_input: the viewer did not quit" >&2; }
  wait "$viewer" || status=$?
  return $status
}

d="$out/3d"
start env/cube/front "$d"
shot "$d" 1
shot "$d" 2
drag 1 300 20 200 20  # the title bar, leftwards: moves the panel, never the camera
shot "$d" 3
drag 1 560 300 720 340
shot "$d" 4
xdotool key c
shot "$d" 5
xdotool mousemove --window "$wid" 640 300 click 4 click 4 click 4
shot "$d" 6
xdotool key Home
drag 3 560 300 660 360
shot "$d" 7
xdotool key Home
shot "$d" 8
finish

d="$out/2d"
start basics/triangle/color "$d"
shot "$d" 1
shot "$d" 2
drag 1 560 300 720 340
drag 3 560 300 660 360
xdotool mousemove --window "$wid" 640 300 click 4 click 4 click 5
shot "$d" 3
finish
