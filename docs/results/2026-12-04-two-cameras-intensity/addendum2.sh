#!/usr/bin/env bash
# plan.md's addendum 2: addendum 1's script on edges rounded 0.3 mm, no chips.
exec "$(dirname "$0")/addendum.sh" round
