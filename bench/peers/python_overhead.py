# `glint bench bake` (h): the Python module's own cost on a small bake (issue 36): the wall
# time of glint.bake() against the bake job's own time (its report's total seconds), which
# includes loading the meshes and baking; what is left is the module's (options in, a
# thread, arrays out).
#
#   PYTHONPATH=build/python python3 bench/peers/python_overhead.py LOW.obj HIGH.obj SIZE REPEATS
#
# Prints RESULT {"wall": [...], "job": [...]}.
import json
import sys
import time

import glint

low, high, size, repeats = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
glint.bake(low, high, size=size, max_front=0.06, max_rear=0.06)  # warm: the module's first call loads its libraries
walls, jobs = [], []
for _ in range(repeats):
    start = time.perf_counter()
    result = glint.bake(low, high, size=size, max_front=0.06, max_rear=0.06)
    walls.append(time.perf_counter() - start)
    jobs.append(result.report["seconds"]["total"])
print("RESULT " + json.dumps({"wall": walls, "job": jobs}))
