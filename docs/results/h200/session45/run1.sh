# Session 45 run1: session 44's run2, which did not run there (the GPU
# suites, the peer's comparison with both structures, `bench` of the goals'
# sphere fields and meshes), as it is, at this session's code: no render
# code changed since session 44 (7db178e's checks). Pack: tools/gpu_pack.sh
# of this session's first commit (its COMMIT). Carried: .gl, .gpub,
# .assets, .peers/karim. Expectations in expected.md (run1).
bash docs/results/h200/session44/run2.sh
