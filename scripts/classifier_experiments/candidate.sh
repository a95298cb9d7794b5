#!/bin/bash
# candidate.sh NAME CAMPAIGN_DIR...: train a model on the campaigns' train and val splits and score it on the
# rendered scenarios under $SCEN (default ./sc: dataset2, dataset2_60, multi_target, multi_target300, default, dataset1, dataset4), writing NAME.json.
set -eu
here=$(cd "$(dirname "$0")" && pwd); B=$here/../../build/apps/ladarsim; S=${SCEN:-sc}
n=$1; shift
nice "$B" train-classifier "$@" --split train --split val --out "$n.json" --force | head -1
nice python3 "$here/score.py" "$n.json" $S/dataset2 $S/dataset2_60 $S/multi_target $S/multi_target300 $S/default $S/dataset1 $S/dataset4 | python3 "$here/summ.py"
python3 "$here/first40.py" "$n" $S/default
