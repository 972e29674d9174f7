#!/usr/bin/env bash
# A state saved by the octrace before log 130 (OLD) resumed by the one after
# (NEW): accepted (the same scene hash) and, resumed from 2 to 4 spp, the
# same image bit for bit as NEW's uninterrupted render of 4 spp; fp32 and fp16.
# Usage: old_state_resume.sh OLD NEW
set -u
old=$1 new=$2
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
d=$(mktemp -d)
flags="--device cpu --spheres 300 --seed 5 --size 48x32"
for prec in fp32 fp16; do
  "$old" render $flags --spp 2 --precision $prec --state $d/st -q -o $d/part.pfm
  "$new" render $flags --spp 4 --precision $prec --resume $d/st -q -o $d/resumed.pfm
  rc=$?
  "$new" render $flags --spp 4 --precision $prec -q -o $d/full.pfm
  cmp -s $d/resumed.pfm $d/full.pfm && same=identical || same=DIFFERENT
  echo "$prec: resume rc=$rc, resumed against uninterrupted: $same"
  rm -f $d/*
done
rmdir $d
