"""Halo screen: `station eval` with the highlight mask grown by GROW input px instead of 5 (``HIGHLIGHT_GROW_PX``, a
module constant read when each frame is judged; the shipped file's fit is unchanged).
Usage: python grow.py GROW STATION_EVAL_ARGS..."""
import sys

import model.draem.variation as variation
from station.cli import main

variation.HIGHLIGHT_GROW_PX = int(sys.argv[1])
sys.exit(main(["eval", *sys.argv[2:]]))
