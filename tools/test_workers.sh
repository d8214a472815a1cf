#!/usr/bin/env bash
# The number of processes the test suite runs on (pytest-xdist -n): the
# machine's cores, at most 4 (each test may run threads of its own). Used by
# setup.sh test and by .ci/run step 5, so that both run the suite alike.
n=$(nproc 2>/dev/null || echo 1)
[ "$n" -gt 4 ] && n=4
echo "$n"
