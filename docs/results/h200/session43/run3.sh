# Session 43 run3: why log 137's `ident` made the balloon 16% slower: the
# balloon's pipeline statistics with HEAD and each run2 probe (the pack of
# run2), and the balloon's A/B again (head, ident; 7 rounds).
# Carried: .gl, .gpub (run2's pack), .assets. Expectation in expected.md (run3).
source tools/gpu_run.sh
for b in $B build-gpu/octrace-ident build-gpu/octrace-shear6 build-gpu/octrace-both; do
  echo "$(basename $b) balloon: $($b render $S --scene .assets/balloon/scene.gltf --accel octree --pipeline-stats --json -q -o $R/x.pfm 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps(j.get("pipeline_statistics")))' | head -c 400)" >> $T
done
rm -f $R/x.pfm
V=(--variant "head=" --variant "ident=BIN=build-gpu/octrace-ident")
AB_ROUNDS=7 ab balloon $S --scene .assets/balloon/scene.gltf --accel octree
gpu_finish
