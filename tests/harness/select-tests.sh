#!/bin/sh
# select-tests.sh NN FILE... - print the stage test sources that apply to
# stage NN.  A file named NN_topic.c applies from stage NN on; one named
# NN-MM_topic.c applies to stages NN through MM only.
stage=$1
shift
for f in "$@"; do
    base=$(basename "$f")
    range=${base%%_*}
    from=${range%-*}
    to=${range#*-}
    [ "$from" = "$range" ] && to=99
    if [ "$stage" -ge "$from" ] 2>/dev/null && [ "$stage" -le "$to" ]; then
        echo "$f"
    fi
done
