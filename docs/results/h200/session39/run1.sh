# Session 39 run1, at 35a27ec's pack: session 38's next1.sh, unchanged (the
# file ran as a copy of it, these lines being the only difference).
source docs/results/h200/session38/next1.sh
